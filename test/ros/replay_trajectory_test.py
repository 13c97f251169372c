#!/usr/bin/python3
"""replay checks planned paths (test/ros/replay_trajectory.test). A bag of
trajectory_msgs/JointTrajectory: each point a sample at header.stamp (the bag's time when 0)
plus its time_from_start. The seed's task 2, written as one trajectory of both arms, replays as
the same cycles, times and warnings as its recording of sensor_msgs/JointState; every tenth
point alone (a sparse plan) still warns every pair the dense run warns; a plan of two points
warns, between them, a pair that neither point comes near (the swept check); a plan of one arm
joins the other arm's state recorded at its start; plans of each arm replay side by side, in
time order, each arm moving between its points while the other's points come (a millisecond
apart, they warn what one plan of both arms warns); a later plan supersedes, for its joints, an
earlier one's points after its start; a bag of both recorded states and plans of the same joints
is refused unless --topic picks one; a point of the wrong size or whose stamp is out of
ros::Time's range is refused and counted, the others replay; times that do not increase, or a
position not finite, are an error naming the message, the point and the joint. MoveIt's display
of a plan (moveit_msgs/DisplayTrajectory, written raw with the definition a bag carries, as this
machine has no moveit_msgs) replays as its recording in either layout of RobotTrajectory, a plan
of one arm taking the other from its start state; one cut short or whose definition differs from
this build's is an error naming the bag, the message and the field. The goal sent to a
trajectory controller (control_msgs/FollowJointTrajectoryActionGoal, written raw the same way)
replays as its recording too, and one cut short is such an error."""
import io
import json
import math
import os
import shutil
import struct
import tempfile
import unittest

import rosbag
import rospkg
import rospy
import rostest
from sensor_msgs.msg import JointState, MultiDOFJointState
from geometry_msgs.msg import Transform
from std_msgs.msg import Header
from trajectory_msgs.msg import (JointTrajectory, JointTrajectoryPoint, MultiDOFJointTrajectory,
                                 MultiDOFJointTrajectoryPoint)

from acm_test_util import (LEFT_JOINTS, LEFT_TOWARDS_RIGHT, RIGHT_JOINTS, RIGHT_TOWARDS_LEFT,
                           rosrun)

PKG = 'arm_collision_monitor'


def both_arm_samples(bag_path):
    """[(stamp, positions in LEFT_JOINTS + RIGHT_JOINTS order)] of a recording of both arms whose
    two messages of a cycle share their stamp."""
    by_stamp = {}
    with rosbag.Bag(bag_path) as bag:
        for _, msg, _ in bag.read_messages():
            by_stamp.setdefault(msg.header.stamp, {}).update(zip(msg.name, msg.position))
    return [(stamp, [joints[name] for name in LEFT_JOINTS + RIGHT_JOINTS])
            for stamp, joints in sorted(by_stamp.items())]


def write_plan(path, samples, bad_points=()):
    """One JointTrajectory of both arms with the samples as points, header.stamp 0 (MoveIt's
    'start now'), recorded at the first sample's time; `bad_points` are appended after them."""
    start = samples[0][0]
    plan = trajectory_of(samples, slice(0, 14), start)
    plan.points.extend(bad_points)
    with rosbag.Bag(path, 'w') as bag:
        bag.write('/move_group/planned_path', plan, start)


# moveit_msgs/DisplayTrajectory without moveit_msgs: the definition a bag carries for it (the
# type's fields, then each type it uses after a separator line), written from moveit_msgs' .msg
# files; `group_name` is in RobotTrajectory from MoveIt 1.1 on. AttachedCollisionObject is
# abridged to three of its fields: the reader skips it by whatever definition the bag gives.
SEPARATOR = '=' * 80 + '\n'
MOVEIT_DEFINITIONS = {
    'moveit_msgs/DisplayTrajectory':
        '# The model id\nstring model_id\nRobotTrajectory[] trajectory\n'
        'RobotState trajectory_start\n',
    'moveit_msgs/RobotTrajectory':
        'trajectory_msgs/JointTrajectory joint_trajectory\n'
        'trajectory_msgs/MultiDOFJointTrajectory multi_dof_joint_trajectory\n',
    'moveit_msgs/RobotState':
        'sensor_msgs/JointState joint_state\nsensor_msgs/MultiDOFJointState multi_dof_joint_state\n'
        'AttachedCollisionObject[] attached_collision_objects\nbool is_diff\n',
    'moveit_msgs/AttachedCollisionObject':
        'string link_name\nstring[] touch_links\nfloat64 weight\n',
}


def sections(main_type, full_text):
    """{type: its own fields} of a generated message's full definition text."""
    parts = full_text.split(SEPARATOR)
    found = {main_type: parts[0]}
    for part in parts[1:]:
        first, _, body = part.partition('\n')
        found[first[len('MSG: '):].strip()] = body
    return found


def display_definition(group_name, joint_trajectory_text=None):
    definitions = dict(MOVEIT_DEFINITIONS)
    if group_name:
        definitions['moveit_msgs/RobotTrajectory'] += 'string group_name\n'
    for main_type, cls in (('trajectory_msgs/JointTrajectory', JointTrajectory),
                           ('trajectory_msgs/MultiDOFJointTrajectory', MultiDOFJointTrajectory),
                           ('sensor_msgs/JointState', JointState),
                           ('sensor_msgs/MultiDOFJointState', MultiDOFJointState)):
        definitions.update(sections(main_type, cls._full_text))
    if joint_trajectory_text is not None:
        definitions['trajectory_msgs/JointTrajectoryPoint'] = joint_trajectory_text
    main = definitions.pop('moveit_msgs/DisplayTrajectory')
    return main + ''.join('%sMSG: %s\n%s' % (SEPARATOR, name, body)
                          for name, body in definitions.items())


def serialized_string(text):
    data = text.encode()
    return struct.pack('<I', len(data)) + data


