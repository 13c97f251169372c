"""Shared helpers of the package's rostests: publish joint states, wait on reports.

Every wait has a timeout and polls topics (never a fixed sleep standing in for a condition).
"""
import shutil
import subprocess
import tempfile
import threading
import time

import rospy
from catkin.find_in_workspaces import find_in_workspaces
from sensor_msgs.msg import JointState
from std_msgs.msg import Bool

from arm_collision_monitor.msg import MonitorReport

PKG = 'arm_collision_monitor'

LEFT_JOINTS = ['left_joint%d' % i for i in range(1, 8)]
RIGHT_JOINTS = ['right_joint%d' % i for i in range(1, 8)]

# Home: every link points straight up; the arms (1.1 m apart) are far from everything.
HOME = [0.0] * 7
# The arms tilt towards each other (roll -/+90 deg, then pitch 0.5 rad): their upper links
# cross the gap between them, so left-right warnings are certain.
LEFT_TOWARDS_RIGHT = [-1.5708, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0]
RIGHT_TOWARDS_LEFT = [1.5708, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0]
# Left arm yawed towards the front box (-0.525 rad), shoulder, elbow and wrist pitches putting
# the gripper (left_link7) on the box top, pointing down: they touch.
LEFT_AT_FRONT_BOX = [-0.525, 0.849, 0.0, 1.074, 0.0, 1.219, 0.0]
# Its mirror image: the right gripper on the same spot (touching the box and the left gripper).
RIGHT_AT_FRONT_BOX = [0.525, 0.849, 0.0, 1.074, 0.0, 1.219, 0.0]

POLL_PERIOD_S = 0.02
REPUBLISH_PERIOD_S = 0.05


def warning_pairs(report):
    """The report's warnings as a set of (owner, owner) pairs, each sorted by name."""
    return set(tuple(sorted((w.owner_a, w.owner_b))) for w in report.warnings)


def sample_warning_pairs(report):
    """warning_pairs of the warnings at the report's sample, without those the swept check found
    between the previous sample and this one (they depend on where the arms came from)."""
    return set(tuple(sorted((w.owner_a, w.owner_b))) for w in report.warnings
               if not w.between_samples)


def describe_warnings(report):
    """For failure messages: each warning's owners, primitives and distance."""
    return ', '.join('%s (%s) - %s (%s) at %.3f m' % (w.owner_a, w.primitive_a_name, w.owner_b,
                                                        w.primitive_b_name, w.distance_m)
                     for w in report.warnings) or 'none'


def joint_state(names, positions, stamp=None):
    msg = JointState()
    msg.header.stamp = rospy.Time.now() if stamp is None else stamp
    msg.name = list(names)
    msg.position = list(positions)
    return msg


