#!/usr/bin/python3
"""Fault injection: the monitor node is killed mid-task and respawned (fault_respawn.test).

Stop policy under test (src/ros/monitor_node.h): a monitor starts with stop requested (latched
~stop true) until every model joint has been received; then the first cycle on accepted,
complete, fresh input without warnings clears it. So after a crash and respawn the consumer
sees ~stop true from the new process before it ever sees false."""
import os
import signal
import sys
import time
import unittest
import xmlrpc.client

import rosgraph
import rosnode
import rospy
import rostest
from std_msgs.msg import Bool

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import MonitorClient

NODE = '/arm_collision_monitor'
KILLS = 2
WAIT_S = 30.0


class RespawnTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('fault_respawn_test')
        cls.client = MonitorClient(NODE, topics=())
        cls.stops = []  # (wall time, value) of every ~stop message
        rospy.Subscriber(NODE + '/stop', Bool,
                         lambda m: cls.stops.append((time.time(), m.data)), queue_size=100)

    def node_pid(self):
        """The monitor's process id (from its XML-RPC API), or None while it is down."""
        try:
            uri = rosnode.get_api_uri(rosgraph.Master('/fault_respawn_test'), NODE, skip_cache=True)
            if not uri:
                return None
            code, _, pid = xmlrpc.client.ServerProxy(uri).getPid('/fault_respawn_test')
            return pid if code == 1 else None
        except (OSError, xmlrpc.client.Error, rosnode.ROSNodeIOException):
            return None

    def wait_report(self, start, predicate, timeout_s=WAIT_S):
        return self.client.wait_report(start, predicate, timeout_s)

    def wait_new_pid(self, old_pid, timeout_s=WAIT_S):
        """The monitor's process id once a process other than old_pid runs it; None on
        timeout."""
        deadline = time.time() + timeout_s
        while time.time() < deadline and not rospy.is_shutdown():
            pid = self.node_pid()
            if pid is not None and pid != old_pid:
                return pid
            time.sleep(0.1)
        return None

    def test_killed_monitor_respawns_in_stop_and_clears(self):
        c = self.client
        for kill in range(KILLS):
            clear = self.wait_report(
                0, lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop)
            self.assertIsNotNone(clear, 'kill %d: no clear report before the kill' % kill)
            pid = self.node_pid()
            self.assertIsNotNone(pid, 'kill %d: the monitor has no pid' % kill)
            killed_at = time.time()
            os.kill(pid, signal.SIGKILL)
            # A new process reports, and ends up clear. Every report received once it runs is
            # its own: the old one was killed respawn_delay (1 s) before it started. (Told apart
            # by its cycle numbers, starting over, it could not be: it may count past the old
            # one's last cycle before the test's subscription to it is up.)
            self.assertIsNotNone(self.wait_new_pid(pid), 'kill %d: no respawned monitor' % kill)
            first_new = c.report_count()
            restarted = self.wait_report(first_new, lambda r: True)
            self.assertIsNotNone(restarted, 'kill %d: no report from a respawned monitor' % kill)
            clear = self.wait_report(
                first_new, lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop)
            self.assertIsNotNone(clear, 'kill %d: the respawned monitor never cleared' % kill)
            # ~stop from the new process: true first (start-up), then false. (A false sent by
            # the old process just before the kill may still arrive after it: not counted.)
            self.assertTrue(c.wait_stop(False, WAIT_S))
            after = [value for (t, value) in self.stops if t > killed_at]
            self.assertIn(True, after, 'kill %d: the new process never requested a stop' % kill)
            self.assertIn(False, after[after.index(True):],
                          'kill %d: the new process never cleared its stop' % kill)


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'fault_respawn', RespawnTest, sys.argv)
