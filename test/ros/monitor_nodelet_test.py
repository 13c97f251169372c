#!/usr/bin/python3
"""The monitor nodelet (test/ros/monitor_nodelet.test): loaded into a nodelet manager, it answers
joint states on its input topics with reports on ~report, with left-right warnings when the arms
tilt into each other and none at home."""
import sys
import time
import unittest

import rosnode
import rospy
import rostest

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import (HOME, LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT, MonitorClient,
                           describe_warnings)

NODE = '/arm_collision_monitor'
MANAGER = '/test_manager'


def left_right_warnings(report):
    return [w for w in report.warnings
            if {w.owner_a.split('_')[0], w.owner_b.split('_')[0]} == {'left', 'right'}]


class MonitorNodeletTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('monitor_nodelet_test')
        cls.client = MonitorClient(NODE)
        assert cls.client.wait_connected(), 'the monitor nodelet never subscribed to its input'

    def test_01_runs_in_the_manager(self):
        # The monitor's topics are served by the manager's process, not by a node of its own.
        self.assertTrue(rosnode.get_api_uri(rospy.get_master(), MANAGER),
                        'no nodelet manager %s' % MANAGER)
        publishers = rospy.get_master().getSystemState()[2][0]
        report_publishers = [nodes for topic, nodes in publishers if topic == NODE + '/report']
        self.assertEqual(report_publishers, [[MANAGER]])

    def test_02_clear_configuration_no_warnings(self):
        c = self.client
        self.assertIsNotNone(c.go_clear(), 'no clear report at home')
        start = c.report_count()
        stamps = []
        for _ in range(10):
            stamps += c.publish_pose(HOME, HOME)
            time.sleep(0.01)
        reports = c.wait_stamps(start, stamps)
        self.assertIsNotNone(reports, 'a message got no report')
        for r in reports:
            self.assertEqual(r.input_status, MonitorReport.INPUT_OK)
            self.assertEqual(len(r.warnings), 0, describe_warnings(r))
            self.assertFalse(r.stop, r.stop_reason)

    def test_03_colliding_configuration_warns(self):
        c = self.client
        self.assertIsNotNone(c.go_clear(), 'no clear report at home')
        report = c.publish_until(lambda: c.publish_pose(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT),
                                 lambda r: len(left_right_warnings(r)) > 0)
        self.assertIsNotNone(report, 'no left-right warning with the arms tilted into each other')
        self.assertEqual(report.input_status, MonitorReport.INPUT_OK)
        self.assertTrue(report.stop)
        # At the sample a warning is within its threshold (the swept check's between samples
        # ones may exceed it by up to its resolution).
        for w in left_right_warnings(report):
            if not w.between_samples:
                self.assertLessEqual(w.distance_m, w.threshold_m)
        # And home again: the warnings go away.
        self.assertIsNotNone(c.go_clear(), 'the stop never cleared back at home')


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'monitor_nodelet', MonitorNodeletTest, sys.argv)