class MonitorClient(object):
    """Talks to one monitor node: its input topics, ~report and ~stop."""

    def __init__(self, node='/arm_collision_monitor',
                 topics=('left_arm/joint_states', 'right_arm/joint_states'), queue_size=100):
        self.node = node
        self._lock = threading.Lock()
        self._reports = []
        self._stops = []
        self.publishers = [rospy.Publisher(t, JointState, queue_size=queue_size) for t in topics]
        rospy.Subscriber(node + '/report', MonitorReport, self._on_report, queue_size=1000)
        rospy.Subscriber(node + '/stop', Bool, self._on_stop, queue_size=100)

    def _on_report(self, msg):
        with self._lock:
            self._reports.append(msg)

    def _on_stop(self, msg):
        with self._lock:
            self._stops.append(msg.data)

    def report_count(self):
        with self._lock:
            return len(self._reports)

    def reports_since(self, index):
        with self._lock:
            return list(self._reports[index:])

    def wait_report(self, start, predicate, timeout_s=10.0):
        """The first report from index `start` on that satisfies `predicate`; None on timeout."""
        deadline = time.time() + timeout_s
        while time.time() < deadline and not rospy.is_shutdown():
            for report in self.reports_since(start):
                if predicate(report):
                    return report
            time.sleep(POLL_PERIOD_S)
        return None

    def last_stop(self):
        with self._lock:
            return self._stops[-1] if self._stops else None

    def wait_connected(self, timeout_s=20.0):
        """Waits until the monitor subscribes to every input topic."""
        deadline = time.time() + timeout_s
        while time.time() < deadline and not rospy.is_shutdown():
            if all(p.get_num_connections() > 0 for p in self.publishers):
                return True
            time.sleep(POLL_PERIOD_S)
        return False

    def publish_until(self, publish, predicate, timeout_s=10.0, republish=True):
        """Calls publish() (again every REPUBLISH_PERIOD_S if `republish`) until a report
        received after the first call satisfies predicate(report); returns that report, or None
        on timeout."""
        start = self.report_count()
        deadline = time.time() + timeout_s
        publish()
        next_publish = time.time() + REPUBLISH_PERIOD_S
        while time.time() < deadline and not rospy.is_shutdown():
            for report in self.reports_since(start):
                if predicate(report):
                    return report
            if republish and time.time() >= next_publish:
                publish()
                next_publish = time.time() + REPUBLISH_PERIOD_S
            time.sleep(POLL_PERIOD_S)
        return None

    def wait_stop(self, value, timeout_s=10.0):
        deadline = time.time() + timeout_s
        while time.time() < deadline and not rospy.is_shutdown():
            if self.last_stop() == value:
                return True
            time.sleep(POLL_PERIOD_S)
        return False

    def publish_pose(self, left, right):
        """One message per arm (two topics) or one combined message (one topic), each with a
        distinct stamp; returns the stamps sent."""
        if len(self.publishers) == 2:
            left_msg = joint_state(LEFT_JOINTS, left)
            right_msg = joint_state(RIGHT_JOINTS, right,
                                    stamp=left_msg.header.stamp + rospy.Duration(0, 1000))
            self.publishers[0].publish(left_msg)
            self.publishers[1].publish(right_msg)
            return [left_msg.header.stamp, right_msg.header.stamp]
        msg = joint_state(LEFT_JOINTS + RIGHT_JOINTS, list(left) + list(right))
        self.publishers[0].publish(msg)
        return [msg.header.stamp]

    def hold_pose(self, left, right, timeout_s=10.0):
        """Publishes the pose (again every REPUBLISH_PERIOD_S) until accepted reports on every
        message of one publish have arrived; returns the last of them, on which both arms are in
        the pose, or None on timeout. With one topic per arm the node may take the two messages
        in either order: the report on the message published second can come first, the other
        arm still in its previous pose."""
        partner = {}
        seen = set()

        def publish():
            stamps = [(s.secs, s.nsecs) for s in self.publish_pose(left, right)]
            partner[stamps[0]] = stamps[-1]
            partner[stamps[-1]] = stamps[0]

        def both_arms_in(report):
            stamp = (report.header.stamp.secs, report.header.stamp.nsecs)
            if report.input_status != MonitorReport.INPUT_OK or stamp not in partner:
                return False
            seen.add(stamp)
            return partner[stamp] in seen

        return self.publish_until(publish, both_arms_in, timeout_s)

    def wait_stamps(self, start, stamps, timeout_s=10.0):
        """Waits for reports (received after index `start`) stamped with each of `stamps`;
        returns them in arrival order, or None on timeout."""
        wanted = set((s.secs, s.nsecs) for s in stamps)
        deadline = time.time() + timeout_s
        while time.time() < deadline and not rospy.is_shutdown():
            found = [r for r in self.reports_since(start)
                     if (r.header.stamp.secs, r.header.stamp.nsecs) in wanted]
            if set((r.header.stamp.secs, r.header.stamp.nsecs) for r in found) == wanted:
                return found
            time.sleep(POLL_PERIOD_S)
        return None

    def go_clear(self, timeout_s=10.0):
        """Drives both arms home until a report is accepted with no stop; returns it."""
        return self.publish_until(
            lambda: self.publish_pose(HOME, HOME),
            lambda r: r.input_status == MonitorReport.INPUT_OK and not r.stop, timeout_s)

    def settle(self, timeout_s=10.0):
        """Publishes home once (never again) and waits for the reports on its messages; returns
        the last of them, or None on timeout. Each topic is delivered in order and the node runs
        one callback at a time, so every message published before on these topics (go_clear()'s
        republished ones still in flight too) has then been processed and reported."""
        reports = self.wait_stamps(self.report_count(), self.publish_pose(HOME, HOME), timeout_s)
        return reports[-1] if reports else None


def temp_dir(test, prefix):
    """A scratch directory of its own for `test` (a unittest.TestCase), removed when it ends."""
    directory = tempfile.mkdtemp(prefix=prefix)
    test.addCleanup(shutil.rmtree, directory, True)
    return directory


def rosrun(executable, *args, timeout_s=600):
    """Runs one of the package's executables, found the way rosrun finds it (the workspace's
    libexec directory) without rosrun's search of the whole package tree; returns the
    subprocess.CompletedProcess with stdout and stderr as text."""
    path = find_in_workspaces(search_dirs=['libexec'], project=PKG, path=executable,
                              first_match_only=True)
    assert path, 'no executable %s in the workspace' % executable
    return subprocess.run([path[0]] + list(args), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True, timeout=timeout_s)
