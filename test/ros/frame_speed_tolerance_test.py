#!/usr/bin/python3
"""Speed-scaled tolerance of frame-bound objects (test/ros/frame_speed_tolerance.test).

Both nodes run with speed-scaled tolerance (test/ros/frame_speed_tolerance.yaml: gain
reaction_time_s + stopping_time_s = 0.12 s, max_speed_mps 0.61, cycle_period_s 0.05 s). This
node sends their objects' frames itself (tf2_msgs/TFMessage on /tf or /tf_static, as
frame_bound_object_test.py does) beside the left arm's column (home: straight up; its links'
tolerance 0.0305 m, the objects' 0), so that the object's warnings against the left arm come in
every cycle, each with threshold_m = tol(object) + tol(link). Both arms come at 20 Hz: the left
arm holds home (at rest: its base tolerance), the right one sways about its vertical first axis,
on which its capsules lie (far from everything), so that the cycle of each of its messages runs
(an idle cycle, unchanged joints and scene, repeats the last report) with its R primitives
moved, the object not among them.

A tracker's frame (stamped): config/scene.yaml's box `camera` on camera_link, sent with every
other message of the arms, stamped now (a 10 Hz tracker). Each new stamp poses the camera, its
speed being its move over the time since the stamp before, kept in the cycles until the next
stamp; the same pose at a later stamp brings it to rest; its first pose (no stamp before) takes
max_speed_mps. The camera moving up the column at 0.2 m/s, every report must carry
0.0305 + 0.2 * 0.12 m, in the cycles between its TF samples as in those of a sample. The node
used to pose it only when moved, its speed being its move in the cycle over cycle_period_s:
0.02 m / 0.05 s = 0.4 m/s in the cycle of a sample, at rest (0.0305 m) in the others; both fail
here. Stopped, still sent with new stamps, the camera comes back to 0.0305 m and stays there.

A static chain's frame (stamped 0): test/data/two_frames_scene.yaml's probe on probe_link, sent
on /tf_static, keeps the rule from before: its move in the cycle over cycle_period_s, at rest in
the next cycle that runs without moving it."""
import collections
import sys
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import TransformStamped
from tf2_msgs.msg import TFMessage

from arm_collision_monitor.msg import MonitorReport

from acm_test_util import HOME, POLL_PERIOD_S, REPUBLISH_PERIOD_S, MonitorClient

NODE = '/arm_collision_monitor'
CAMERA = 'camera'
CAMERA_FRAME = 'camera_link'
STATIC_NODE = '/static_frame_monitor'
PROBE = 'probe'
PROBE_FRAME = 'probe_link'
# test/ros/frame_speed_tolerance.yaml; the scenes' tolerances.
GAIN_S = 0.1 + 0.02
MAX_SPEED_MPS = 0.61
CYCLE_PERIOD_S = 0.05
ARM_TOLERANCE_M = 0.0305
OBJECT_TOLERANCE_M = 0.0
REST_THRESHOLD_M = OBJECT_TOLERANCE_M + ARM_TOLERANCE_M
FIRST_THRESHOLD_M = REST_THRESHOLD_M + MAX_SPEED_MPS * GAIN_S
# The camera's speed up the left arm's column.
SPEED_MPS = 0.2
MOVING_THRESHOLD_M = REST_THRESHOLD_M + SPEED_MPS * GAIN_S
# The camera (half extents 0.06, 0.1, 0.05 m; unrotated) beside the left arm's column (x 0,
# y 0.55; left_link4 and left_link5, radius 0.07 m, from z 1.7 to 2.3 m, then left_link6 and
# left_link7, radius 0.06 m, up to 2.705 m): its -x face 0.015 m off their surface, within the
# tolerances' sum of some left-arm link from z 1.8 m up to 2.6 m.
CAMERA_X_M = 0.145
CAMERA_Y_M = 0.55
CAMERA_START_Z_M = 1.8
CAMERA_TOP_Z_M = 2.6
# The probe (a 0.05 m cube) 0.01 m off left_link4, then moved up by PROBE_STEP_M.
PROBE_XYZ_M = (0.105, 0.55, 1.85)
PROBE_STEP_M = 0.005
PROBE_MOVED_THRESHOLD_M = REST_THRESHOLD_M + PROBE_STEP_M / CYCLE_PERIOD_S * GAIN_S
# The right arm's sway: its first joint (a yaw about its column) by 0.01 rad, every other
# message.
RIGHT_SWAY = [0.01] + [0.0] * 6
# Rounding only: the thresholds are sums of a few terms under 0.2 m.
ROUNDING_M = 1e-9
# Cycles of each kind (R moved primitives: the object unmoved; 1 or R + 1: moved by a sample) a
# phase must show before it ends, and the samples a rest must span.
MIN_BETWEEN_CYCLES = 10
MIN_SAMPLE_CYCLES = 5
MIN_REST_SAMPLES = 3
TIMEOUT_S = 10.0


