#!/usr/bin/python3
"""joint_defaults in the node (test/ros/joint_defaults.test): with the right arm's joints given
defaults (turned towards the left arm) and never published, the left arm's input alone runs
cycles, which see the right arm at its defaults; once the right arm is published its messages
win, and its silence then goes stale like any input joint's."""
import sys
import unittest

import rospy
import rostest

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import (HOME, LEFT_JOINTS, LEFT_TOWARDS_RIGHT, RIGHT_JOINTS, MonitorClient,
                           joint_state)

NODE = '/arm_collision_monitor'


class JointDefaultsTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('joint_defaults_test')
        cls.client = MonitorClient(NODE)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input topics'

    def last_reports(self):
        """(input status, stop reason) of the last three reports, for a failure message."""
        return [(r.input_status, r.stop_reason) for r in self.client.reports_since(0)[-3:]]

    def publish_left_until(self, left, predicate):
        c = self.client
        return c.publish_until(lambda: c.publishers[0].publish(joint_state(LEFT_JOINTS, left)),
                               predicate)

    def test_defaults_until_published(self):
        c = self.client
        # The left arm alone completes the model: the right arm is at its defaults.
        clear = self.publish_left_until(
            HOME, lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop)
        self.assertIsNotNone(clear, 'the left arm alone did not give a clear report: %s' %
                             self.last_reports())
        self.assertTrue(c.wait_stop(False))
        # Turned towards the right arm, which its defaults turn towards the left: they meet.
        crossed = self.publish_left_until(LEFT_TOWARDS_RIGHT, lambda r: len(r.warnings) > 0)
        self.assertIsNotNone(crossed, 'no warning against the right arm at its defaults')
        self.assertEqual(crossed.input_status, MonitorReport.INPUT_OK)
        self.assertTrue(crossed.stop)
        # The right arm published at home: its message wins over the defaults.
        moved = c.publish_until(
            lambda: (c.publishers[1].publish(joint_state(RIGHT_JOINTS, HOME)),
                     c.publishers[0].publish(joint_state(LEFT_JOINTS, LEFT_TOWARDS_RIGHT))),
            lambda r: r.input_status == MonitorReport.INPUT_OK and len(r.warnings) == 0)
        self.assertIsNotNone(moved, 'the published right arm did not replace its defaults')
        # From then on the right arm is an input: its silence goes stale.
        stale = self.publish_left_until(
            HOME, lambda r: r.input_status == MonitorReport.INPUT_STALE)
        self.assertIsNotNone(stale, 'the silent right arm never went stale')
        self.assertTrue(stale.stop)
        self.assertIn('right_joint', stale.stop_reason)


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'joint_defaults', JointDefaultsTest, sys.argv)
