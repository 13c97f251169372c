#!/usr/bin/python3
"""launch/demo.launch replaying test/bags/task2.bag (test/ros/demo_launch.test): reports arrive
on accepted bag input, task 2's warnings (a left-arm link against front_table_top) appear with a
stop request on the report and on ~stop, and robot_state_publisher, fed by the monitor's merged
~joint_states, puts the arms' links into TF. Bag time drives ROS time here (/use_sim_time):
the waits below count wall time."""
import sys
import time
import unittest

import rospy
import rostest
from tf2_msgs.msg import TFMessage

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import POLL_PERIOD_S, MonitorClient, describe_warnings, warning_pairs

NODE = '/arm_collision_monitor'
# task2.bag lasts 7.5 s of bag time and loops: a whole pass fits several times into these.
TIMEOUT_S = 40.0
# Both arms' last links: robot_state_publisher broadcasts them on /tf once it has joint states.
ARM_TIPS = ('left_link7', 'right_link7')


def table_warning(report):
    """A left-arm link warning against the front table top (task 2's collision)."""
    return any(first == 'front_table_top' and second.startswith('left_link')
               for first, second in warning_pairs(report))


class DemoLaunchTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('demo_launch_test')
        # Only listens: the bag is the monitor's input.
        cls.client = MonitorClient(NODE, topics=())
        cls.tf_children = set()
        rospy.Subscriber('/tf', TFMessage, cls.on_tf, queue_size=100)

    @classmethod
    def on_tf(cls, msg):
        cls.tf_children.update(t.child_frame_id for t in msg.transforms)

    def test_bag_replay_warns_and_stops(self):
        c = self.client
        clear = c.wait_report(0, lambda r: r.input_status == MonitorReport.INPUT_OK and
                              not r.stop, TIMEOUT_S)
        self.assertIsNotNone(clear, 'no clear report on accepted input in %.0f s (%d reports in '
                             'all)' % (TIMEOUT_S, c.report_count()))
        self.assertTrue(c.wait_stop(False, TIMEOUT_S), '~stop never went false')
        start = c.report_count()
        warned = c.wait_report(start, table_warning, TIMEOUT_S)
        seen = c.reports_since(start)
        self.assertIsNotNone(warned, 'no left-arm / front_table_top warning in %d reports; '
                             'warnings seen: %s' % (len(seen), sorted(set(
                                 describe_warnings(r) for r in seen if r.warnings))[:5]))
        self.assertTrue(warned.stop, 'a warning without a stop request: %s'
                        % describe_warnings(warned))
        self.assertTrue(c.wait_stop(True, TIMEOUT_S), '~stop never went true after false')
        deadline = time.time() + TIMEOUT_S
        while time.time() < deadline and not self.tf_children.issuperset(ARM_TIPS):
            time.sleep(POLL_PERIOD_S)
        self.assertTrue(self.tf_children.issuperset(ARM_TIPS),
                        'robot_state_publisher did not broadcast %s; /tf children seen: %s'
                        % (ARM_TIPS, sorted(self.tf_children)))


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'demo_launch', DemoLaunchTest, sys.argv)
