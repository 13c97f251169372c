#!/usr/bin/python3
"""A frame-bound object follows its TF frame (test/ros/frame_bound_object.test).

config/scene.yaml binds the box `camera` (0.12 x 0.2 x 0.1 m, its centre at the frame's origin)
to the TF frame camera_link. This node broadcasts that frame while it holds both arms home (on
/tf as tf2_msgs/TFMessage, what tf2_ros's TransformBroadcaster sends: Debian's python3-tf2-ros
is not among the package's dependencies). At the scene's pose the cell is clear; moved onto the
left arm's column the camera must warn against a left-arm link, its closest point on the camera
near the new pose; moved back, the warning must clear. Not broadcast for ~frame_timeout_s, the
frame is stale: a stop naming the object and the frame, until it comes back. A second node with
two frame-bound objects (test/data/two_frames_scene.yaml) follows the second one's frame while
the first one's is unavailable."""
import math
import sys
import unittest

import rospy
import rostest
from geometry_msgs.msg import Quaternion, TransformStamped
from tf2_msgs.msg import TFMessage

from arm_collision_monitor.msg import MonitorReport
from arm_collision_monitor.srv import AttachObject, DetachObject

from acm_test_util import HOME, MonitorClient, describe_warnings

NODE = '/arm_collision_monitor'
OBJECT = 'camera'
FRAME = 'camera_link'
# The scene's pose of the camera (config/scene.yaml): above the front table, far from the arms.
SCENE_XYZ_M = (1.6, 0.0, 2.4)
SCENE_RPY = (0.0, 0.6, 0.0)
# On the left arm's column (the left base is at x 0, y 0.55, z 0.8; home points straight up),
# at the height of left_link4 (z 1.7 .. 2.0).
IN_LEFT_ARM_XYZ_M = (0.0, 0.55, 1.85)
# The camera's half diagonal (0.06, 0.1, 0.05 m): its closest point lies within this of its frame.
CAMERA_HALF_DIAGONAL_M = 0.127
# The node of test/data/two_frames_scene.yaml and its second frame-bound object.
TWO_FRAMES_NODE = '/two_frames_monitor'
PROBE = 'probe'
PROBE_FRAME = 'probe_link'
PROBE_CLEAR_XYZ_M = (1.6, 1.0, 2.4)  # its scene pose, far from the arms at home
TIMEOUT_S = 10.0


