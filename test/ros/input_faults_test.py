#!/usr/bin/python3
"""Fail-safe behaviour of the monitor node on bad input, its services, one cycle per message and
cycles at a fixed rate (test/ros/input_faults.test). The tests run in name order on one node:
each starts by driving the model to a clear state itself."""
import random
import sys
import time
import unittest

import rosgraph
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import JointState

from arm_collision_monitor.msg import MonitorReport
from arm_collision_monitor.srv import (AddObject, AttachObject, CheckJointState, DetachObject,
                                       SetGraspTarget)

from acm_test_util import (HOME, LEFT_AT_FRONT_BOX, LEFT_JOINTS, LEFT_TOWARDS_RIGHT,
                           RIGHT_JOINTS, RIGHT_TOWARDS_LEFT, MonitorClient, joint_state)

NODE = '/arm_collision_monitor'


def left_only(positions, stamp=None, names=None):
    return joint_state(LEFT_JOINTS if names is None else names, positions, stamp)


class InputFaultsTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('input_faults_test')
        # The node's log, from the start: which refusals it names.
        cls.node_log = []
        cls.log_sub = rospy.Subscriber('/rosout', Log, lambda m: cls.node_log.append(m.msg)
                                       if m.name == NODE else None)
        cls.client = MonitorClient(NODE)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input topics'
        # Connected to the monitor's own /rosout publisher (its first refusal is logged once).
        monitor_uri = rosgraph.Master('/input_faults_test').lookupNode(NODE)
        deadline = time.time() + 20.0
        while (not any(c.endpoint_id == monitor_uri for c in cls.log_sub.impl.connections) and
               time.time() < deadline):
            time.sleep(0.05)
        for name in ('check', 'attach', 'detach', 'set_grasp_target'):
            rospy.wait_for_service(NODE + '/' + name, timeout=20.0)

    def refused_with(self, status, message_fn, clear=None, reason=None, reason_prefix=None):
        """Clears (unless given the clear report), then publishes message_fn() on the left
        topic until a report with `status` arrives; asserts the stop (its reason `reason`, or
        starting with `reason_prefix`, if given) and the refusal count, then that good input
        clears again. Returns the refusal's report."""
        c = self.client
        clear = clear or c.go_clear()
        self.assertIsNotNone(clear, 'no clear report on home input')
        # ~stop is a topic of its own: its false first, or a true still in flight from before
        # the clear report would pass for the refusal's stop below.
        self.assertTrue(c.wait_stop(False), '~stop did not clear before the refusal')
        report = c.publish_until(lambda: c.publishers[0].publish(message_fn()),
                                 lambda r: r.input_status == status)
        self.assertIsNotNone(report, 'no report with input_status %d' % status)
        self.assertTrue(report.stop)
        self.assertNotEqual(report.stop_reason, '')
        if reason is not None:
            self.assertEqual(report.stop_reason, reason)
        if reason_prefix is not None:
            self.assertTrue(report.stop_reason.startswith(reason_prefix), report.stop_reason)
        self.assertGreater(report.refused_inputs, clear.refused_inputs)
        self.assertTrue(c.wait_stop(True), '~stop never went true')
        self.assertIsNotNone(c.go_clear(), 'good input did not clear the stop')
        self.assertTrue(c.wait_stop(False), '~stop never went back to false')
        return report

    def test_01_incomplete_model_requests_stop(self):
        c = self.client
        # Before anything: the latched stop is true.
        self.assertTrue(c.wait_stop(True))
        report = c.publish_until(lambda: c.publishers[0].publish(left_only(HOME)),
                                 lambda r: True)
        self.assertIsNotNone(report)
        self.assertEqual(report.input_status, MonitorReport.INPUT_INCOMPLETE)
        self.assertTrue(report.stop)
        self.assertIn('right_joint1', report.stop_reason)
        self.assertEqual(c.last_stop(), True)
        # The check service names every joint that neither the input nor the request gives.
        check = rospy.ServiceProxy(NODE + '/check', CheckJointState)
        res = check(joint_state(LEFT_JOINTS + RIGHT_JOINTS[2:], list(HOME) + list(HOME[2:])))
        self.assertFalse(res.success)
        self.assertEqual(res.report.input_status, MonitorReport.INPUT_INCOMPLETE)
        self.assertEqual(res.message, "no position for 2 model joints: 'right_joint1', "
                         "'right_joint2': never received, and not in the request")
        # The right arm arrives: the model is complete, the stop clears.
        self.assertIsNotNone(c.go_clear())
        self.assertTrue(c.wait_stop(False))

    def test_02_one_cycle_per_message(self):
        c = self.client
        self.assertIsNotNone(c.go_clear())
        # go_clear()'s republished messages may still be in flight: through before ours.
        self.assertIsNotNone(c.settle())
        start = c.report_count()
        stamps = []
        for _ in range(20):
            stamps += c.publish_pose(HOME, HOME)
            time.sleep(0.005)
        reports = c.wait_stamps(start, stamps)
        self.assertIsNotNone(reports, 'a message got no report')
        self.assertEqual(len(reports), len(stamps), 'one report per message')
        cycles = [r.cycle for r in reports]
        self.assertEqual(cycles, sorted(set(cycles)), 'one cycle each, in order')
        self.assertEqual(cycles[-1] - cycles[0] + 1, len(stamps), 'consecutive cycles')
        for r in reports:
            self.assertEqual(r.header.frame_id, 'world')
            self.assertEqual(r.input_status, MonitorReport.INPUT_OK)
            self.assertGreater(r.cycle_time_s, 0.0)

    def test_03_nan_refused(self):
        self.refused_with(MonitorReport.INPUT_NON_FINITE,
                          lambda: left_only([0.0, float('nan'), 0, 0, 0, 0, 0]),
                          reason="input refused: non_finite (joint 'left_joint2' at nan)")

    def test_04_inf_refused(self):
        self.refused_with(MonitorReport.INPUT_NON_FINITE,
                          lambda: left_only([0.0, 0, 0, float('-inf'), 0, 0, 0]))

    def test_05_length_mismatch_refused(self):
        self.refused_with(MonitorReport.INPUT_WRONG_SIZE, lambda: left_only([0.0] * 6))

    def test_06_duplicate_name_refused(self):
        names = LEFT_JOINTS[:6] + [LEFT_JOINTS[0]]
        self.refused_with(MonitorReport.INPUT_WRONG_SIZE, lambda: left_only([0.0] * 7, names=names),
                          reason="input refused: wrong_size (joint 'left_joint1' named twice)")

    def test_07_stamp_backwards_refused(self):
        c = self.client
        c.go_clear()
        later = rospy.Time.now() + rospy.Duration(0.1)
        # The left joints accept a stamp slightly ahead; an older one must then be refused.
        report = c.publish_until(lambda: c.publishers[0].publish(left_only(HOME, stamp=later)),
                                 lambda r: r.header.stamp == later and not r.stop)
        self.assertIsNotNone(report)
        refused = self.refused_with(
            MonitorReport.INPUT_STAMP_BACKWARDS,
            lambda: left_only(HOME, stamp=later - rospy.Duration(0.05)), clear=report,
            reason="input refused: stamp_backwards (joint 'left_joint1' 0.050 s before its last "
                   "accepted stamp)")
        # The report of a refused message carries that message's stamp (a Techman user's
        # carried the last accepted one's).
        self.assertEqual(refused.header.stamp, later - rospy.Duration(0.05))

    def test_08_old_stamp_refused(self):
        self.refused_with(MonitorReport.INPUT_STALE,
                          lambda: left_only(HOME, stamp=rospy.Time.now() - rospy.Duration(5.0)),
                          reason_prefix="input refused: stale (stamped 5.0")

    def test_08b_future_stamp_refused(self):
        self.refused_with(MonitorReport.INPUT_FUTURE_STAMP,
                          lambda: left_only(HOME, stamp=rospy.Time.now() + rospy.Duration(100.0)))

    def test_09_no_known_joint_refused(self):
        self.refused_with(MonitorReport.INPUT_NO_KNOWN_JOINTS,
                          lambda: left_only([0.1, 0.2], names=['elbow', 'wrist']))
        # A driver's unprefixed names: the topic is named, and the model's prefixed joints.
        self.refused_with(MonitorReport.INPUT_NO_KNOWN_JOINTS,
                          lambda: left_only([0.1, 0.2], names=['joint1', 'joint2']),
                          reason_prefix="input refused: no_known_joints (none of its 2 names is "
                                        "a model joint, the first 'joint1' on "
                                        "/left_arm/joint_states; the model has 'joint1' as "
                                        "'left_joint1', 'right_joint1'; 'joint2' as "
                                        "'left_joint2', 'right_joint2' (give each input topic "
                                        "its prefix: ~input_joint_prefixes))")

    def test_09c_each_kind_of_refusal_is_logged(self):
        # Refusals are logged once a second at most, but the first of each kind always: a dual
        # FR3 user's burst of NaN messages hid the wrong-size ones from the log.
        for kind in ('non_finite', 'wrong_size', 'stamp_backwards', 'stale', 'future_stamp',
                     'no_known_joints'):
            text = 'arm_collision_monitor: refused a JointState (%s' % kind
            deadline = time.time() + 5.0
            while not any(m.startswith(text) for m in self.node_log) and time.time() < deadline:
                time.sleep(0.05)
            self.assertTrue(any(m.startswith(text) for m in self.node_log),
                            '%s: not in the log: %s' % (kind, self.node_log))

    def test_10_unknown_names_ignored_and_counted(self):
        c = self.client
        c.go_clear()
        report = c.publish_until(
            lambda: c.publishers[0].publish(left_only(HOME + [3.0, 4.0],
                                                      names=LEFT_JOINTS + ['bogus1', 'bogus2'])),
            lambda r: r.unknown_joints == 2)
        self.assertIsNotNone(report)
        self.assertEqual(report.input_status, MonitorReport.INPUT_OK)
        self.assertFalse(report.stop)

    def test_10b_position_less_messages_ignored(self):
        # JointState's arrays may be empty: a driver publishing efforts only. Not a refusal, and
        # no stop: the next good message's report has the same refusal count.
        c = self.client
        clear = c.go_clear()
        self.assertIsNotNone(clear)
        efforts_only = left_only([])
        efforts_only.effort = [0.5] * 7
        for _ in range(5):
            c.publishers[0].publish(efforts_only)
            time.sleep(0.02)
        report = c.go_clear()
        self.assertIsNotNone(report)
        self.assertFalse(report.stop)
        self.assertEqual(report.input_status, MonitorReport.INPUT_OK)
        self.assertEqual(report.refused_inputs, clear.refused_inputs)

    def test_11_silence_goes_stale(self):
        c = self.client
        self.assertIsNotNone(c.go_clear())
        # The stop topic is a second subscription: wait for its false before the silence, or an
        # earlier true still in flight would pass for the stale stop.
        self.assertTrue(c.wait_stop(False), '~stop did not clear before the silence')
        start = c.report_count()
        t0 = time.time()
        # No more input: the staleness timer must request a stop and report it. The node sends
        # the stop before the report, each on its own topic: wait for both.
        first = c.wait_report(start, lambda r: r.input_status == MonitorReport.INPUT_STALE)
        elapsed = time.time() - t0
        self.assertIsNotNone(first, 'no stale report after the input stopped')
        self.assertTrue(c.wait_stop(True), 'no stop after the input stopped')
        timeout_s = rospy.get_param(NODE + '/input_timeout_s')
        time.sleep(2.0 * timeout_s)  # the timer goes on firing: the episode must not report again
        stale = [r for r in c.reports_since(start) if r.input_status == MonitorReport.INPUT_STALE]
        self.assertEqual(len(stale), 1, 'one stale report per episode')
        self.assertTrue(stale[0].stop)
        self.assertIn('not received', stale[0].stop_reason)
        self.assertGreaterEqual(elapsed, 0.5 * timeout_s)  # not before the timeout (slack: poll)
        self.assertIsNotNone(c.go_clear())
        self.assertTrue(c.wait_stop(False))

    def check(self, left, right):
        check = rospy.ServiceProxy(NODE + '/check', CheckJointState)
        return check(joint_state(LEFT_JOINTS + RIGHT_JOINTS, list(left) + list(right)))

    def test_12_jump_is_swept_correct_and_reported(self):
        c = self.client
        self.assertIsNotNone(c.go_clear())
        expected = self.check(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT)
        self.assertTrue(expected.success, expected.message)
        self.assertTrue(any(w.owner_a.startswith('left') and w.owner_b.startswith('right') or
                            w.owner_a.startswith('right') and w.owner_b.startswith('left')
                            for w in expected.report.warnings),
                        'the test pose must make the arms warn against each other')
        start = c.report_count()
        # One message per arm, each a jump of about a metre (the per-cycle bound is 3 cm).
        reports = c.wait_stamps(start, c.publish_pose(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT))
        self.assertIsNotNone(reports)
        self.assertEqual(len(reports), 2)
        self.assertGreater(sum(r.reinsert_fallbacks for r in reports), 0,
                           'a jump beyond the per-cycle bound must be reported as a fallback')
        # Each jump is swept (from the last accepted positions) and reported with its motion
        # bound; one beyond max_step_m requests a stop "input jumped".
        for r in reports:
            self.assertGreater(r.step_motion_m, 0.5)
            if r.input_jumped:
                self.assertTrue(r.stop)
                self.assertIn('input jumped', r.stop_reason)
            for w in r.warnings:
                if w.between_samples:
                    self.assertTrue(0.0 <= w.step_fraction <= 1.0)
                    self.assertLessEqual(w.distance_m, w.threshold_m + 0.001 + 1e-9)
        last = reports[-1]
        self.assertEqual(last.input_status, MonitorReport.INPUT_OK)
        self.assertTrue(last.stop)
        # The warnings at the new positions are those of the check service.
        at_sample = [w for w in last.warnings if not w.between_samples]
        got = [(w.primitive_a, w.primitive_b) for w in at_sample]
        want = [(w.primitive_a, w.primitive_b) for w in expected.report.warnings]
        self.assertEqual(got, want)
        for g, w in zip(at_sample, expected.report.warnings):
            self.assertAlmostEqual(g.distance_m, w.distance_m, places=9)
        # Back home: another jump, the warnings go away.
        self.assertIsNotNone(c.go_clear())

    def test_12b_arms_back_after_a_pause_are_no_jump(self):
        # Both drivers silent for 2 s, then back with each arm far from where it was, one message
        # per arm 1 us apart: each joint's move is timed from its own last message (within twice
        # the 1 rad/s velocity limits over 2 s), so neither report is a jump; dated by the newest
        # message alone, the second arm's step would take 1 us and be one.
        c = self.client
        self.assertIsNotNone(c.go_clear())
        time.sleep(2.0)
        start = c.report_count()
        reports = c.wait_stamps(start, c.publish_pose(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT))
        self.assertIsNotNone(reports)
        self.assertEqual(len(reports), 2)
        for r in reports:
            self.assertGreater(r.step_motion_m, 1.0)  # beyond max_step_m
            self.assertFalse(r.input_jumped, r.stop_reason)

    def test_13_check_service_does_not_touch_live_model(self):
        c = self.client
        self.assertIsNotNone(c.go_clear())
        res = self.check(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT)
        self.assertTrue(res.success)
        self.assertTrue(res.report.stop)
        self.assertGreater(len(res.report.warnings), 0)
        # A stop says why, as a live report does ("" only without a stop: a Doosan user's
        # reply had stop true and no reason).
        self.assertTrue(res.report.stop_reason.startswith(
            '%d warning(s), the deepest ' % len(res.report.warnings)), res.report.stop_reason)
        bad = self.check([float('nan')] * 7, HOME)
        self.assertFalse(bad.success)
        self.assertEqual(bad.report.input_status, MonitorReport.INPUT_NON_FINITE)
        self.assertEqual(bad.message,
                         "joint state refused: non_finite (joint 'left_joint1' at nan)")
        self.assertEqual(bad.report.stop_reason, bad.message)
        beyond = self.check([0.0, 10.0, 0, 0, 0, 0, 0], HOME)
        self.assertFalse(beyond.success)
        self.assertTrue(beyond.message.startswith(
            "joint state refused: out_of_limits (joint 'left_joint2' at 10, outside its limits ["),
            beyond.message)
        # The refusal, not the live model's warnings that the reply carries with it.
        self.assertEqual(beyond.report.stop_reason, beyond.message)
        # A name that is no model joint is ignored and said (a Piper user's 'bogus_joint' was
        # answered "0 warning(s)" without a word).
        check = rospy.ServiceProxy(NODE + '/check', CheckJointState)
        extra = check(joint_state(LEFT_JOINTS + RIGHT_JOINTS + ['bogus_joint'],
                                  HOME + HOME + [0.0]))
        self.assertTrue(extra.success, extra.message)
        self.assertEqual(extra.message,
                         "0 warning(s); ignored, no joints of the model: 'bogus_joint'")
        self.assertEqual(extra.report.unknown_joints, 1)
        # A fixed joint of the URDF a driver publishes is marked so (a Sawyer's torso_t0).
        fixed = check(joint_state(LEFT_JOINTS + RIGHT_JOINTS + ['left_tool_joint', 'bogus'],
                                  HOME + HOME + [0.0, 0.0]))
        self.assertEqual(fixed.message,
                         "0 warning(s); ignored, no joints of the model: 'left_tool_joint' "
                         "(a fixed joint of the URDF), 'bogus'")
        self.assertEqual(fixed.report.unknown_joints, 2)
        # A request whose left arm joints lack their prefix (a MOVO user's): counted, and the
        # model joints it left to their live positions said.
        bare = check(joint_state([name[len('left_'):] for name in LEFT_JOINTS] + RIGHT_JOINTS,
                                 HOME + HOME))
        self.assertEqual(bare.report.unknown_joints, 7)
        self.assertTrue(bare.message.startswith("0 warning(s); ignored, no joints of the model: "
                                                "'joint1', "), bare.message)
        self.assertTrue(bare.message.endswith(
            "; 7 of the model's 14 joints not in the request, checked at their live positions "
            "(or defaults)"), bare.message)
        # Counted on a refusal too: no name of the request a model joint.
        none = check(joint_state([name[len('left_'):] for name in LEFT_JOINTS], HOME))
        self.assertFalse(none.success)
        self.assertEqual(none.report.unknown_joints, 7)
        self.assertIn("; ignored, no joints of the model: 'joint1', ", none.message)
        # The live model still gives a clear report on home input.
        report = c.publish_until(lambda: c.publish_pose(HOME, HOME), lambda r: True)
        self.assertEqual(report.warnings, [])

    def test_14_attach_detach_grasp_services(self):
        c = self.client
        attach = rospy.ServiceProxy(NODE + '/attach', AttachObject)
        detach = rospy.ServiceProxy(NODE + '/detach', DetachObject)
        grasp = rospy.ServiceProxy(NODE + '/set_grasp_target', SetGraspTarget)
        self.assertIsNotNone(c.go_clear())
        self.assertFalse(attach('no_such_object', 'left_link7').success)
        self.assertFalse(attach('front_box', 'no_such_link').success)
        # At home the gripper is far from the box: the Monitor refuses to attach it.
        self.assertFalse(attach('front_box', 'left_link7').success)
        # The left gripper just above the front box (planar two-link solution, gripper down).
        self.assertIsNotNone(c.hold_pose(LEFT_AT_FRONT_BOX, HOME))
        res = grasp('left_link7', 'front_box', True)
        self.assertTrue(res.success, res.message)
        res = attach('front_box', 'left_link7')
        self.assertTrue(res.success, res.message)
        res = detach('front_box')
        self.assertTrue(res.success, res.message)
        self.assertFalse(detach('front_box').success, 'detached twice')
        res = grasp('left_link7', 'front_box', False)
        self.assertTrue(res.success, res.message)
        self.assertFalse(grasp('right_link7', 'no_such_object', True).success)
        self.assertIsNotNone(c.go_clear())

    def test_15_random_garbage_never_crashes(self):
        c = self.client
        seed = int(rospy.get_param('~seed', 20261121))
        print('test_15_random_garbage_never_crashes: seed %d' % seed)
        rng = random.Random(seed)
        specials = [float('nan'), float('inf'), -float('inf'), 1e308, -1e308, 0.0, 5.0]
        names = LEFT_JOINTS + RIGHT_JOINTS + ['', 'x' * 300, 'left_joint1 ']
        self.assertIsNotNone(c.go_clear())
        # The last report before the garbage: go_clear()'s republished messages, possibly still
        # in flight, would add cycles of their own.
        clear = c.settle()
        self.assertIsNotNone(clear)
        garbage_start = c.report_count()
        sent = 0  # messages that make a cycle: not those naming joints without positions
        for _ in range(300):
            msg = JointState()
            k = rng.randint(0, 16)
            msg.name = [rng.choice(names) for _ in range(k)]
            msg.position = [rng.choice(specials) if rng.random() < 0.3 else rng.uniform(-4, 4)
                            for _ in range(max(0, k + rng.choice([-1, 0, 0, 0, 1])))]
            msg.velocity = [rng.uniform(-1, 1) for _ in range(rng.randint(0, 3))]
            roll = rng.random()
            if roll < 0.5:
                msg.header.stamp = rospy.Time.now()
            elif roll < 0.75:
                msg.header.stamp = rospy.Time(0)
            else:
                msg.header.stamp = rospy.Time(rng.randint(0, 2**32 - 1), rng.randint(0, 999999999))
            rng.choice(c.publishers).publish(msg)
            sent += 1 if msg.position or not msg.name else 0
            time.sleep(0.001)
        # The node stamps an unstamped message with the time it reads it, so a sentinel stamped
        # before the node read the last of the garbage would rightly be refused (stamp going
        # backwards, or stale when the node lags by more than input_timeout_s). Wait until it
        # has run one cycle per garbage message and gone quiet.
        self.assertIsNotNone(
            c.wait_report(garbage_start, lambda r: r.cycle - clear.cycle >= sent, timeout_s=20.0),
            'the node did not work through the garbage')
        count = -1
        while count != c.report_count():
            count = c.report_count()
            time.sleep(0.3)
        # A good message after the garbage: its report proves the node alive and that every
        # message before it was processed (one cycle each).
        start = c.report_count()
        sentinel = joint_state(LEFT_JOINTS, HOME)
        c.publishers[0].publish(sentinel)
        reports = c.wait_stamps(start, [sentinel.header.stamp], timeout_s=20.0)
        self.assertIsNotNone(reports, 'the node did not answer after the garbage')
        self.assertEqual(reports[0].cycle - clear.cycle, sent + 1)

    def test_16_combined_topic(self):
        """A second node reading one combined joint_states topic."""
        c = MonitorClient('/combined_monitor', topics=('joint_states',))
        self.assertTrue(c.wait_connected())
        self.assertIsNotNone(c.go_clear())
        report = c.publish_until(lambda: c.publish_pose(LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT),
                                 lambda r: len(r.warnings) > 0)
        self.assertIsNotNone(report)
        self.assertTrue(report.stop)
        self.assertEqual(report.input_status, MonitorReport.INPUT_OK)

    def test_16b_fixed_rate_cycles(self):
        """A node cycling at ~cycle_rate_hz (20 Hz) on one combined topic: the messages between
        two ticks make one cycle, whose report carries the newest accepted stamp, or a refused
        message's with its refusal."""
        c = MonitorClient('/timed_monitor', topics=('timed_joint_states',))
        self.assertTrue(c.wait_connected())
        self.assertIsNotNone(c.go_clear())
        names = LEFT_JOINTS + RIGHT_JOINTS
        base = rospy.Time.now()
        stamps = [base + rospy.Duration(0, 1000 * k) for k in range(1, 11)]
        start = c.report_count()
        for stamp in stamps:
            c.publishers[0].publish(joint_state(names, HOME + HOME, stamp))
        newest = c.wait_report(start, lambda r: r.header.stamp == stamps[-1])
        self.assertIsNotNone(newest, 'no report stamped with the newest message')
        self.assertEqual(newest.input_status, MonitorReport.INPUT_OK)
        # Ten messages within about a millisecond: fewer reports on them than messages (one per
        # message only if each came in a tick of its own, 50 ms apart).
        sent = set((s.secs, s.nsecs) for s in stamps)
        on_burst = [r for r in c.reports_since(start)
                    if (r.header.stamp.secs, r.header.stamp.nsecs) in sent]
        self.assertLess(len(on_burst), len(stamps))
        # Stamped 1 ms before the message just before it: refused, the report carrying its
        # stamp (the two in one tick or in two).
        accepted_stamp = rospy.Time.now()
        refused_stamp = accepted_stamp - rospy.Duration(0.001)
        start = c.report_count()
        c.publishers[0].publish(joint_state(names, HOME + HOME, accepted_stamp))
        c.publishers[0].publish(joint_state(names, HOME + HOME, refused_stamp))
        refused = c.wait_report(start, lambda r: r.header.stamp == refused_stamp)
        self.assertIsNotNone(refused, 'no report stamped with the refused message')
        self.assertEqual(refused.input_status, MonitorReport.INPUT_STAMP_BACKWARDS)
        self.assertTrue(refused.stop)
        later = rospy.Time.now()
        start = c.report_count()
        c.publishers[0].publish(joint_state(names, HOME + HOME, later))
        accepted = c.wait_report(start, lambda r: r.header.stamp == later)
        self.assertIsNotNone(accepted, 'no report stamped with the accepted message after it')
        self.assertEqual(accepted.input_status, MonitorReport.INPUT_OK)
        # A reading outside the joint limits (the merger passes it, the Monitor refuses it),
        # then good ones within the same tick: the bad reading was overwritten before the
        # timer's cycle, and lost. Its cycle runs at once: refused, a stop.
        bad = list(HOME)
        bad[1] = 5.0  # left_joint2, limits +-2.094 rad
        bad_stamp = rospy.Time.now()
        start = c.report_count()
        c.publishers[0].publish(joint_state(names, bad + HOME, bad_stamp))
        for k in range(1, 4):
            c.publishers[0].publish(joint_state(names, HOME + HOME,
                                                bad_stamp + rospy.Duration(0, 1000 * k)))
        refused = c.wait_report(start, lambda r: r.header.stamp == bad_stamp)
        self.assertIsNotNone(refused, 'no report on the reading outside the joint limits')
        self.assertEqual(refused.input_status, MonitorReport.INPUT_OUT_OF_LIMITS)
        self.assertTrue(refused.stop)

    def test_17_lost_object_frame_requests_stop(self):
        """A node whose fixed frame is not connected to the camera's TF frame cannot place the
        frame-bound camera: stop, naming the object, even on good input."""
        c = MonitorClient('/frameless_monitor')
        self.assertTrue(c.wait_connected())
        report = c.publish_until(lambda: c.publish_pose(HOME, HOME),
                                 lambda r: r.input_status == MonitorReport.INPUT_OK)
        self.assertIsNotNone(report)
        self.assertTrue(report.stop)
        self.assertIn("object 'camera'", report.stop_reason)

    def assert_camera_stop(self, node, needle):
        """Good input to `node` gets (once its TF has come) a stop naming the frame-bound camera
        and `needle`."""
        c = MonitorClient(node)
        self.assertTrue(c.wait_connected())
        report = c.publish_until(lambda: c.publish_pose(HOME, HOME),
                                 lambda r: r.input_status == MonitorReport.INPUT_OK and r.stop)
        self.assertIsNotNone(report, '%s: no stop on good input' % node)
        self.assertIn("object 'camera'", report.stop_reason)
        self.assertIn(needle, report.stop_reason)

    def test_17b_fixed_frame_apart_from_the_root_stops(self):
        """A fixed frame that TF puts apart from the URDF root (odom, 0.8 m from world) would
        misplace every pose looked up in it or given in it: the frame-bound camera (a stop naming
        it and the offset, even on good input), a live object in a TF frame, in the fixed frame
        or in no frame (refused); the Safety diagnostics say so (reports and markers carry the
        fixed frame's name on the root's coordinates); a pose in the root's own frame is taken
        as it is."""
        offset = "the fixed frame 'odom' is 0.8 m and 0 rad from the URDF root 'world' in TF"
        self.assert_camera_stop('/offset_monitor', offset)
        rospy.wait_for_service('/offset_monitor/add_object', timeout=20.0)
        add = rospy.ServiceProxy('/offset_monitor/add_object', AddObject)
        far = Pose(position=Point(x=3.0, y=0.0, z=3.0), orientation=Quaternion(w=1.0))
        for frame in ('camera_link', 'odom', ''):
            res = add(name='drum', type='sphere', dimensions_m=[0.05], frame=frame, pose=far)
            self.assertFalse(res.success, 'added in %r through the offset fixed frame' % frame)
            self.assertEqual(res.message, "add_object 'drum': " + offset +
                             " (fixed_frame only renames the root's frame: leave it empty)")
        res = add(name='drum', type='sphere', dimensions_m=[0.05], frame='world', pose=far)
        self.assertTrue(res.success, res.message)
        safety = []

        def on_diagnostics(msg):
            safety.extend(s for s in msg.status if s.name == 'offset_monitor: Safety')

        sub = rospy.Subscriber('/diagnostics', DiagnosticArray, on_diagnostics)
        deadline = time.time() + 10.0
        while time.time() < deadline and not safety:
            time.sleep(0.05)
        sub.unregister()
        self.assertTrue(safety, 'no Safety diagnostics from offset_monitor')
        self.assertEqual(safety[-1].level, DiagnosticStatus.ERROR)
        self.assertIn(offset, safety[-1].message)

    def test_17c_fixed_frame_unrelated_to_the_root_stops(self):
        """A fixed frame TF has in a tree apart from the URDF root's (a driver's tree not yet
        joined) may be anywhere: the frame-bound camera stops, naming it."""
        self.assert_camera_stop('/island_monitor', "TF has the fixed frame 'island' and the URDF "
                                "root 'world' but does not relate them")

    def test_18_diagnostics(self):
        c = self.client
        self.assertIsNotNone(c.go_clear())
        statuses = {}

        def on_diagnostics(msg):
            for status in msg.status:
                statuses[status.name] = dict((kv.key, kv.value) for kv in status.values)

        sub = rospy.Subscriber('/diagnostics', DiagnosticArray, on_diagnostics)
        prefix = NODE.strip('/') + ': '
        deadline = time.time() + 10.0
        while time.time() < deadline and not all(
                prefix + n in statuses for n in ('Input', 'Cycle', 'Safety')):
            c.publish_pose(HOME, HOME)
            time.sleep(0.05)
        sub.unregister()
        for name in ('Input', 'Cycle', 'Safety'):
            self.assertIn(prefix + name, statuses)
        inputs = statuses[prefix + 'Input']
        cycle = statuses[prefix + 'Cycle']
        # The earlier tests refused messages of several kinds and made the input go stale.
        self.assertGreater(int(inputs['refused (total)']), 0)
        self.assertGreater(int(inputs['refused: non_finite']), 0)
        # Each refusal is in one category (test_08 refused a message stamped too long ago).
        self.assertGreater(int(inputs['refused: stale']), 0)
        self.assertEqual(sum(int(v) for k, v in inputs.items() if k.startswith('refused: ')),
                         int(inputs['refused (total)']), inputs)
        self.assertGreater(int(inputs['unknown joint names (total)']), 0)
        # The bundled workcell has no mimic joint: none counted apart.
        self.assertEqual(inputs['mimic joint names, ignored (total)'], '0')
        self.assertGreaterEqual(int(inputs['position-less messages (ignored)']), 5)
        self.assertGreater(int(inputs['stale episodes']), 0)
        self.assertIn('message rate (Hz)', inputs)
        # The go-clear messages, stamped when sent, were accepted: their ages at arrival, from
        # transport alone here (well under a second), ordered as percentiles are.
        self.assertGreater(int(inputs['stamped messages in the age window']), 0)
        median_ms = float(inputs['message age at arrival median (ms)'])
        p99_ms = float(inputs['message age at arrival p99 (ms)'])
        max_ms = float(inputs['message age at arrival max (ms)'])
        self.assertGreaterEqual(median_ms, 0.0)
        self.assertLess(median_ms, 1000.0)
        self.assertLessEqual(median_ms, p99_ms)
        self.assertLessEqual(p99_ms, max_ms)
        self.assertGreater(int(cycle['re-insert fallbacks (total)']), 0)
        self.assertGreater(float(cycle['cycle time p99 (us)']), 0.0)


if __name__ == '__main__':
    rostest.rosrun('arm_collision_monitor', 'input_faults', InputFaultsTest, sys.argv)
