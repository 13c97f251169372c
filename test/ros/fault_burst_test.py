#!/usr/bin/python3
"""Fault injection: bursts of 10,000 messages, out-of-order and duplicate stamps
(fault_burst.test).

Stop policy under test (src/ros/monitor_node.h): a message whose stamp is older than the last
accepted stamp of one of its joints is refused (INPUT_STAMP_BACKWARDS) and requests a stop; a
duplicate (the same stamp again) is not older, so it is accepted; excess messages of a burst may
be dropped by the node's input queues, and its reports by ~report's (the oldest first), so the
tests read the node's state after a burst from fresh messages on the same topics and from its
count of refused inputs, which no queue loses; the first cycle on accepted, complete, fresh input
without warnings after ~stop_hold_s clears the stop."""
import random
import sys
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import JointState

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import (HOME, LEFT_JOINTS, LEFT_TOWARDS_RIGHT, POLL_PERIOD_S, RIGHT_JOINTS,
                           RIGHT_TOWARDS_LEFT, MonitorClient, joint_state)

NODE = '/arm_collision_monitor'
BURST_MESSAGES = 10000
# Seed of the shuffled-stamp burst (printed by the test).
SEED = 20261121
# Random lateness of a stamp in the shuffled burst (s): far below ~input_timeout_s (10 s, longer
# than a burst takes to send), so the refusals are for going backwards, never for being old.
MAX_LATENESS_S = 0.05
WAIT_S = 30.0


def swing(i):
    """A small, clear pose for message i of a burst (joint 2 swings by up to 0.1 rad)."""
    return [0.0, 0.1 * ((i % 20) / 10.0 - 1.0), 0.0, 0.0, 0.0, 0.0, 0.0]


class BurstTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('fault_burst_test')
        # A burst must leave this process whole: the publisher queue holds all of it. rospy
        # shares one publisher per topic in a process, its connections keeping the queue size
        # of the first: the client's too.
        cls.client = MonitorClient(NODE, queue_size=BURST_MESSAGES)
        cls.left = rospy.Publisher('left_arm/joint_states', JointState,
                                   queue_size=BURST_MESSAGES)
        cls.right = rospy.Publisher('right_arm/joint_states', JointState,
                                    queue_size=BURST_MESSAGES)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input topics'
        deadline = time.time() + 20.0
        while time.time() < deadline and (cls.left.get_num_connections() == 0 or
                                           cls.right.get_num_connections() == 0):
            time.sleep(POLL_PERIOD_S)

    def wait_report(self, start, predicate, timeout_s=WAIT_S):
        return self.client.wait_report(start, predicate, timeout_s)

    @staticmethod
    def describe(reports, stamps):
        """What the reports of a burst were, for a failure message."""
        statuses = {}
        for r in reports:
            statuses[r.input_status] = statuses.get(r.input_status, 0) + 1
        newest = reports[-1].header.stamp.to_sec() if reports else float('nan')
        return ('%d reports, input statuses %s, newest report stamped %.6f, last left %.6f, '
                'last right %.6f' % (len(reports), sorted(statuses.items()), newest,
                                     stamps['left'].to_sec(), stamps['right'].to_sec()))

    def publish_burst(self, stamp_of, pose_of):
        """BURST_MESSAGES messages, alternating left and right; returns the last stamps."""
        stamps = {}
        for i in range(BURST_MESSAGES):
            is_left = i % 2 == 0
            stamp = stamp_of(i)
            msg = joint_state(LEFT_JOINTS if is_left else RIGHT_JOINTS, pose_of(i), stamp)
            (self.left if is_left else self.right).publish(msg)
            stamps['left' if is_left else 'right'] = stamp
        return stamps

    def test_01_in_order_burst_ends_on_the_newest_input(self):
        c = self.client
        self.assertIsNotNone(c.go_clear(), 'no clear report on home input')
        # go_clear()'s republished messages may still be in flight on the client's own
        # publishers: stamped before the burst and taken after some of it, they would be refused.
        settled = c.settle()
        self.assertIsNotNone(settled, 'no reports on home input after go_clear()')
        # ~stop is a topic of its own: its false first, so that the true waited for after the
        # burst is the burst's.
        self.assertTrue(c.wait_stop(False))
        start = c.report_count()
        last = BURST_MESSAGES - 2  # the last left-right pair: the arms tilt into each other
        pose_of = (lambda i: swing(i) if i < last else
                   (LEFT_TOWARDS_RIGHT if i % 2 == 0 else RIGHT_TOWARDS_LEFT))
        newest = [rospy.Time.now()]
        burst_stamps = set()

        def stamp_of(i):
            # Taken at publication (a burst lasts seconds: stamps must not go stale), strictly
            # increasing even when the clock has not moved since the previous message.
            newest[0] = max(rospy.Time.now(), newest[0] + rospy.Duration(0, 1000))
            burst_stamps.add((newest[0].secs, newest[0].nsecs))
            return newest[0]

        stamps = self.publish_burst(stamp_of, pose_of)
        # Not the reports of the burst's last two messages: the topics are taken in no fixed
        # order, so one arm's last report can be followed by hundreds of the other's, and ~report
        # (queue 100, oldest dropped) loses it when this process falls behind (helper-67: 9 of
        # 69 loaded runs). The final pose again, fresh stamps, until reported: each topic is
        # delivered in order, so both bursts have been taken by then, every report of them
        # accepted (below).
        final = c.hold_pose(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT, WAIT_S)
        self.assertIsNotNone(final, 'no report on the final pose after the burst; '
                             + self.describe(c.reports_since(start), stamps))
        self.assertEqual(final.input_status, MonitorReport.INPUT_OK)
        self.assertGreater(len(final.warnings), 0, 'the final pose must warn (arms crossed)')
        self.assertTrue(final.stop)
        burst_reports = c.reports_since(start)
        self.assertTrue(any((r.header.stamp.secs, r.header.stamp.nsecs) in burst_stamps
                            for r in burst_reports), 'no report on a message of the burst')
        # The refusal count covers the reports ~report dropped too.
        self.assertEqual(final.refused_inputs, settled.refused_inputs,
                         'an in-order burst must not be refused; '
                         + self.describe(burst_reports, stamps))
        self.assertTrue(all(r.input_status == MonitorReport.INPUT_OK for r in burst_reports),
                        'an in-order burst must not be refused; '
                        + self.describe(burst_reports, stamps))
        rospy.loginfo('in-order burst: %d reports for %d messages', len(burst_reports),
                      BURST_MESSAGES)
        self.assertTrue(c.wait_stop(True))
        self.assertIsNotNone(c.go_clear(), 'good input after the burst did not clear the stop')
        self.assertTrue(c.wait_stop(False))

    def test_02_shuffled_and_duplicate_stamps(self):
        c = self.client
        rng = random.Random(SEED)
        print('fault_burst: shuffled-stamp burst seed %d' % SEED)
        self.assertIsNotNone(c.go_clear(), 'no clear report on home input')
        start = c.report_count()
        previous = {}

        def stamp_of(i):
            # Every fourth message repeats its arm's previous stamp (a duplicate); the others
            # are late by a random amount, so successive stamps go back and forth.
            side = i % 2
            if i % 4 >= 2 and side in previous:
                return previous[side]
            previous[side] = rospy.Time.now() - rospy.Duration(rng.uniform(0.0, MAX_LATENESS_S))
            return previous[side]

        stamps = self.publish_burst(stamp_of, swing)
        backwards = self.wait_report(
            start, lambda r: r.input_status == MonitorReport.INPUT_STAMP_BACKWARDS)
        self.assertIsNotNone(backwards, 'no stamp went backwards in the shuffled burst')
        self.assertTrue(backwards.stop)
        self.assertNotEqual(backwards.stop_reason, '')
        # The burst may still be on its way (its publishers' sending threads fall behind on a
        # loaded machine), and would be refused after go_clear()'s newer stamps, into the next
        # test. Home on the same topics (each delivered in order), stamped after all of it and
        # republished until both arms' reports of one round come (hold_pose): then the whole
        # burst has been taken (or dropped by the input queues). Not one message each: ~report
        # (queue 100, oldest dropped) can lose one arm's report behind the other arm's burst
        # tail when this process falls behind (helper-67: 6 of 69 loaded runs).
        self.assertIsNotNone(c.hold_pose(HOME, HOME, WAIT_S),
                             'no reports after the burst; '
                             + self.describe(c.reports_since(start), stamps))
        reports = c.reports_since(start)
        self.assertTrue(all(r.input_status in (MonitorReport.INPUT_OK,
                                               MonitorReport.INPUT_STAMP_BACKWARDS)
                            for r in reports),
                        'unexpected input statuses %s' % sorted(set(r.input_status
                                                                    for r in reports)))
        self.assertIsNotNone(c.go_clear(), 'good input after the burst did not clear the stop')
        self.assertTrue(c.wait_stop(False))

    def test_03_duplicate_stamp_is_accepted(self):
        c = self.client
        self.assertIsNotNone(c.go_clear(), 'no clear report on home input')
        # go_clear()'s republished messages may still be in flight on the client's own
        # publishers: stamped before the duplicates and taken after them, they would be refused.
        clear = c.settle()
        self.assertIsNotNone(clear, 'no reports on home input after go_clear()')
        stamp = rospy.Time.now()
        start = c.report_count()
        for _ in range(3):
            self.left.publish(joint_state(LEFT_JOINTS, HOME, stamp))
        self.assertIsNotNone(self.wait_report(start, lambda r: r.header.stamp == stamp))
        deadline = time.time() + WAIT_S
        while time.time() < deadline and len([r for r in c.reports_since(start)
                                              if r.header.stamp == stamp]) < 3:
            time.sleep(POLL_PERIOD_S)
        same = [r for r in c.reports_since(start) if r.header.stamp == stamp]
        self.assertEqual(len(same), 3, 'one report per duplicate')
        self.assertTrue(all(r.input_status == MonitorReport.INPUT_OK for r in same))
        self.assertEqual(same[-1].refused_inputs, clear.refused_inputs)


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'fault_burst', BurstTest, sys.argv)
