#!/usr/bin/python3
"""The monitor nodelet under in-process input at 1 kHz (test/ros/monitor_nodelet_stress.test)
with TCP input on the same topic and service calls at the same time: its reports keep flowing,
each second, and its services keep answering. A deadlock in the manager stops both."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import JointState

from arm_collision_monitor.msg import MonitorReport
from arm_collision_monitor.srv import CheckJointState

from acm_test_util import HOME, LEFT_JOINTS, RIGHT_JOINTS, joint_state

NODE = '/nodelet_monitor'
INPUT = '/bench/joint_states'
STRESS_S = 8.0
WINDOW_S = 1.0
TCP_RATE_HZ = 200.0
# The probe publishes at 1 kHz: a window of 1 s with less than a tenth of that is a stall (the
# count also includes the answers to the test's TCP input).
MIN_PROBE_REPORTS_PER_WINDOW = 100
SERVICE_TIMEOUT_S = 5.0


class MonitorNodeletStressTest(unittest.TestCase):

    def setUp(self):
        rospy.init_node('monitor_nodelet_stress_test')
        self.lock = threading.Lock()
        self.report_times = []
        self.tcp_stamps = set()
        self.answered_tcp = 0
        rospy.Subscriber(NODE + '/report', MonitorReport, self.on_report, queue_size=10000,
                         tcp_nodelay=True)
        self.input = rospy.Publisher(INPUT, JointState, queue_size=100, tcp_nodelay=True)
        rospy.wait_for_service(NODE + '/check', timeout=30.0)
        self.check = rospy.ServiceProxy(NODE + '/check', CheckJointState)

    def on_report(self, report):
        with self.lock:
            self.report_times.append(time.time())
            stamp = (report.header.stamp.secs, report.header.stamp.nsecs)
            if stamp in self.tcp_stamps:
                self.answered_tcp += 1

    def reports_between(self, start, end):
        with self.lock:
            return sum(1 for t in self.report_times if start <= t < end)

    def wait_reports_flowing(self, timeout_s=40.0):
        deadline = time.time() + timeout_s
        while time.time() < deadline and not rospy.is_shutdown():
            now = time.time()
            if self.reports_between(now - 0.2, now) >= 0.2 * MIN_PROBE_REPORTS_PER_WINDOW:
                return True
            time.sleep(0.05)
        return False

    def call_check(self):
        """One ~check call on its own thread, so that a hung manager fails the test instead of
        blocking it; True if it answered within SERVICE_TIMEOUT_S."""
        answers = []
        request = joint_state(LEFT_JOINTS + RIGHT_JOINTS, HOME + HOME)
        caller = threading.Thread(target=lambda: answers.append(self.check(request)), daemon=True)
        caller.start()
        caller.join(SERVICE_TIMEOUT_S)
        return bool(answers) and answers[0].success

    def test_reports_keep_flowing(self):
        self.assertTrue(self.wait_reports_flowing(), 'the probe never drove the monitor nodelet')
        start = time.time()
        next_call = start
        calls = 0
        period_s = 1.0 / TCP_RATE_HZ
        while time.time() - start < STRESS_S and not rospy.is_shutdown():
            msg = joint_state(LEFT_JOINTS + RIGHT_JOINTS, HOME + HOME)
            with self.lock:
                self.tcp_stamps.add((msg.header.stamp.secs, msg.header.stamp.nsecs))
            self.input.publish(msg)
            if time.time() >= next_call:
                self.assertTrue(self.call_check(), 'the ~check service did not answer')
                calls += 1
                next_call = time.time() + 0.1
            time.sleep(period_s)
        end = time.time()
        windows = int((end - start) / WINDOW_S)
        counts = [self.reports_between(start + i * WINDOW_S, start + (i + 1) * WINDOW_S)
                  for i in range(windows)]
        rospy.loginfo('stress: %d TCP messages, %d answered, %d ~check calls; reports per '
                      'second: %s', len(self.tcp_stamps), self.answered_tcp, calls, counts)
        for i, count in enumerate(counts):
            self.assertGreaterEqual(count, MIN_PROBE_REPORTS_PER_WINDOW,
                                    'reports stalled in second %d: %s' % (i, counts))
        # The TCP input went through the ST queue (poll thread) beside the in-process input.
        self.assertGreater(self.answered_tcp, 0, 'no report answered the TCP input')
        self.assertTrue(self.call_check(), 'the ~check service did not answer after the run')


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'monitor_nodelet_stress', MonitorNodeletStressTest,
                   sys.argv)