def to_sec(stamp):
    """ros::Time::toSec's arithmetic (the node's), bit for bit."""
    return float(stamp.secs) + 1e-9 * float(stamp.nsecs)


def transform(frame, xyz_m, stamp):
    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id = 'world'
    t.child_frame_id = frame
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz_m
    t.transform.rotation.w = 1.0
    return t


def object_warnings(report, name):
    return [w for w in report.warnings if name in (w.owner_a, w.owner_b)]


def other_owner(warning, name):
    return warning.owner_b if warning.owner_a == name else warning.owner_a


def has_threshold(report, name, threshold_m):
    """Whether the report has warnings of object `name` and each has threshold_m, to rounding."""
    warnings = object_warnings(report, name)
    return bool(warnings) and all(abs(w.threshold_m - threshold_m) <= ROUNDING_M
                                  for w in warnings)


def first_with(reports, name, threshold_m, begin=0):
    """The index of the first report from `begin` on whose warnings of object `name` all have
    threshold_m, else None."""
    return next((i for i in range(begin, len(reports))
                 if has_threshold(reports[i], name, threshold_m)), None)


def describe(reports, name):
    """For failure messages: per report, its cycle, moved primitives and warnings of `name`."""
    return '; '.join('cycle %d (%d moved): %s' % (
        r.cycle, r.moved_primitives,
        ', '.join('%s at %.4f m, threshold %.12f m' % (other_owner(w, name), w.distance_m,
                                                        w.threshold_m)
                  for w in object_warnings(r, name)) or 'no %s warning' % name)
                     for r in reports) or 'no report'


def tally(reports, name, right):
    """For failure messages: the thresholds of object `name`'s warnings, each with its count of
    reports of cycles of a sample (1 or `right` + 1 moved), between samples (`right` moved) and
    idle (0 moved)."""
    kinds = {0: 'idle', 1: 'sample', right: 'between', right + 1: 'sample'}
    counts = collections.Counter(
        ('%.4f m' % w.threshold_m, kinds.get(r.moved_primitives, 'other'))
        for r in reports for w in object_warnings(r, name)[:1])
    return ', '.join('%s in %d %s' % (key[0], n, key[1]) for key, n in sorted(counts.items()))


class FrameSpeedToleranceTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('frame_speed_tolerance_test')
        cls.client = MonitorClient(NODE)
        cls.static_client = MonitorClient(STATIC_NODE)
        cls.tf_pub = rospy.Publisher('/tf', TFMessage, queue_size=100)
        cls.tf_static_pub = rospy.Publisher('/tf_static', TFMessage, queue_size=10, latch=True)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input topics'
        assert cls.static_client.wait_connected(), '%s never subscribed' % STATIC_NODE

    def setUp(self):
        self.messages = 0
        self.is_tracking = False  # camera_link sent with the arms' messages
        self.rest_z_m = CAMERA_START_Z_M
        self.moving_since_s = None  # the stamp from which the camera moves up from rest_z_m
        self.samples = []  # (stamp in s, z) of each camera_link transform sent
        self.is_at_top = False  # the camera moved up to CAMERA_TOP_Z_M

    def send(self):
        """Both arms (the right one swaying every other message) and, every other message while
        tracking, one camera_link transform stamped now: the camera at rest_z_m or moving up
        from it (past CAMERA_TOP_Z_M, none: is_at_top)."""
        self.messages += 1
        if self.is_tracking and self.messages % 2 == 1:
            stamp = rospy.Time.now()
            stamp_s = to_sec(stamp)
            z_m = self.rest_z_m
            if self.moving_since_s is not None:
                z_m += SPEED_MPS * (stamp_s - self.moving_since_s)
            if z_m > CAMERA_TOP_Z_M:  # the end of the column: it stays at its last sample
                self.is_at_top = True
            else:
                self.tf_pub.publish(TFMessage(
                    transforms=[transform(CAMERA_FRAME, (CAMERA_X_M, CAMERA_Y_M, z_m), stamp)]))
                self.samples.append((stamp_s, z_m))
        self.client.publish_pose(HOME, RIGHT_SWAY if self.messages % 2 == 1 else HOME)

    def drive(self, done, timeout_s=TIMEOUT_S):
        """send() every REPUBLISH_PERIOD_S (20 Hz; after a delay, on from then) until done() is
        true; returns whether it became true within timeout_s."""
        deadline = time.time() + timeout_s
        next_send = time.time()
        while time.time() < deadline and not rospy.is_shutdown():
            if time.time() >= next_send:
                self.send()
                next_send = max(next_send + REPUBLISH_PERIOD_S, time.time())
            if done():
                return True
            time.sleep(POLL_PERIOD_S)
        return False

    @staticmethod
    def good_reports(client, start):
        """The reports of `client` from index `start` on of cycles run on accepted input."""
        return [r for r in client.reports_since(start)
                if r.input_status == MonitorReport.INPUT_OK]

    def assert_each(self, reports, name, threshold_m, what):
        """Every report has warnings of object `name`, against the left arm, of threshold_m."""
        wrong = [r for r in reports if not has_threshold(r, name, threshold_m)]
        self.assertFalse(wrong, '%s: %d of %d reports without %s warnings of threshold %.12f '
                         'm, the first: %s' % (what, len(wrong), len(reports), name, threshold_m,
                                               describe(wrong[:5], name)))
        others = [r for r in reports if not all(other_owner(w, name).startswith('left_link')
                                                for w in object_warnings(r, name))]
        self.assertFalse(others, '%s: %s warnings against other than the left arm: %s'
                         % (what, name, describe(others[:5], name)))

    def assert_within(self, reports, name, low_m, high_m, what):
        """Every report has warnings of object `name`, each of a threshold in [low_m, high_m]."""
        wrong = [r for r in reports if not object_warnings(r, name) or not all(
            low_m - ROUNDING_M <= w.threshold_m <= high_m + ROUNDING_M
            for w in object_warnings(r, name))]
        self.assertFalse(wrong, '%s: reports without %s warnings of threshold within '
                         '[%.4f, %.4f] m: %s' % (what, name, low_m, high_m,
                                                 describe(wrong[:5], name)))

    def right_moved(self, reports, name):
        """R, the moved primitives of a cycle of a right-arm message, from reports of cycles in
        which the object rested: it and the arms' idle cycles' 0 are the only counts."""
        moved = set(r.moved_primitives for r in reports)
        right = max(moved)
        self.assertGreater(right, 1, 'no cycle moved the swaying right arm')
        self.assertEqual(moved - {0, right}, set(), 'with the %s at rest, cycles moving other '
                         'counts of primitives than 0 and %d' % (name, right))
        return right

    def test_static_frame_probe_rests_between_its_moves(self):
        # probe_link on /tf_static (stamped 0) beside the left arm: the probe's warnings, at
        # rest, of the tolerances' sum. Moved up by 5 mm: the cycle of that move has a speed of
        # 5 mm / cycle_period_s, the idle cycles after it repeat its report, and the next cycle
        # that runs (a right-arm message: R moved) has it at rest again, for good. A speed kept
        # as for a tracker's frame would stay on (and the first timed pose of a frame with no
        # stamp before takes max_speed_mps, until a next stamp that never comes).
        client = self.static_client
        probe = {'xyz_m': PROBE_XYZ_M}

        def send_probe():
            self.tf_static_pub.publish(TFMessage(
                transforms=[transform(PROBE_FRAME, probe['xyz_m'], rospy.Time(0))]))
        send_probe()
        start = client.report_count()
        rest = {}

        def at_rest():
            reports = self.good_reports(client, start)
            rest['first'] = first_with(reports, PROBE, REST_THRESHOLD_M)
            return rest['first'] is not None and len(
                [r for r in reports[rest['first']:] if r.moved_primitives > 1]) >= (
                    MIN_BETWEEN_CYCLES)
        self.assertTrue(self.drive(at_rest), 'the probe on its static frame never came to rest '
                        'beside the left arm: %s'
                        % describe(self.good_reports(client, start)[-5:], PROBE))
        reports = self.good_reports(client, start)
        self.assert_each(reports[rest['first']:], PROBE, REST_THRESHOLD_M, 'at rest')
        right = self.right_moved(reports[rest['first']:], PROBE)

        start = client.report_count()
        probe['xyz_m'] = (PROBE_XYZ_M[0], PROBE_XYZ_M[1], PROBE_XYZ_M[2] + PROBE_STEP_M)
        send_probe()
        moved = {}

        def moved_and_rested():
            reports = self.good_reports(client, start)
            moved['first'] = first_with(reports, PROBE, PROBE_MOVED_THRESHOLD_M)
            if moved['first'] is None:
                return False
            moved['rest'] = first_with(reports, PROBE, REST_THRESHOLD_M, moved['first'])
            return moved['rest'] is not None and len(
                [r for r in reports[moved['rest']:] if r.moved_primitives == right]) >= (
                    MIN_BETWEEN_CYCLES)
        is_done = self.drive(moved_and_rested)
        reports = self.good_reports(client, start)
        self.assertTrue(is_done, 'moved by %.3f m on its static frame, the probe never had the '
                        'threshold %.12f m, then %.12f m for %d cycles: %s'
                        % (PROBE_STEP_M, PROBE_MOVED_THRESHOLD_M, REST_THRESHOLD_M,
                           MIN_BETWEEN_CYCLES, describe(reports[-8:], PROBE)))
        self.assert_each(reports[:moved['first']], PROBE, REST_THRESHOLD_M, 'before the move')
        moving = reports[moved['first']:moved['rest']]
        self.assert_each(moving, PROBE, PROBE_MOVED_THRESHOLD_M, 'moved')
        self.assertIn(moving[0].moved_primitives, (1, right + 1),
                      'the cycle of the move did not move the probe: %s'
                      % describe(moving[:1], PROBE))
        self.assertEqual([r for r in moving[1:] if r.moved_primitives != 0], [],
                         'cycles that ran after the move without bringing the probe to rest')
        self.assertEqual(reports[moved['rest']].moved_primitives, right,
                         'the probe came to rest in other than the next cycle of the right arm')
        self.assert_each(reports[moved['rest']:], PROBE, REST_THRESHOLD_M, 'after the move')

    def test_tracked_camera_keeps_its_speed_between_samples(self):
        # Both arms first, camera_link not yet sent (a stop naming it, the input accepted): a
        # few cycles, so that the left arm's joints have been sampled unmoved (at rest).
        start = self.client.report_count()
        self.assertTrue(self.drive(lambda: len(self.good_reports(self.client, start)) >= 6),
                        'no accepted input from the arms')

        # 1. The camera appears beside the left arm, unmoved from then on. Its first pose (a
        # move from its scene pose with no stamp before) takes max_speed_mps; the next sample,
        # the same pose at a later stamp, brings it to rest.
        start = self.client.report_count()
        self.is_tracking = True
        rest = {}

        def at_rest():
            reports = self.good_reports(self.client, start)
            rest['first'] = first_with(reports, CAMERA, REST_THRESHOLD_M)
            return rest['first'] is not None and len(
                [r for r in reports[rest['first']:] if r.moved_primitives > 1]) >= (
                    MIN_BETWEEN_CYCLES)
        self.assertTrue(self.drive(at_rest), 'the camera beside the left arm, unmoved, never '
                        'came to rest: %s'
                        % describe(self.good_reports(self.client, start)[-5:], CAMERA))
        reports = self.good_reports(self.client, start)
        first = next(r for r in reports if object_warnings(r, CAMERA))
        self.assertTrue(has_threshold(first, CAMERA, FIRST_THRESHOLD_M),
                        'the camera\'s first pose, with no stamp before, not at max_speed_mps '
                        '(threshold %.12f m): %s' % (FIRST_THRESHOLD_M, describe([first], CAMERA)))
        self.assert_each(reports[rest['first']:], CAMERA, REST_THRESHOLD_M, 'at rest')
        right = self.right_moved(reports[rest['first']:], CAMERA)

        # 2. The camera moves up the column at SPEED_MPS, its height linear in the stamps from
        # the last rest sample's. The reports from the first with the moving threshold on must
        # all have it: those of cycles of a sample (1 or R + 1 moved) and those of cycles that
        # ran between two (R moved) alike.
        start = self.client.report_count()
        self.moving_since_s = self.samples[-1][0]
        moving = {}

        def enough_moving():
            reports = self.good_reports(self.client, start)
            moving['first'] = first_with(reports, CAMERA, MOVING_THRESHOLD_M)
            if moving['first'] is None:
                return False
            after = reports[moving['first']:]
            return (len([r for r in after if r.moved_primitives == right]) >=
                    MIN_BETWEEN_CYCLES and
                    len([r for r in after if r.moved_primitives in (1, right + 1)]) >=
                    MIN_SAMPLE_CYCLES)
        is_enough = self.drive(lambda: enough_moving() or self.is_at_top)
        # Sent before the camera stops: every report received so far is of the move.
        reports = self.good_reports(self.client, start)
        self.assertTrue(is_enough and not self.is_at_top,
                        'moving at %.2f m/s up to z %.2f m: not %d cycles between TF samples and '
                        '%d of samples from the first with threshold %.12f m; the thresholds '
                        'seen: %s; the last reports: %s'
                        % (SPEED_MPS, CAMERA_TOP_Z_M, MIN_BETWEEN_CYCLES, MIN_SAMPLE_CYCLES,
                           MOVING_THRESHOLD_M, tally(reports, CAMERA, right),
                           describe(reports[-6:], CAMERA)))
        # Before it: at rest until the node had a sample of the move (slower, over an interval
        # from an older rest sample than the last).
        self.assert_within(reports[:moving['first']], CAMERA, REST_THRESHOLD_M,
                           MOVING_THRESHOLD_M, 'starting to move')
        self.assert_each(reports[moving['first']:], CAMERA, MOVING_THRESHOLD_M,
                         'moving at %.2f m/s' % SPEED_MPS)

        # 3. The camera stops where its last sample put it, its frame still sent with new
        # stamps: at rest from a report on, in every cycle after it. Before it, cycles still of
        # the move (or of a last interval that ended at rest: slower).
        start = self.client.report_count()
        self.rest_z_m = self.samples[-1][1]
        self.moving_since_s = None
        stopped = {}

        def enough_stopped():
            reports = self.good_reports(self.client, start)
            stopped['first'] = first_with(reports, CAMERA, REST_THRESHOLD_M)
            if stopped['first'] is None:
                return False
            stopped.setdefault('samples', len(self.samples))
            return (len([r for r in reports[stopped['first']:] if r.moved_primitives == right])
                    >= MIN_BETWEEN_CYCLES and
                    len(self.samples) - stopped['samples'] >= MIN_REST_SAMPLES)
        is_enough = self.drive(enough_stopped)
        reports = self.good_reports(self.client, start)
        self.assertTrue(is_enough, 'stopped: the threshold never came back to %.12f m for %d '
                        'cycles; the last: %s' % (REST_THRESHOLD_M, MIN_BETWEEN_CYCLES,
                                                  describe(reports[-8:], CAMERA)))
        self.assert_within(reports[:stopped['first']], CAMERA, REST_THRESHOLD_M,
                           MOVING_THRESHOLD_M, 'stopping')
        self.assert_each(reports[stopped['first']:], CAMERA, REST_THRESHOLD_M, 'stopped')


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'frame_speed_tolerance', FrameSpeedToleranceTest,
                   sys.argv)
