#!/usr/bin/python3
"""Fault injection: the joint state publisher restarts mid-task (fault_publisher_restart.test).

Stop policy under test (src/ros/monitor_node.h): while a model joint has not been received for
longer than ~input_timeout_s the monitor requests a stop (~stop true, a report with
INPUT_STALE and a stop_reason naming the joint); the first cycle on accepted, complete, fresh
input without warnings after ~stop_hold_s clears it."""
import sys
import unittest

import rospy
import rostest

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import MonitorClient

NODE = '/arm_collision_monitor'
# Restarts to observe: each is one outage (stop) and one recovery (clear).
RESTARTS = 3
# Per transition; a lifetime is 3 s and an outage ~2-4 s, so this is ample even on a slow CI.
TRANSITION_TIMEOUT_S = 20.0


class PublisherRestartTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('fault_publisher_restart_test')
        # No input topics of its own: the respawning fault_publisher feeds the monitor.
        cls.client = MonitorClient(NODE, topics=())

    def wait_report(self, start, predicate, timeout_s=TRANSITION_TIMEOUT_S):
        return self.client.wait_report(start, predicate, timeout_s)

    def test_stop_while_publisher_down_and_clear_after_restart(self):
        c = self.client
        start = 0
        for restart in range(RESTARTS):
            clear = self.wait_report(
                start, lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop)
            self.assertIsNotNone(clear, 'restart %d: no clear report from the publisher' % restart)
            self.assertTrue(c.wait_stop(False, TRANSITION_TIMEOUT_S),
                            'restart %d: ~stop not false while input flows' % restart)
            start = c.report_count()
            stale = self.wait_report(start, lambda r: r.input_status == MonitorReport.INPUT_STALE)
            self.assertIsNotNone(stale, 'restart %d: publisher gone but no stale report' % restart)
            self.assertTrue(stale.stop)
            self.assertIn('not received', stale.stop_reason)
            self.assertTrue(c.wait_stop(True, TRANSITION_TIMEOUT_S),
                            'restart %d: ~stop not true while the input is missing' % restart)
            # The outage report carries the state before it: the cycle counter did not move.
            self.assertGreaterEqual(stale.cycle, clear.cycle)
            start = c.report_count()
        # And after the last outage, the restarted publisher clears it once more.
        self.assertIsNotNone(self.wait_report(
            start, lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop))
        self.assertTrue(c.wait_stop(False, TRANSITION_TIMEOUT_S))


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'fault_publisher_restart', PublisherRestartTest,
                   sys.argv)