def display_bytes(trajectories, start_state, group_name, multi_dof=None, start_multi_dof=None):
    """A DisplayTrajectory serialized by display_definition(group_name), with one attached
    object in its start state; `multi_dof` (a MultiDOFJointTrajectory) beside each trajectory,
    `start_multi_dof` (a MultiDOFJointState) in the start state, else empty ones."""
    buff = io.BytesIO()
    buff.write(serialized_string('dual_arm'))
    buff.write(struct.pack('<I', len(trajectories)))
    for trajectory in trajectories:
        trajectory.serialize(buff)
        (multi_dof or MultiDOFJointTrajectory()).serialize(buff)
        if group_name:
            buff.write(serialized_string('both_arms'))
    start_state.serialize(buff)
    (start_multi_dof or MultiDOFJointState()).serialize(buff)
    buff.write(struct.pack('<I', 1) + serialized_string('left_link7') + struct.pack('<I', 2) +
               serialized_string('left_link6') + serialized_string('left_link5') +
               struct.pack('<d', 0.5))
    buff.write(struct.pack('<B', 0))  # is_diff
    return buff.getvalue()


class RawType:
    """What rosbag's raw write needs of a message class it does not have."""
    _md5sum = '*'


def write_raw(path, topic, msg_type, data, definition, recorded_at):
    """A bag of one message of `msg_type`, serialized as `data` by `definition`."""
    header = {'topic': topic, 'type': msg_type, 'md5sum': '*', 'message_definition': definition}
    with rosbag.Bag(path, 'w') as bag:
        bag.write(topic, (msg_type, data, '*', RawType), recorded_at, raw=True,
                  connection_header=header)


def write_display(path, data, definition, recorded_at):
    write_raw(path, '/move_group/display_planned_path', 'moveit_msgs/DisplayTrajectory', data,
              definition, recorded_at)


# control_msgs/FollowJointTrajectoryActionGoal, from control_msgs' and actionlib_msgs' .msg files
# (this machine has neither package).
FOLLOW_GOAL_DEFINITIONS = {
    'actionlib_msgs/GoalID': 'time stamp\nstring id\n',
    'control_msgs/FollowJointTrajectoryGoal':
        'trajectory_msgs/JointTrajectory trajectory\nJointTolerance[] path_tolerance\n'
        'JointTolerance[] goal_tolerance\nduration goal_time_tolerance\n',
    'control_msgs/JointTolerance':
        'string name\nfloat64 position\nfloat64 velocity\nfloat64 acceleration\n',
}


def follow_goal(trajectory):
    """(definition, bytes) of a FollowJointTrajectoryActionGoal carrying `trajectory`."""
    definitions = dict(FOLLOW_GOAL_DEFINITIONS)
    definitions.update(sections('trajectory_msgs/JointTrajectory', JointTrajectory._full_text))
    definition = ('Header header\nactionlib_msgs/GoalID goal_id\nFollowJointTrajectoryGoal goal\n' +
                  ''.join('%sMSG: %s\n%s' % (SEPARATOR, name, body)
                          for name, body in definitions.items()))
    buff = io.BytesIO()
    Header(frame_id='').serialize(buff)
    buff.write(struct.pack('<II', 5, 0) + serialized_string('goal-1'))
    trajectory.serialize(buff)
    buff.write(struct.pack('<IIii', 0, 0, 0, 0))  # no tolerances, goal_time_tolerance 0
    return definition, buff.getvalue()


def pose_along_y(y):
    """A geometry_msgs/Transform `y` m along y, not turned."""
    transform = Transform()
    transform.translation.y = y
    transform.rotation.w = 1.0
    return transform


def trajectory_of(samples, joints, start):
    """The samples' positions of `joints` (a slice of LEFT_JOINTS + RIGHT_JOINTS) from `start`."""
    plan = JointTrajectory(joint_names=(LEFT_JOINTS + RIGHT_JOINTS)[joints])
    for stamp, positions in samples:
        plan.points.append(JointTrajectoryPoint(positions=positions[joints],
                                                time_from_start=stamp - start))
    return plan


class ReplayTrajectoryTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        package = rospkg.RosPack().get_path(PKG)
        cls.recording = os.path.join(package, 'test', 'bags', 'task2.bag')
        cls.recording_task3 = os.path.join(package, 'test', 'bags', 'task3.bag')
        cls.samples = both_arm_samples(cls.recording)
        cls.directory = tempfile.mkdtemp(prefix='acm_replay_trajectory_')
        cls.addClassCleanup(shutil.rmtree, cls.directory, True)

    @staticmethod
    def replay(bag_path):
        result = rosrun('replay', '--task', '2', '--json', bag_path)
        return result, (json.loads(result.stdout) if result.returncode == 0 else None)

    @staticmethod
    def warned_pairs(report, key):
        return [sorted((w[0], w[1]) for w in cycle[key]) for cycle in report['per_cycle']]

    def assert_same_cycles(self, report, expected):
        """`report` has `expected`'s cycle times and warned pairs."""
        self.assertEqual([c['time_s'] for c in report['per_cycle']],
                         [c['time_s'] for c in expected['per_cycle']])
        self.assertEqual(self.warned_pairs(report, 'warnings'),
                         self.warned_pairs(expected, 'warnings'))

    def test_a_plan_replays_as_its_recording(self):
        recorded, recorded_report = self.replay(self.recording)
        self.assertEqual(recorded.returncode, 0, recorded.stderr)
        plan_path = os.path.join(self.directory, 'plan.bag')
        write_plan(plan_path, self.samples)
        planned, report = self.replay(plan_path)
        self.assertEqual(planned.returncode, 0, planned.stderr)
        self.assertEqual(len(self.samples), 150)
        self.assertEqual(report['cycles'], 150)
        self.assertEqual(report['messages'], 150)  # one sample a point
        self.assertEqual(report['refused_messages'], {})
        self.assertEqual(report['incomplete_cycles'], 0)
        self.assertGreater(recorded_report['warning_cycles'], 0)
        self.assert_same_cycles(report, recorded_report)
        self.assertEqual(self.warned_pairs(report, 'between_samples'),
                         self.warned_pairs(recorded_report, 'between_samples'))

    def test_a_sparse_plan_still_warns_every_pair(self):
        _, dense = self.replay(self.recording)
        sparse_path = os.path.join(self.directory, 'sparse.bag')
        write_plan(sparse_path, self.samples[::10])
        result, sparse = self.replay(sparse_path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(sparse['cycles'], 15)
        dense_pairs = {pair for cycle in self.warned_pairs(dense, 'warnings') for pair in cycle}
        at_samples = {pair for cycle in self.warned_pairs(sparse, 'warnings') for pair in cycle}
        between = {pair for cycle in self.warned_pairs(sparse, 'between_samples')
                   for pair in cycle}
        self.assertTrue(dense_pairs)
        self.assertEqual(dense_pairs - (at_samples | between), set())

    def test_what_lies_between_two_points_is_warned(self):
        # Task 3's right arm at a pose beside front_box (its cycle 515: right_link7 touches the
        # table), planned from right_joint1 - 0.6 rad to + 0.6 rad in one step: at both points it
        # touches the table only; on the way right_link6 sweeps through front_box.
        stamp, pose = both_arm_samples(self.recording_task3)[515]
        joint = (LEFT_JOINTS + RIGHT_JOINTS).index('right_joint1')
        start, end = list(pose), list(pose)
        start[joint] -= 0.6
        end[joint] += 0.6
        path = os.path.join(self.directory, 'two_points.bag')
        write_plan(path, [(stamp, start), (stamp + rospy.Duration(1.0), end)])
        result = rosrun('replay', '--task', '3', '--json', path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual(report['cycles'], 2)
        for cycle in report['per_cycle']:
            self.assertEqual([(w[0], w[1]) for w in cycle['warnings']],
                             [('right_link7', 'front_table_top')])
        between = report['per_cycle'][1]['between_samples']
        self.assertEqual([(w[0], w[1]) for w in between], [('right_link6', 'front_box')])
        self.assertTrue(0.0 < between[0][3] < 1.0, between)  # the step fraction

    def test_a_one_arm_plan_starts_where_the_other_arm_was_recorded(self):
        # The right arm's state at the plan's start, then a plan of the left arm alone: the
        # plan's first point has the state's stamp (header.stamp 0: the time the bag recorded
        # the plan; or header.stamp itself, recorded later), so the two make the first cycle.
        start = self.samples[0][0]
        for header_stamp, recorded_at in ((rospy.Time(0), start),
                                          (start, start + rospy.Duration(5.0))):
            state = JointState(name=RIGHT_JOINTS, position=self.samples[0][1][7:])
            state.header.stamp = start
            plan = JointTrajectory(joint_names=LEFT_JOINTS)
            plan.header.stamp = header_stamp
            for stamp, positions in self.samples[:20]:
                plan.points.append(JointTrajectoryPoint(positions=positions[:7],
                                                        time_from_start=stamp - start))
            path = os.path.join(self.directory, 'left_plan.bag')
            with rosbag.Bag(path, 'w') as bag:
                # recorded just before the plan (a bag need not keep the order of equal times)
                bag.write('/right_arm/joint_states', state, start - rospy.Duration(0.01))
                bag.write('/move_group/planned_path', plan, recorded_at)
            result, report = self.replay(path)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertEqual(report['messages'], 21)
            self.assertEqual(report['incomplete_cycles'], 0, header_stamp)
            self.assertEqual(report['cycles'], 20, header_stamp)
            self.assertEqual(report['refused_messages'], {})

    def test_two_one_arm_plans_replay_side_by_side(self):
        # Task 2 as a plan of each arm, recorded one after the other with the same start: their
        # points are taken in time order, not all the left arm's first.
        _, recorded = self.replay(self.recording)
        start = self.samples[0][0]
        path = os.path.join(self.directory, 'two_plans.bag')
        with rosbag.Bag(path, 'w') as bag:
            for joints in (slice(0, 7), slice(7, 14)):
                bag.write('/move_group/planned_path', trajectory_of(self.samples, joints, start),
                          start)
        result, report = self.replay(path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual((report['messages'], report['cycles']), (300, 150))
        self.assertEqual((report['superseded_points'], report['incomplete_cycles']), (0, 0))
        self.assert_same_cycles(report, recorded)

    def test_one_arm_plans_a_millisecond_apart_move_both_arms_at_once(self):
        # Each arm swings joint 1 by 2 rad through the pose where the arms lean into each other,
        # as one plan of both arms and as a plan of each arm whose points come 1 ms after the
        # other's (a Kinova Gen3 user's plans missed 4 of 21 pairs). Taken as a staircase, one
        # arm moving while the other waits at its last point, the arms never meet.
        def swing(pose, way):
            return [[pose[0] - way] + pose[1:], [pose[0] + way] + pose[1:]]

        def plan(names, points, offset_s):
            trajectory = JointTrajectory(joint_names=names)
            for k, positions in enumerate(points):
                trajectory.points.append(JointTrajectoryPoint(
                    positions=positions, time_from_start=rospy.Duration(2.0 * k + offset_s)))
            return trajectory

        left, right = swing(LEFT_TOWARDS_RIGHT, 1.0), swing(RIGHT_TOWARDS_LEFT, -1.0)
        start = rospy.Time(100)
        both_path = os.path.join(self.directory, 'both_arms.bag')
        with rosbag.Bag(both_path, 'w') as bag:
            bag.write('/plan', plan(LEFT_JOINTS + RIGHT_JOINTS,
                                    [l + r for l, r in zip(left, right)], 0.0), start)
        apart_path = os.path.join(self.directory, 'one_arm_each.bag')
        with rosbag.Bag(apart_path, 'w') as bag:
            bag.write('/plan', plan(LEFT_JOINTS, left, 0.0), start)
            bag.write('/plan', plan(RIGHT_JOINTS, right, 0.001), start)

        def warned(path):
            result = rosrun('replay', '--json', path)
            self.assertEqual(result.returncode, 0, result.stderr)
            return {(w[0], w[1]) for cycle in json.loads(result.stdout)['per_cycle']
                    for w in cycle['warnings'] + cycle['between_samples']}

        both = warned(both_path)
        self.assertIn(('left_link7', 'right_link7'), both)
        self.assertEqual(warned(apart_path), both)

    def test_times_that_do_not_increase_or_a_position_not_finite_are_errors(self):
        for name, times, bad_joint in (('backwards', (0.0, 1.5, 1.0), None),
                                       ('not_finite', (0.0, 1.0, 2.0), 1)):
            trajectory = JointTrajectory(joint_names=LEFT_JOINTS)
            for k, t in enumerate(times):
                positions = [0.1 * k] * 7
                if k == 1 and bad_joint is not None:
                    positions[bad_joint] = float('nan')
                trajectory.points.append(JointTrajectoryPoint(
                    positions=positions, time_from_start=rospy.Duration(t)))
            path = os.path.join(self.directory, name + '.bag')
            with rosbag.Bag(path, 'w') as bag:
                bag.write('/left/plan', trajectory, rospy.Time(100))
            result = rosrun('replay', '--json', path)
            self.assertEqual(result.returncode, 1, result.stdout)
            where = ('%s: trajectory_msgs/JointTrajectory on /left/plan at bag time 100.000000, '
                     % path)
            if bad_joint is None:
                self.assertIn(where + 'point 2: time_from_start 1.000000 s does not increase past '
                              'the point before it (1.500000 s)', result.stderr)
            else:
                self.assertIn(where + "point 1: joint 'left_joint2' at nan", result.stderr)

    def test_joints_never_given_are_explained_by_what_the_plans_held(self):
        # A plan of both arms with one joint misspelt, and an empty one (a Kinova Gen3 user read
        # only which model joints were missing).
        names = LEFT_JOINTS + RIGHT_JOINTS
        names[2] = 'left_joint_3'
        plan = JointTrajectory(joint_names=names)
        plan.points.append(JointTrajectoryPoint(positions=[0.0] * 14,
                                                time_from_start=rospy.Duration(0.0)))
        path = os.path.join(self.directory, 'misspelt.bag')
        with rosbag.Bag(path, 'w') as bag:
            bag.write('/plan', plan, rospy.Time(100))
            bag.write('/plan', JointTrajectory(joint_names=LEFT_JOINTS), rospy.Time(101))
        result = rosrun('replay', '--json', path)
        self.assertEqual(result.returncode, 1, result.stdout)
        self.assertIn("gives model joint 'left_joint3' (", result.stderr)
        self.assertIn("; the input gives these names that are no joints of the model: "
                      "'left_joint_3' (publish the model's joint names); 1 of the 2 "
                      "trajectories read have no points", result.stderr)

    def test_a_later_plan_supersedes_an_earlier_one_after_its_start(self):
        # Task 2 as one plan of both arms; then, from its cycle 50 on, a plan that holds the left
        # arm at its pose there, with a point every 0.5 s. The left arm's points of the first plan
        # after that start go (its right arm's stay): the run is the one of task 2 with the left
        # arm stopped at cycle 50, which never reaches the table (cycles 108 on in task 2).
        _, recorded = self.replay(self.recording)
        self.assertIn(['left_link7', 'front_table_top'],
                      [[w[0], w[1]] for w in recorded['per_cycle'][108]['warnings']])
        cut = 50
        held = self.samples[cut][1][:7]
        stopped = [(stamp, (held if k > cut else positions[:7]) + positions[7:])
                   for k, (stamp, positions) in enumerate(self.samples)]
        expected_path = os.path.join(self.directory, 'stopped.bag')
        write_plan(expected_path, stopped)
        _, expected = self.replay(expected_path)
        start, cut_stamp = self.samples[0][0], self.samples[cut][0]
        hold = JointTrajectory(joint_names=LEFT_JOINTS)
        hold.header.stamp = cut_stamp
        for k in range(cut, len(self.samples), 10):
            hold.points.append(JointTrajectoryPoint(positions=held,
                                                    time_from_start=self.samples[k][0] - cut_stamp))
        path = os.path.join(self.directory, 'replanned.bag')
        with rosbag.Bag(path, 'w') as bag:
            bag.write('/move_group/planned_path', trajectory_of(self.samples, slice(0, 14), start),
                      start)
            bag.write('/move_group/planned_path', hold, cut_stamp)
        result, report = self.replay(path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(report['messages'], 150 + len(hold.points))
        self.assertEqual(report['superseded_points'], 150 - cut - 1)
        self.assertEqual(report['cycles'], 150)
        self.assert_same_cycles(report, expected)
        self.assertNotEqual(self.warned_pairs(report, 'warnings'),
                            self.warned_pairs(recorded, 'warnings'))

    def test_a_plan_cut_at_one_of_its_points_moves_its_other_arm_on(self):
        # Both arms swing towards each other in one plan (points at 0, 10 and 20 s, meeting
        # about 15 s); a plan of the right arm alone from exactly 10 s, a point of the first,
        # carries it on the same way. The left arm's rest of the first plan moves on from 10 s
        # with the new plan's cycles: at 15 s the arms warn (held at its 10 s pose until 20 s, it
        # warned only between samples). A plan of the left arm from 12 s then cuts that rest:
        # the first plan's points it drops were counted superseded once already.
        def plan(names, points, stamp):
            trajectory = JointTrajectory(joint_names=names)
            trajectory.header.stamp = stamp
            for t, positions in points:
                trajectory.points.append(JointTrajectoryPoint(positions=positions,
                                                              time_from_start=rospy.Duration(t)))
            return trajectory

        def left(turn):
            return [LEFT_TOWARDS_RIGHT[0] + turn] + LEFT_TOWARDS_RIGHT[1:]

        def right(turn):
            return [RIGHT_TOWARDS_LEFT[0] + turn] + RIGHT_TOWARDS_LEFT[1:]

        start = rospy.Time(100)
        path = os.path.join(self.directory, 'cut_at_point.bag')
        both = plan(LEFT_JOINTS + RIGHT_JOINTS, [(0, left(-2) + right(2)),
                                                 (10, left(-1) + right(1)),
                                                 (20, left(1) + right(-1))], start)
        cut = start + rospy.Duration(10)
        for is_left_cut, superseded in ((False, 1), (True, 1)):
            with rosbag.Bag(path, 'w') as bag:
                bag.write('/plan', both, start)
                carried_on = [(0, right(1)), (5, right(0)), (10, right(-1))]
                bag.write('/plan', plan(RIGHT_JOINTS, carried_on, cut), cut)
                if is_left_cut:
                    later = start + rospy.Duration(17)
                    bag.write('/plan', plan(LEFT_JOINTS, [(1, left(0.4))], later), later)
            result = rosrun('replay', '--json', path)
            self.assertEqual(result.returncode, 0, result.stderr)
            report = json.loads(result.stdout)
            self.assertEqual(report['superseded_points'], superseded, is_left_cut)
            at_15 = [c for c in report['per_cycle'] if round(c['time_s'], 6) == 15.0]
            self.assertEqual(len(at_15), 1)
            self.assertTrue(any(w[0].startswith('left_link') and w[1].startswith('right_link')
                                for w in at_15[0]['warnings']), at_15[0]['warnings'])

    def test_states_and_plans_of_the_same_joints_need_a_topic(self):
        # What `rosbag record -a` keeps of a robot: its joint states and the plan it was sent.
        # Both give the same joints; replay asks which to check, and checks either.
        _, recorded = self.replay(self.recording)
        start = self.samples[0][0]
        path = os.path.join(self.directory, 'states_and_plan.bag')
        with rosbag.Bag(path, 'w') as bag, rosbag.Bag(self.recording) as states:
            bag.write('/move_group/planned_path', trajectory_of(self.samples, slice(0, 14), start),
                      start)
            for topic, msg, t in states.read_messages():
                bag.write(topic, msg, t)
        result, _ = self.replay(path)
        self.assertEqual(result.returncode, 1)
        self.assertRegex(result.stderr,
                         r"states_and_plan.bag: joint '(left|right)_joint1' has both recorded "
                         r'states \(sensor_msgs/JointState on (left|right)_arm/joint_states\) and '
                         r'planned paths \(on /move_group/planned_path\): replay one of them with '
                         r'--topic')
        for topics, messages in ((['/move_group/planned_path'], 150),
                                 (['left_arm/joint_states', 'right_arm/joint_states'], 300)):
            args = [arg for topic in topics for arg in ('--topic', topic)]
            result = rosrun('replay', '--task', '2', '--json', *args, path)
            self.assertEqual(result.returncode, 0, result.stderr)
            report = json.loads(result.stdout)
            self.assertEqual((report['messages'], report['cycles']), (messages, 150))
            self.assert_same_cycles(report, recorded)
        result = rosrun('replay', '--topic', '/no_such_topic', path)
        self.assertEqual(result.returncode, 1)
        self.assertIn('states_and_plan.bag: --topic /no_such_topic: no sensor_msgs/JointState, '
                      'trajectory_msgs/JointTrajectory, moveit_msgs/DisplayTrajectory, '
                      'control_msgs/FollowJointTrajectoryActionGoal or '
                      'moveit_msgs/ExecuteTrajectoryActionGoal message on it', result.stderr)
        csv_path = os.path.join(self.directory, 'plan.csv')
        with open(csv_path, 'w') as csv:
            csv.write(','.join(LEFT_JOINTS + RIGHT_JOINTS) + '\n')
            csv.write(','.join(str(x) for x in self.samples[0][1]) + '\n')
        result = rosrun('replay', '--topic', '/move_group/planned_path', csv_path)
        self.assertEqual(result.returncode, 1)
        self.assertIn("--topic selects a bag's topics; %s is a CSV file" % csv_path,
                      result.stderr)

    def test_a_trajectory_controller_goal_replays_as_its_recording(self):
        # Task 2 as the goal MoveIt sends a trajectory controller (its trajectory's header.stamp
        # 0: it starts when the goal is recorded).
        _, recorded = self.replay(self.recording)
        start = self.samples[0][0]
        definition, data = follow_goal(trajectory_of(self.samples, slice(0, 14), start))
        path = os.path.join(self.directory, 'follow_goal.bag')
        write_raw(path, '/arm_controller/follow_joint_trajectory/goal',
                  'control_msgs/FollowJointTrajectoryActionGoal', data, definition, start)
        result, report = self.replay(path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual((report['messages'], report['cycles']), (150, 150))
        self.assert_same_cycles(report, recorded)
        # Cut short: an error naming the message and the field.
        write_raw(path, '/arm_controller/follow_joint_trajectory/goal',
                  'control_msgs/FollowJointTrajectoryActionGoal', data[:-30], definition, start)
        result, _ = self.replay(path)
        self.assertEqual(result.returncode, 1)
        self.assertIn('follow_goal.bag: control_msgs/FollowJointTrajectoryActionGoal on '
                      '/arm_controller/follow_joint_trajectory/goal at bag time ', result.stderr)
        self.assertIn('the message ends early', result.stderr)

    def test_a_moveit_display_replays_as_its_recording(self):
        # Task 2 as move_group would display a plan of both arms in two trajectories (the second
        # timed from the first's end), its start state the first sample; both layouts of
        # RobotTrajectory.
        _, recorded = self.replay(self.recording)
        half = len(self.samples) // 2
        first = trajectory_of(self.samples[:half], slice(0, 14), self.samples[0][0])
        second = trajectory_of(self.samples[half:], slice(0, 14), self.samples[half - 1][0])
        start_state = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=self.samples[0][1])
        for group_name in (False, True):
            path = os.path.join(self.directory, 'display.bag')
            write_display(path, display_bytes([first, second], start_state, group_name),
                          display_definition(group_name), self.samples[0][0])
            result, report = self.replay(path)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertEqual(report['messages'], 151, group_name)  # the start state + points
            self.assertEqual(report['cycles'], 150, group_name)
            self.assertEqual(report['refused_messages'], {})
            self.assertEqual(report['incomplete_cycles'], 0)
            self.assert_same_cycles(report, recorded)

    def test_a_moveit_display_of_one_arm_takes_the_other_from_its_start_state(self):
        start_state = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=self.samples[0][1])
        left = trajectory_of(self.samples[:30], slice(0, 7), self.samples[0][0])
        path = os.path.join(self.directory, 'display_left.bag')
        write_display(path, display_bytes([left], start_state, True), display_definition(True),
                      self.samples[0][0])
        result, report = self.replay(path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual((report['cycles'], report['incomplete_cycles']), (30, 0))
        # Without its start state's right arm, the plan of the left arm is refused, naming them.
        left_state = JointState(name=LEFT_JOINTS, position=self.samples[0][1][:7])
        write_display(path, display_bytes([left], left_state, True), display_definition(True),
                      self.samples[0][0])
        result, _ = self.replay(path)
        self.assertEqual(result.returncode, 1)
        self.assertIn("trajectory point gives 7 model joints: 'right_joint1', 'right_joint2'",
                      result.stderr)

    def test_a_moveit_display_is_unwound_as_moveit_executes_it(self):
        # left_joint1 made continuous (no limits): MoveIt's display of a plan may give it
        # wrapped, 3.1 then 3.1 + 0.083 - 2 pi, which MoveIt unwinds before it executes the plan
        # (the short way). A plan of the right arm has a point between the two: there the left
        # arm is where its controller has it, on the short way, not halfway round the long way
        # (3.1 rad from its start in 0.05 s: an 'input jumped' stop, twice).
        urdf_path = self.continuous_joint1_urdf()
        start = rospy.Time(100)
        wrapped = 3.1 + 0.083 - 2.0 * math.pi
        left = JointTrajectory(joint_names=LEFT_JOINTS)
        for t, q1 in ((0.0, 3.1), (0.1, wrapped)):
            left.points.append(JointTrajectoryPoint(positions=[q1, 1.0, 0, 0, 0, 0, 0],
                                                    time_from_start=rospy.Duration(t)))
        start_state = JointState(name=LEFT_JOINTS + RIGHT_JOINTS,
                                 position=[3.1, 1.0] + [0.0] * 12)
        right = JointTrajectory(joint_names=RIGHT_JOINTS)
        right.header.stamp = start
        for t in (0.05, 0.1):
            right.points.append(JointTrajectoryPoint(positions=[0.0] * 7,
                                                     time_from_start=rospy.Duration(t)))
        path = os.path.join(self.directory, 'display_wrapped.bag')
        topic = '/move_group/display_planned_path'
        header = {'topic': topic, 'type': 'moveit_msgs/DisplayTrajectory', 'md5sum': '*',
                  'message_definition': display_definition(True)}
        with rosbag.Bag(path, 'w') as bag:
            bag.write(topic, ('moveit_msgs/DisplayTrajectory',
                              display_bytes([left], start_state, True), '*', RawType), start,
                      raw=True, connection_header=header)
            bag.write('/right/plan', right, start)
        result = self.replay_with(urdf_path, path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual([round(c['time_s'], 9) for c in report['per_cycle']], [0.0, 0.05, 0.1])
        self.assertEqual(report['jumped_cycles'], 0)

    def continuous_joint1_urdf(self):
        """The workcell's URDF with left_joint1 continuous (no position limits), written to the
        test's directory: its path."""
        with open(os.path.join(rospkg.RosPack().get_path(PKG), 'urdf', 'workcell.urdf')) as f:
            urdf = f.read()
        for old, new in (('<joint name="left_joint1" type="revolute">',
                          '<joint name="left_joint1" type="continuous">'),
                         ('<limit lower="-2.967060" upper="2.967060" velocity="1.0"',
                          '<limit velocity="1.0"')):
            self.assertIn(old, urdf)
            urdf = urdf.replace(old, new, 1)
        urdf_path = os.path.join(self.directory, 'continuous_joint1.urdf')
        with open(urdf_path, 'w') as f:
            f.write(urdf)
        return urdf_path

    @staticmethod
    def replay_with(urdf_path, bag_path):
        scene = os.path.join(rospkg.RosPack().get_path(PKG), 'config', 'scene.yaml')
        return rosrun('replay', '--json', '--urdf', urdf_path, '--scene', scene, bag_path)

    def test_a_raw_plan_turns_a_continuous_joint_as_its_positions_say(self):
        # A trajectory controller takes a plan's positions literally: left_joint1 (continuous,
        # 1 rad/s) from 2 to -2 rad turns through 0, past -pi/2, where the left arm points at the
        # right arm (RIGHT_TOWARDS_LEFT, held by its own plan), not the short way through pi.
        # Replay checks the turn it makes, a quarter turn or less a cycle (no 'input jumped'
        # stop for a step either way round within the velocity limit); to 2 pi - 2 it turns the
        # other way, clear of the right arm; 20 rad in 12 s in 13 steps. 400 rad in 12 s,
        # beyond the limit, whose short way (2.1 rad) is within it, in 255 steps too: its
        # passes by the right arm are checked (a single step a quarter turn on missed them).
        urdf_path = self.continuous_joint1_urdf()
        start = rospy.Time(100)
        path = os.path.join(self.directory, 'plan_turning.bag')
        for end_rad, steps, warns, jumps in ((-2.0, 3, True, False),
                                             (2.0 * math.pi - 2.0, 1, False, False),
                                             (22.0, 13, None, False),
                                             (402.0, 255, True, None)):
            self.write_turning_plan(path, start, end_rad)
            result = self.replay_with(urdf_path, path)
            self.assertEqual(result.returncode, 0, result.stderr)
            report = json.loads(result.stdout)
            # To the microsecond: the stamps put between are whole nanoseconds.
            self.assertEqual([round(c['time_s'], 6) for c in report['per_cycle']],
                             [round(12.0 * k / steps, 6) for k in range(steps + 1)], end_rad)
            if jumps is not None:
                self.assertEqual(report['jumped_cycles'] > 0, jumps, end_rad)
            self.assertEqual(report['messages'], 4)  # the points read, none put between
            met = [sorted(w[:2]) for c in report['per_cycle']
                   for w in c['warnings'] + c['between_samples']]
            arms_met = any(a.startswith('left_link') and b.startswith('right_link')
                           for a, b in met)
            if warns is not None:
                self.assertEqual(arms_met, warns, (end_rad, met))
        # A plan replacing the left arm's while it turns (at 9.9 s of a turn from 0 to 3.1 rad
        # in 10 s) starts where that one has it then, 3.07 rad, on to 4 rad: not from 0 rad,
        # over half a turn either way round within the limit (an 'input jumped' stop).
        with rosbag.Bag(path, 'w') as bag:
            for t0, points in ((0.0, ((0.0, 0.0), (10.0, 3.1))), (9.9, ((1.0, 4.0), (5.0, 5.0)))):
                left = JointTrajectory(joint_names=LEFT_JOINTS)
                left.header.stamp = start + rospy.Duration(t0)
                for t, q1 in points:
                    left.points.append(JointTrajectoryPoint(positions=[q1, 0.5, 0, 0, 0, 0, 0],
                                                            time_from_start=rospy.Duration(t)))
                bag.write('/left/plan', left, left.header.stamp)
            right = JointTrajectory(joint_names=RIGHT_JOINTS)
            right.header.stamp = start
            for t in (0.0, 30.0):
                right.points.append(JointTrajectoryPoint(positions=[0.0] * 7,
                                                         time_from_start=rospy.Duration(t)))
            bag.write('/right/plan', right, start)
        report = json.loads(self.replay_with(urdf_path, path).stdout)
        self.assertEqual([round(c['time_s'], 6) for c in report['per_cycle']],
                         [0.0, 9.9, 10.9, 14.9, 30.0])
        self.assertEqual((report['jumped_cycles'], report['superseded_points']), (0, 1))
        # A later plan naming the joint twice: its two points refused, not the points put
        # between them.
        self.write_turning_plan(path, start, 2.0, duration_s=1.0)
        twice = JointTrajectory(joint_names=LEFT_JOINTS + LEFT_JOINTS[:1])
        twice.header.stamp = start + rospy.Duration(1.0)
        for t, q1 in ((0.0, 2.0), (12.0, -2.0)):
            twice.points.append(JointTrajectoryPoint(positions=[q1, 0.5, 0, 0, 0, 0, 0, q1],
                                                     time_from_start=rospy.Duration(t)))
        with rosbag.Bag(path, 'a') as bag:
            bag.write('/left/plan', twice, twice.header.stamp)
        result = self.replay_with(urdf_path, path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(json.loads(result.stdout)['refused_messages'], {'wrong_size': 2})
        # 200,000 rad in 10^6 s (within the limit) needs over 100,000 points: refused.
        self.write_turning_plan(path, start, 2.0e5, duration_s=1.0e6)
        result = self.replay_with(urdf_path, path)
        self.assertEqual(result.returncode, 1)
        self.assertIn("/left/plan at bag time 100.000000, point 1: over 100000 points put between "
                      "the plans' points to follow continuous joints' turns", result.stderr)

    @staticmethod
    def write_turning_plan(path, start, end_rad, duration_s=12.0):
        """Plans of both arms over `duration_s`: the left arm's joint1 from 2 rad to `end_rad`,
        its shoulder at 0.5; the right arm held at RIGHT_TOWARDS_LEFT."""
        left = JointTrajectory(joint_names=LEFT_JOINTS)
        right = JointTrajectory(joint_names=RIGHT_JOINTS)
        for plan in (left, right):
            plan.header.stamp = start
        for t, q1 in ((0.0, 2.0), (duration_s, end_rad)):
            left.points.append(JointTrajectoryPoint(positions=[q1, 0.5, 0, 0, 0, 0, 0],
                                                    time_from_start=rospy.Duration(t)))
            right.points.append(JointTrajectoryPoint(positions=RIGHT_TOWARDS_LEFT,
                                                     time_from_start=rospy.Duration(t)))
        with rosbag.Bag(path, 'w') as bag:
            bag.write('/left/plan', left, start)
            bag.write('/right/plan', right, start)

    def test_a_moveit_display_moving_the_base_is_refused(self):
        # A mobile manipulator's plan: its multi-DOF part moves the SRDF's virtual joint (the
        # base) 0.4 m, or stands still 0.3 m from where its start state has it. The monitor's
        # robot stands on a fixed root, so replay cannot check it and says so, naming the
        # message and trajectory; the base standing still where it starts replays.
        start_state = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=self.samples[0][1])
        plan = trajectory_of(self.samples[:5], slice(0, 14), self.samples[0][0])
        path = os.path.join(self.directory, 'display_base.bag')

        for step_m, start_y, moved in ((0.4, 0.0, '0.4'), (0.0, 0.3, '0.3'), (0.0, 0.0, None)):
            base = MultiDOFJointTrajectory(joint_names=['virtual_joint'])
            for k in range(2):
                base.points.append(MultiDOFJointTrajectoryPoint(
                    transforms=[pose_along_y(k * step_m)], time_from_start=rospy.Duration(0.1 * k)))
            base_start = MultiDOFJointState(joint_names=['virtual_joint'],
                                            transforms=[pose_along_y(start_y)])
            write_display(path, display_bytes([plan], start_state, True, base, base_start),
                          display_definition(True), self.samples[0][0])
            result, report = self.replay(path)
            if moved is None:
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertEqual(report['cycles'], 5)
                continue
            self.assertEqual(result.returncode, 1, moved)
            self.assertIn('display_base.bag: moveit_msgs/DisplayTrajectory on '
                          '/move_group/display_planned_path at bag time ', result.stderr)
            self.assertIn(", trajectory 0: its multi_dof_joint_trajectory moves 'virtual_joint' "
                          'by up to %s m and 0 rad' % moved, result.stderr)
            self.assertIn('cannot check a plan that moves it', result.stderr)

    def test_a_moveit_display_must_start_where_the_scene_placed_the_robot(self):
        # The planning scene's objects in 'odom' (the frame a floating virtual joint moves the
        # robot in) are placed with the robot where its robot state puts the joint, 0.3 m along
        # y. A display starting there replays; one starting at odom's origin is refused, naming
        # the scene's line, as is one whose start state leaves the base out and whose base
        # trajectory stands at the origin.
        package = rospkg.RosPack().get_path(PKG)
        with open(os.path.join(package, 'config', 'scene.yaml')) as f:
            scene = f.read()
        files = {
            'mobile.srdf': '<robot name="workcell"><virtual_joint name="base_joint" '
                           'type="floating" parent_frame="odom" child_link="world"/></robot>\n',
            'mobile_ps.yaml':
                'robot_state:\n  multi_dof_joint_state:\n    joint_names: [base_joint]\n'
                '    transforms: [{translation: {x: 0, y: 0.3, z: 0}, '
                'rotation: {x: 0, y: 0, z: 0, w: 1}}]\n'
                'world:\n  collision_objects:\n    - {id: post, header: {frame_id: odom}, '
                'primitives: [{type: 1, dimensions: [0.1, 0.1, 0.1]}], '
                'primitive_poses: [{position: {x: 3, y: 3, z: 0.05}}]}\n',
            'mobile_scene.yaml': scene + '\nsrdf: mobile.srdf\nplanning_scene: mobile_ps.yaml\n',
        }
        for name, text in files.items():
            with open(os.path.join(self.directory, name), 'w') as f:
                f.write(text)
        start_state = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=self.samples[0][1])
        plan = trajectory_of(self.samples[:5], slice(0, 14), self.samples[0][0])
        path = os.path.join(self.directory, 'display_mobile.bag')

        placed = (r"from where \S+/mobile_ps\.yaml:4 \(robot_state\.multi_dof_joint_state\) "
                  r"places the robot; the monitor checks the arms against the planning scene's "
                  r"objects placed with the robot there")
        away = r"its start state puts 'base_joint' 0.3 m and 0 rad " + placed
        first = (r"trajectory 0: its multi_dof_joint_trajectory's first point puts 'base_joint' "
                 r"0.3 m and 0 rad " + placed)
        # A localised base's jitter (0.5 mm) passes.
        for start_y, base_y, error in ((0.3, 0.3, None), (0.3005, 0.3005, None),
                                       (None, 0.3005, None), (0.0, 0.3, away), (None, 0.0, first)):
            base = MultiDOFJointTrajectory(joint_names=['base_joint'])
            for k in range(2):
                base.points.append(MultiDOFJointTrajectoryPoint(
                    transforms=[pose_along_y(base_y)], time_from_start=rospy.Duration(0.1 * k)))
            base_start = MultiDOFJointState(
                joint_names=['base_joint'] if start_y is not None else [],
                transforms=[pose_along_y(start_y)] if start_y is not None else [])
            write_display(path, display_bytes([plan], start_state, True, base, base_start),
                          display_definition(True), self.samples[0][0])
            result = rosrun('replay', '--json', '--scene',
                            os.path.join(self.directory, 'mobile_scene.yaml'), path)
            if error is None:
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertEqual(json.loads(result.stdout)['cycles'], 5)
                continue
            self.assertEqual(result.returncode, 1, error)
            self.assertRegex(result.stderr, error)

    def test_an_unreadable_display_names_the_message_and_field(self):
        start_state = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=self.samples[0][1])
        plan = trajectory_of(self.samples[:5], slice(0, 14), self.samples[0][0])
        data = display_bytes([plan], start_state, False)
        path = os.path.join(self.directory, 'display_bad.bag')
        where = ('display_bad.bag: moveit_msgs/DisplayTrajectory on '
                 '/move_group/display_planned_path at bag time ')
        # Cut short inside the start state.
        write_display(path, data[:-40], display_definition(False), self.samples[0][0])
        result, _ = self.replay(path)
        self.assertEqual(result.returncode, 1)
        self.assertIn(where, result.stderr)
        self.assertIn('trajectory_start', result.stderr)
        self.assertIn('the message ends early', result.stderr)
        # A definition whose trajectory points differ from this build's.
        point = sections('trajectory_msgs/JointTrajectoryPoint',
                         JointTrajectoryPoint._full_text)['trajectory_msgs/JointTrajectoryPoint']
        write_display(path, data, display_definition(
            False, point.replace('float64[] positions', 'float32[] positions')),
            self.samples[0][0])
        result, _ = self.replay(path)
        self.assertEqual(result.returncode, 1)
        self.assertIn(where, result.stderr)
        self.assertIn('trajectory[0].joint_trajectory: trajectory_msgs/JointTrajectoryPoint is',
                      result.stderr)
        self.assertIn('in this build', result.stderr)

    def test_bad_points_are_refused_and_counted(self):
        short = JointTrajectoryPoint(positions=self.samples[-1][1][:7],
                                     time_from_start=rospy.Duration(100.0))
        before_time = JointTrajectoryPoint(positions=self.samples[-1][1],
                                           time_from_start=rospy.Duration(-2.0e9))
        # Velocities alone (a point may leave positions out): ignored and counted, not refused.
        velocities_only = JointTrajectoryPoint(velocities=[0.1] * 14,
                                               time_from_start=rospy.Duration(101.0))
        path = os.path.join(self.directory, 'bad_points.bag')
        write_plan(path, self.samples[:20], bad_points=[short, before_time, velocities_only])
        result, report = self.replay(path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(report['messages'], 23)
        self.assertEqual(report['position_less_messages'], 1)
        self.assertEqual(report['refused_messages'], {'wrong_size': 1, 'time_out_of_range': 1})
        self.assertEqual(report['cycles'], 20)  # refused points make no cycle
        # The first met (the earliest stamp) is named, with its message and point (a Reachy 2 user
        # found a refused point only counted): the point dated before the plan's start, read
        # after the short one.
        self.assertRegex(report['first_refused_message'],
                         r'^stamped -400000000\.000000 s: \S+/bad_points\.bag: '
                         r'trajectory_msgs/JointTrajectory on \S+ at bag time [0-9.]+, point 21: '
                         r'time_out_of_range \(time_from_start -2000000000\.000000 s from a start '
                         r'at [0-9.]+ s\)$')
        path = os.path.join(self.directory, 'short_point.bag')
        write_plan(path, self.samples[:20], bad_points=[short])
        result, report = self.replay(path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(report['first_refused_message'],
                         r', point 20: wrong_size \(7 positions for 14 joint names\)$')
        # A plan naming a joint twice is refused when merged, point by point, each named too.
        path = os.path.join(self.directory, 'twice_named.bag')
        start = self.samples[0][0]
        twice = JointTrajectory(joint_names=LEFT_JOINTS + LEFT_JOINTS[:1])
        twice.header.stamp = self.samples[19][0]
        for t in (0.5, 1.0):
            twice.points.append(JointTrajectoryPoint(positions=self.samples[19][1][:8],
                                                     time_from_start=rospy.Duration(t)))
        with rosbag.Bag(path, 'w') as bag:
            bag.write('/move_group/planned_path', trajectory_of(self.samples[:20], slice(0, 14),
                                                                start), start)
            bag.write('/left/plan', twice, self.samples[19][0])
        result, report = self.replay(path)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(report['refused_messages'], {'wrong_size': 2})
        self.assertRegex(report['first_refused_message'],
                         r'^stamped [0-9.]+ s: \S+/twice_named\.bag: '
                         r'trajectory_msgs/JointTrajectory on /left/plan at bag time [0-9.]+, '
                         r'point 0: wrong_size \(.*left_joint1')

    def test_a_bag_without_joint_input_names_both_types(self):
        path = os.path.join(self.directory, 'empty.bag')
        with rosbag.Bag(path, 'w'):
            pass
        result, _ = self.replay(path)
        self.assertEqual(result.returncode, 1)
        self.assertIn('empty.bag: no sensor_msgs/JointState, trajectory_msgs/JointTrajectory, '
                      'moveit_msgs/DisplayTrajectory, control_msgs/FollowJointTrajectoryActionGoal '
                      'or moveit_msgs/ExecuteTrajectoryActionGoal message', result.stderr)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'replay_trajectory', ReplayTrajectoryTest)
