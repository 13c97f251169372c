#!/usr/bin/python3
"""Fault injection: clock jumps under simulated time (fault_sim_clock.test).

This node owns /clock: simulated time advances 10 ms per 10 ms of wall time and jumps when a
test says so. Stop policy under test (src/ros/monitor_node.h): stop while a model joint has not
been received for longer than ~input_timeout_s of ROS time (INPUT_STALE), or while the last
input was refused; the first cycle on accepted, complete, fresh input without warnings after
~stop_hold_s clears it. After the clock goes back the node forgets the input stamps (a looping
bag): new input is good input."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import (HOME, LEFT_JOINTS, LEFT_TOWARDS_RIGHT, RIGHT_JOINTS,
                           RIGHT_TOWARDS_LEFT, MonitorClient, joint_state)

NODE = '/arm_collision_monitor'
CLOCK_STEP_S = 0.01
START_S = 1000.0
JUMP_S = 100.0
WAIT_S = 20.0


class SimClockTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('fault_sim_clock_test')
        cls.lock = threading.Lock()
        cls.sim_s = START_S
        cls.clock_pub = rospy.Publisher('/clock', Clock, queue_size=10)
        cls.clock_thread = threading.Thread(target=cls.run_clock, daemon=True)
        cls.clock_thread.start()
        cls.client = MonitorClient(NODE)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input topics'

    @classmethod
    def run_clock(cls):
        while not rospy.is_shutdown():
            with cls.lock:
                cls.sim_s += CLOCK_STEP_S
                now = rospy.Time.from_sec(cls.sim_s)
            cls.clock_pub.publish(Clock(clock=now))
            time.sleep(CLOCK_STEP_S)

    @classmethod
    def sim_now(cls):
        with cls.lock:
            return rospy.Time.from_sec(cls.sim_s)

    @classmethod
    def jump(cls, delta_s):
        with cls.lock:
            cls.sim_s += delta_s

    def publish(self, left, right=None):
        """Left (and right unless None) arm, stamped with the simulated time."""
        stamp = self.sim_now()
        self.client.publishers[0].publish(joint_state(LEFT_JOINTS, left, stamp))
        if right is not None:
            self.client.publishers[1].publish(joint_state(RIGHT_JOINTS, right, stamp))

    def go_clear(self):
        return self.client.publish_until(
            lambda: self.publish(HOME, HOME),
            lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop, WAIT_S)

    def test_01_clear_under_sim_time(self):
        report = self.go_clear()
        self.assertIsNotNone(report, 'no clear report under simulated time')
        self.assertGreaterEqual(report.header.stamp.to_sec(), START_S)
        self.assertTrue(self.client.wait_stop(False, WAIT_S))

    def test_02_jump_forward_goes_stale_then_clears(self):
        c = self.client
        self.assertIsNotNone(self.go_clear())
        self.assertTrue(c.wait_stop(False, WAIT_S), '~stop did not clear before the jump')
        start = c.report_count()
        # The clock leaps ahead and the input does not follow (yet): it is stale. The stop and
        # the report come on two topics, the stop first: wait for each.
        self.jump(JUMP_S)
        stale = c.wait_report(start, lambda r: r.input_status == MonitorReport.INPUT_STALE,
                              WAIT_S)
        self.assertIsNotNone(stale, 'no stale report after the jump')
        self.assertTrue(stale.stop)
        self.assertTrue(c.wait_stop(True, WAIT_S), 'no stop after the clock jumped ahead')
        # Input stamped with the new time resumes: the stop clears.
        report = self.go_clear()
        self.assertIsNotNone(report, 'fresh input after a forward jump did not clear the stop')
        self.assertGreaterEqual(report.header.stamp.to_sec(), START_S + JUMP_S)
        self.assertTrue(c.wait_stop(False, WAIT_S))

    def test_03_jump_back_during_a_stop_then_clears(self):
        c = self.client
        self.assertIsNotNone(self.go_clear())
        # A stop on warnings (the arms cross), then the clock goes back.
        warned = c.publish_until(lambda: self.publish(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT),
                                 lambda r: r.stop and len(r.warnings) > 0, WAIT_S)
        self.assertIsNotNone(warned, 'crossed arms did not warn')
        # Seen on ~stop too (its own topic): the false waited for below is then the clear's.
        self.assertTrue(c.wait_stop(True, WAIT_S), 'no stop on the warnings')
        self.jump(-JUMP_S)
        # Good input with the new (earlier) stamps must clear the stop: the hold must not last
        # until the clock is back where it was.
        report = self.go_clear()
        self.assertIsNotNone(report, 'good input after the clock went back did not clear the '
                             'stop (held until the old time?)')
        self.assertTrue(c.wait_stop(False, WAIT_S))

    def test_04_jump_back_then_one_arm_silent_goes_stale(self):
        c = self.client
        self.assertIsNotNone(self.go_clear())
        self.jump(-JUMP_S)
        # Only the left arm publishes after the jump: the right arm's input is missing and must
        # go stale after the timeout, even though it was last received "in the future".
        # Until the monitor has seen the new /clock, a message stamped with the new time is
        # refused as stale ("input refused: stale", also INPUT_STALE): wait for the staleness of
        # the silent arm itself.
        start = c.report_count()
        stale = c.publish_until(
            lambda: self.publish(HOME),
            lambda r: (r.input_status == MonitorReport.INPUT_STALE and
                       not r.stop_reason.startswith('input refused')), WAIT_S)
        self.assertIsNotNone(stale, 'the silent arm never went stale after the clock went back')
        self.assertTrue(stale.stop)
        self.assertIn('right_joint', stale.stop_reason)
        self.assertTrue(all(r.stop for r in c.reports_since(start)
                            if r.input_status == MonitorReport.INPUT_STALE))
        # Seen on ~stop too (its own topic): the false waited for below is then the clear's.
        self.assertTrue(c.wait_stop(True, WAIT_S), 'no stop with the right arm stale')
        self.assertIsNotNone(self.go_clear(), 'both arms again: the stop did not clear')
        self.assertTrue(c.wait_stop(False, WAIT_S))


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'fault_sim_clock', SimClockTest, sys.argv)