def quaternion_from_rpy(roll, pitch, yaw):
    """The rotation Rz(yaw) Ry(pitch) Rx(roll) (URDF's rpy convention) as a quaternion."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return Quaternion(x=sr * cp * cy - cr * sp * sy, y=cr * sp * cy + sr * cp * sy,
                      z=cr * cp * sy - sr * sp * cy, w=cr * cp * cy + sr * sp * sy)


def camera_warnings(report):
    return [w for w in report.warnings if OBJECT in (w.owner_a, w.owner_b)]


class FrameBoundObjectTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('frame_bound_object_test')
        cls.client = MonitorClient(NODE)
        cls.tf_pub = rospy.Publisher('/tf', TFMessage, queue_size=100)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input topics'

    def send(self, xyz_m, rpy, norm=1.0, stamp=None):
        """One camera_link transform (its quaternion of norm `norm`, stamped `stamp` or now) and
        one home pose of both arms (the input that makes the monitor cycle and read the frame)."""
        t = TransformStamped()
        t.header.stamp = rospy.Time.now() if stamp is None else stamp
        t.header.frame_id = 'world'
        t.child_frame_id = FRAME
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz_m
        t.transform.rotation = quaternion_from_rpy(*rpy)
        for axis in ('x', 'y', 'z', 'w'):
            setattr(t.transform.rotation, axis, norm * getattr(t.transform.rotation, axis))
        self.tf_pub.publish(TFMessage(transforms=[t]))
        self.client.publish_pose(HOME, HOME)

    def wait_clear(self, what):
        seen = []

        def clear(report):
            seen.append(report)
            return (report.input_status == MonitorReport.INPUT_OK and not report.warnings and
                    not report.stop)
        report = self.client.publish_until(lambda: self.send(SCENE_XYZ_M, SCENE_RPY), clear,
                                           TIMEOUT_S)
        self.assertIsNotNone(report, '%s: no clear report with the camera at its scene pose; '
                             'last seen: %s' % (what, self.describe(seen)))
        return report

    def wait_camera_unavailable(self, publish, detail, seen):
        """Publishes until a report's stop names camera_link's newest transform as unavailable,
        its reason containing `detail`; the reports seen so far go to `seen`."""
        def unavailable(report):
            seen.append(report)
            return report.stop and report.stop_reason.startswith(
                "object '%s': pose from frame '%s' unavailable: its newest transform is "
                % (OBJECT, FRAME)) and detail in report.stop_reason
        return self.client.publish_until(publish, unavailable, TIMEOUT_S)

    @staticmethod
    def describe(seen):
        if not seen:
            return 'no report at all'
        r = seen[-1]
        return 'input_status %d, stop %s (%s), warnings: %s' % (
            r.input_status, r.stop, r.stop_reason, describe_warnings(r))

    def test_camera_frame_gone_stale_stops_until_it_is_back(self):
        # The frame's broadcaster stops while the arms keep coming (a dual UR5e user's tray kept
        # its last pose for 12 s without a word): past ~frame_timeout_s (0.5 s) a stop naming
        # the object, its frame and the transform's age; the frame back, the stop clears.
        self.wait_clear('before')
        seen = []
        report = self.wait_camera_unavailable(lambda: self.client.publish_pose(HOME, HOME),
                                              's old, over', seen)
        self.assertIsNotNone(report, 'no stale-frame stop with camera_link silent; last seen: %s'
                             % self.describe(seen))
        self.assertIn('s old, over ~frame_timeout_s (0.500 s)', report.stop_reason)
        self.wait_clear('with the frame back')

    def test_camera_frame_moves_into_the_arm_and_away(self):
        self.wait_clear('before')
        seen = []

        def warned(report):
            seen.append(report)
            return any(w.owner_a.startswith('left_link') or w.owner_b.startswith('left_link')
                       for w in camera_warnings(report))
        report = self.client.publish_until(lambda: self.send(IN_LEFT_ARM_XYZ_M, (0.0, 0.0, 0.0)),
                                           warned, TIMEOUT_S)
        self.assertIsNotNone(report, 'no camera - left arm warning with camera_link moved into '
                             'the left arm; last seen: %s' % self.describe(seen))
        self.assertTrue(report.stop, 'a warning without a stop request')
        for w in camera_warnings(report):
            on_camera = w.point_a if w.owner_a == OBJECT else w.point_b
            offset = [on_camera.x - IN_LEFT_ARM_XYZ_M[0], on_camera.y - IN_LEFT_ARM_XYZ_M[1],
                      on_camera.z - IN_LEFT_ARM_XYZ_M[2]]
            self.assertLessEqual(sum(d * d for d in offset) ** 0.5, CAMERA_HALF_DIAGONAL_M,
                                 'the closest point on the camera %s is not on the box at the '
                                 'frame\'s new pose' % (on_camera,))
        report = self.wait_clear('after moving the frame away')
        self.assertEqual(camera_warnings(report), [])

    def test_camera_quaternion_off_unit_norm_is_normalised(self):
        # tf2 keeps a quaternion whose squared norm is within 0.01 of 1; its matrix as it is
        # would stretch the camera by 0.4 % (the monitor refuses such a pose, and stops): the
        # node normalises it, and the camera at its scene pose stays clear, cycle after cycle.
        self.wait_clear('before')
        start = self.client.report_count()
        report = self.client.publish_until(
            lambda: self.send(SCENE_XYZ_M, SCENE_RPY, norm=1.004),
            lambda r: len(self.client.reports_since(start)) >= 40, TIMEOUT_S)
        self.assertIsNotNone(report, 'fewer than 40 reports with camera_link\'s quaternion of '
                             'norm 1.004')
        # The first few cycles may still read the last unit-norm transform.
        late = self.client.reports_since(start)[20:]
        stopped = [r for r in late if r.stop or r.input_status != MonitorReport.INPUT_OK]
        self.assertFalse(stopped, 'with camera_link\'s quaternion of norm 1.004: %s'
                         % self.describe(stopped))

    def send_both(self, client, probe_xyz_m, left=HOME):
        """camera_link at the scene's pose and probe_link at `probe_xyz_m` (none if None), both
        stamped now, then the left arm at `left` and the right one home to `client`'s node."""
        stamp = rospy.Time.now()
        frames = []
        for frame, xyz_m, rpy in ((FRAME, SCENE_XYZ_M, SCENE_RPY),
                                  (PROBE_FRAME, probe_xyz_m, (0.0, 0.0, 0.0))):
            if xyz_m is None:
                continue
            t = TransformStamped()
            t.header.stamp = stamp
            t.header.frame_id = 'world'
            t.child_frame_id = frame
            (t.transform.translation.x, t.transform.translation.y,
             t.transform.translation.z) = xyz_m
            t.transform.rotation = quaternion_from_rpy(*rpy)
            frames.append(t)
        self.tf_pub.publish(TFMessage(transforms=frames))
        client.publish_pose(left, HOME)

    def send_for_reports(self, client, publish, count, what):
        start = client.report_count()
        self.assertIsNotNone(client.publish_until(
            publish, lambda r: len(client.reports_since(start)) >= count, TIMEOUT_S),
            'fewer than %d reports %s' % (count, what))
        return client.reports_since(start)

    def hold_probe(self, client, attach):
        """Lowers the probe's frame onto the left arm (home: straight up) until ~attach takes it
        to left_link7 (within its hold reach, clear of every threshold); returns that pose."""
        x, y = IN_LEFT_ARM_XYZ_M[0], IN_LEFT_ARM_XYZ_M[1]
        for step in range(150):
            xyz_m = (x, y, 3.5 - 0.01 * step)
            self.send_for_reports(client, lambda: self.send_both(client, xyz_m), 3,
                                  'with the probe at %s' % (xyz_m,))
            if attach(PROBE, 'left_link7').success:
                return xyz_m
        self.fail('the probe lowered onto the left arm was never attachable')

    def test_held_probe_follows_its_holder_not_its_frame(self):
        # A held frame-bound object follows its holder; its frame, still broadcast and moving,
        # made every cycle a stop ('held by link', SetObjectPose refusing it) until it was let
        # go. Its frame silent (stale), ~attach is refused: held, it would silence that stop.
        # Held, its frame moves 1 mm a message for 40 reports: none may stop (the first few may
        # still be of cycles before the attach). Let go, it follows its frame again: into the
        # arm, a warning.
        client = MonitorClient(TWO_FRAMES_NODE)
        self.assertTrue(client.wait_connected())
        attach = rospy.ServiceProxy(TWO_FRAMES_NODE + '/attach', AttachObject)
        detach = rospy.ServiceProxy(TWO_FRAMES_NODE + '/detach', DetachObject)

        def clear(report):
            return (report.input_status == MonitorReport.INPUT_OK and not report.warnings and
                    not report.stop)
        self.assertIsNotNone(client.publish_until(
            lambda: self.send_both(client, PROBE_CLEAR_XYZ_M), clear, TIMEOUT_S),
            'no clear report before')
        probe_stale = client.publish_until(
            lambda: self.send_both(client, None),
            lambda r: r.stop and "object '%s'" % PROBE in r.stop_reason, TIMEOUT_S)
        self.assertIsNotNone(probe_stale, 'no stop naming the probe with its frame silent')
        res = attach(PROBE, 'left_link7')
        self.assertFalse(res.success, 'attached with its frame unavailable')
        self.assertIn("its frame '%s' is unavailable" % PROBE_FRAME, res.message)
        held_at = None
        try:
            held_at = self.hold_probe(client, attach)
            moved = [0]

            def send_moved():
                moved[0] += 1
                self.send_both(client, (held_at[0] + 0.001 * (moved[0] % 2), held_at[1],
                                        held_at[2]))
            reports = self.send_for_reports(client, send_moved, 40,
                                            'with the held probe\'s frame moving')
            stopped = [r for r in reports[5:] if r.stop]
            self.assertFalse(stopped, 'the held probe at %s, its frame moving: %s'
                             % (held_at, self.describe(stopped)))
        finally:
            if held_at is not None:
                res = detach(PROBE)
                self.assertTrue(res.success, res.message)

        def probe_warns(report):
            return any(PROBE in (w.owner_a, w.owner_b) for w in report.warnings)
        self.assertIsNotNone(client.publish_until(
            lambda: self.send_both(client, IN_LEFT_ARM_XYZ_M), probe_warns, TIMEOUT_S),
            'no probe warning with the probe let go and its frame in the arm')
        self.assertIsNotNone(client.publish_until(
            lambda: self.send_both(client, PROBE_CLEAR_XYZ_M), clear, TIMEOUT_S),
            'no clear report with the probe let go and its frame moved away')

    def test_let_go_probe_stays_where_released_while_its_frame_repeats(self):
        # A stamped frame that does not follow the object (a static_transform_publisher's, a
        # tracker repeating its estimate while the gripper hides the object) keeps coming with
        # the pose it had when the object was taken. Let go elsewhere, the object must stay
        # where it was released until the frame's pose moves; it was pulled back to the frame's
        # pose at the frame's next stamp, and the monitor modelled it where it no longer was.
        # Held, the probe is carried 0.6 rad about left_joint2 (left_link7 moves about 0.8 m)
        # and let go there; with the arm home again, ~attach to left_link7 must be refused as
        # out of reach (it was taken back at the frame's pose, within reach), and with the arm
        # back where it let go, taken. Let go there again, it follows its frame once that moves
        # away: out of reach of the arm where it let go.
        client = MonitorClient(TWO_FRAMES_NODE)
        self.assertTrue(client.wait_connected())
        attach = rospy.ServiceProxy(TWO_FRAMES_NODE + '/attach', AttachObject)
        detach = rospy.ServiceProxy(TWO_FRAMES_NODE + '/detach', DetachObject)
        self.assertIsNotNone(client.publish_until(
            lambda: self.send_both(client, PROBE_CLEAR_XYZ_M),
            lambda r: not any(PROBE in (w.owner_a, w.owner_b) for w in r.warnings),
            TIMEOUT_S), 'no report without a probe warning before')
        def walk(probe_xyz_m, steps):
            """The left arm through left_joint2 at -0.05 rad times each of `steps`, the probe's
            frame at `probe_xyz_m`, two reports at each; returns the last pose."""
            left = list(HOME)
            for step in steps:
                left = list(HOME)
                left[1] = -0.05 * step
                self.send_for_reports(client, lambda: self.send_both(client, probe_xyz_m, left),
                                      2, 'with left_joint2 at %.2f' % left[1])
            return left

        held_at = self.hold_probe(client, attach)
        is_held = True
        try:
            released = walk(held_at, range(1, 13))
            res = detach(PROBE)
            self.assertTrue(res.success, res.message)
            is_held = False
            self.send_for_reports(client, lambda: self.send_both(client, held_at, released), 10,
                                  'with the probe let go, its frame where it was taken')
            walk(held_at, range(11, -1, -1))
            res = attach(PROBE, 'left_link7')
            is_held = res.success
            self.assertFalse(res.success, 'the let-go probe was in reach of left_link7 at home: '
                             'pulled back to its frame\'s pose %s' % (held_at,))
            self.assertIn('reaches', res.message)
            self.send_for_reports(client, lambda: self.send_both(client, held_at, released), 5,
                                  'with the arm back where it let the probe go')
            res = attach(PROBE, 'left_link7')
            is_held = res.success
            self.assertTrue(res.success, 'the let-go probe is not where the arm let it go: %s'
                            % res.message)
            res = detach(PROBE)
            self.assertTrue(res.success, res.message)
            is_held = False
            self.send_for_reports(client, lambda: self.send_both(client, PROBE_CLEAR_XYZ_M,
                                                                 released), 5,
                                  'with the probe let go, its frame moved away')
            res = attach(PROBE, 'left_link7')
            is_held = res.success
            self.assertFalse(res.success, 'the let-go probe did not follow its frame away')
            self.assertIn('reaches', res.message)
        finally:
            if is_held and not detach(PROBE).success:
                rospy.logerr('could not let the probe go after the test')
        walk(PROBE_CLEAR_XYZ_M, range(11, -1, -1))

    def test_second_frame_followed_while_the_first_is_unavailable(self):
        # test/data/two_frames_scene.yaml: camera (camera_link), then probe (probe_link). Once
        # camera_link is unavailable (not sent for ~frame_timeout_s), the stop names the camera;
        # the probe, then moved into the left arm by its frame, must warn (the node used to stop
        # reading frames at the first unavailable one: the probe kept its last pose, clear of
        # the arms, without a word). With probe_link silent too, the stop names both objects.
        client = MonitorClient(TWO_FRAMES_NODE)
        self.assertTrue(client.wait_connected())
        self.assertTrue(client.wait_stop(True), 'no ~stop from %s' % TWO_FRAMES_NODE)
        seen = []

        def send_probe(xyz_m):
            t = TransformStamped()
            t.header.stamp = rospy.Time.now()
            t.header.frame_id = 'world'
            t.child_frame_id = PROBE_FRAME
            t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz_m
            t.transform.rotation.w = 1.0
            self.tf_pub.publish(TFMessage(transforms=[t]))
            client.publish_pose(HOME, HOME)

        def camera_named(report):
            return report.stop_reason.startswith(
                "object '%s': pose from frame '%s' unavailable: " % (OBJECT, FRAME))

        def probe_warns(report):
            return any(PROBE in (w.owner_a, w.owner_b) for w in report.warnings)

        def clear_probe_camera_named(report):
            seen.append(report)
            return camera_named(report) and not probe_warns(report)
        report = client.publish_until(lambda: send_probe(PROBE_CLEAR_XYZ_M),
                                      clear_probe_camera_named, TIMEOUT_S)
        self.assertIsNotNone(report, 'no stop naming the camera\'s frame with the probe clear; '
                             'last seen: %s' % self.describe(seen))

        def probe_warned_camera_named(report):
            seen.append(report)
            return camera_named(report) and probe_warns(report)
        report = client.publish_until(lambda: send_probe(IN_LEFT_ARM_XYZ_M),
                                      probe_warned_camera_named, TIMEOUT_S)
        self.assertIsNotNone(report, 'no probe warning with the probe moved into the left arm '
                             'while the camera\'s frame is unavailable; last seen: %s'
                             % self.describe(seen))
        self.assertTrue(report.stop)

        def both_named(report):
            seen.append(report)
            return camera_named(report) and report.stop_reason.endswith(
                "; also unavailable: '%s'" % PROBE)
        report = client.publish_until(lambda: client.publish_pose(HOME, HOME), both_named,
                                      TIMEOUT_S)
        self.assertIsNotNone(report, 'no stop naming both objects with both frames silent; '
                             'last seen: %s' % self.describe(seen))

    def test_transform_stamped_far_ahead_stops_and_the_node_lives_on(self):
        # A transform stamped 2^32 s - 296 s (a broken clock; 136 years ahead) made the node's
        # age computation throw (ros::Time's difference past 2^31 s): the node died with its
        # last ~stop False. It is a frame that cannot be dated (as JointState input stamped
        # ahead): a stop naming the object, report after report. Runs last (alphabetical): tf2
        # then ignores camera_link's transforms stamped now, older than that one by far.
        self.wait_clear('before')
        seen = []
        far_ahead = rospy.Time(4294967000)
        report = self.wait_camera_unavailable(
            lambda: self.send(SCENE_XYZ_M, SCENE_RPY, stamp=far_ahead),
            "s ahead of the node's clock, over ~frame_timeout_s", seen)
        self.assertIsNotNone(report, 'no stop naming camera_link stamped far ahead; last seen: %s'
                             % self.describe(seen))
        start = self.client.report_count()
        report = self.client.publish_until(
            lambda: self.send(SCENE_XYZ_M, SCENE_RPY, stamp=far_ahead),
            lambda r: len(self.client.reports_since(start)) >= 20, TIMEOUT_S)
        self.assertIsNotNone(report, 'the node stopped reporting after camera_link came stamped '
                             'far ahead')
        self.assertTrue(all(r.stop for r in self.client.reports_since(start)))


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'frame_bound_object', FrameBoundObjectTest, sys.argv)
