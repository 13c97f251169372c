#!/usr/bin/python3
"""~input_joint_prefixes in the node (test/ros/joint_prefixes.test): both arms' messages name the
same joints, 'joint1' to 'joint7', each on its arm's topic; with the prefixes 'left_' and
'right_' they are the model's two arms: the model completes, the arms at home are clear, and
turned towards each other they warn."""
import sys
import unittest

import rospy
import rostest

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import (HOME, LEFT_JOINTS, LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT,
                           MonitorClient, joint_state)

NODE = '/arm_collision_monitor'
NAMES = [joint.replace('left_', '') for joint in LEFT_JOINTS]


class JointPrefixesTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('joint_prefixes_test')
        cls.client = MonitorClient(NODE)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input topics'

    def publish_both_until(self, left, right, predicate):
        c = self.client
        return c.publish_until(lambda: (c.publishers[0].publish(joint_state(NAMES, left)),
                                        c.publishers[1].publish(joint_state(NAMES, right))),
                               predicate)

    def test_unprefixed_arms_are_told_apart_by_topic(self):
        clear = self.publish_both_until(
            HOME, HOME, lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop)
        self.assertIsNotNone(clear, 'both arms at home never gave a clear report')
        self.assertEqual(clear.unknown_joints, 0)
        crossed = self.publish_both_until(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT,
                                          lambda r: len(r.warnings) > 0)
        self.assertIsNotNone(crossed, 'the arms turned towards each other never warned')
        owners = {(w.owner_a, w.owner_b) for w in crossed.warnings}
        self.assertTrue(any(a.startswith('left') and b.startswith('right') or
                            a.startswith('right') and b.startswith('left') for a, b in owners),
                        owners)


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'joint_prefixes', JointPrefixesTest, sys.argv)
