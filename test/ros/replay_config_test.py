#!/usr/bin/python3
"""replay = node at start-up (test/ros/replay_config.test): replay loads the monitor config first
and gives LoadWorkcell its tolerance_m, as the node does, so a config with a wider tolerance
makes replay warn where the default config does not; it prints the workcell's start-up findings
on stderr before the run; --help and -h print the usage on stdout and exit 0, while a usage error
goes to stderr with exit 2; a recording that never names a model joint is refused with a message
naming it, and replays once the scene file's joint_defaults give it."""
import json
import math
import os
import unittest
from xml.etree import ElementTree

import rosbag
import rospkg
import rospy
import rostest
import yaml
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from acm_test_util import (HOME, LEFT_JOINTS, LEFT_TOWARDS_RIGHT, RIGHT_JOINTS,
                           RIGHT_TOWARDS_LEFT, rosrun, temp_dir)

PKG = 'arm_collision_monitor'
# The finding LoadWorkcell reports for test/data/replay_scene.yaml: cable_guide lies inside
# right_link1 in every configuration.
FINDING = ("'right_link1' and 'cable_guide' are within their tolerances in the home pose and "
           "in all")


def rotation_columns(roll, pitch, yaw):
    """The columns of Rz(yaw) Ry(pitch) Rx(roll), URDF's and the scene file's rpy."""
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return [(cy * cp, sy * cp, -sp),
            (cy * sp * sr - sy * cr, sy * sp * sr + cy * cr, cp * sr),
            (cy * sp * cr + sy * sr, sy * sp * cr - cy * sr, cp * cr)]


def write_csv(path, header, rows):
    """A replay CSV at path: the header's names, then each row's values (str of each)."""
    with open(path, 'w') as f:
        f.write(','.join(header) + '\n')
        for row in rows:
            f.write(','.join(str(x) for x in row) + '\n')


class ReplayConfigTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        package = rospkg.RosPack().get_path(PKG)
        cls.bag = os.path.join(package, 'test', 'bags', 'task3.bag')
        # The bundled scene but with no arm tolerance of its own: the config's applies.
        cls.scene = os.path.join(package, 'test', 'data', 'replay_scene.yaml')
        cls.default_config = os.path.join(package, 'config', 'monitor.yaml')
        cls.wide_config = os.path.join(package, 'test', 'data', 'replay_wide_tolerance.yaml')
        cls.bundled_scene = os.path.join(package, 'config', 'scene.yaml')

    def replay(self, config):
        result = rosrun('replay', '--task', '3', '--json', '--scene', self.scene,
                        '--config', config, self.bag)
        self.assertEqual(result.returncode, 0, result.stderr)
        return json.loads(result.stdout), result.stderr

    @staticmethod
    def config_tolerance_m(config):
        with open(config) as f:
            return yaml.safe_load(f)['tolerance_m']

    @staticmethod
    def warnings(report):
        """The (cycle, a, b) of every warning of the run."""
        return {(cycle['cycle'], w[0], w[1]) for cycle in report['per_cycle']
                for w in cycle['warnings']}

    def test_config_tolerance_applies_as_in_the_node(self):
        default, default_findings = self.replay(self.default_config)
        wide, wide_findings = self.replay(self.wide_config)
        default_m = self.config_tolerance_m(self.default_config)
        wide_m = self.config_tolerance_m(self.wide_config)
        self.assertGreater(wide_m, default_m)
        # The first warning (cycle 0) is right_link1 -- cable_guide, an arm capsule against an
        # object of tolerance 0: its threshold is the arm's tolerance, i.e. the config's
        # tolerance_m, which is what the node gives LoadWorkcell.
        for report, tolerance_m in ((default, default_m), (wide, wide_m)):
            first = report['first_warning']
            self.assertEqual((first['cycle'], first['a'], first['b']),
                             (0, 'right_link1', 'cable_guide'))
            self.assertAlmostEqual(first['threshold_m'], tolerance_m, places=12)
        # The wider zone keeps every warning of the default one and adds some.
        self.assertLessEqual(self.warnings(default), self.warnings(wide))
        self.assertTrue(self.warnings(wide) - self.warnings(default),
                        'the wide config adds no warning')
        # ... and start-up findings: pairs within the wider tolerances in every configuration.
        self.assertTrue(set(wide_findings.splitlines()) - set(default_findings.splitlines()),
                        wide_findings)

    def test_startup_findings_are_printed(self):
        report, stderr = self.replay(self.default_config)
        lines = [line for line in stderr.splitlines() if FINDING in line]
        self.assertEqual(len(lines), 1, stderr)
        self.assertIn('would warn in every cycle', lines[0])
        self.assertTrue(lines[0].startswith('replay: '), lines[0])
        self.assertEqual(report['cycles'], 2000)  # stdout is still the report alone

    def test_joint_defaults_fill_a_recording_of_one_arm(self):
        # A path recorded or planned for the left arm alone, 20 samples at 20 Hz.
        directory = temp_dir(self, 'acm_joint_defaults_')
        bag_path = os.path.join(directory, 'left_only.bag')
        with rosbag.Bag(bag_path, 'w') as bag:
            for k in range(20):
                msg = JointState(name=LEFT_JOINTS, position=[0.01 * k] * len(LEFT_JOINTS))
                msg.header.stamp = rospy.Time(100) + rospy.Duration(0.05 * k)
                bag.write('/left_arm/joint_states', msg, msg.header.stamp)
        refused = rosrun('replay', '--json', '--scene', self.bundled_scene, bag_path)
        self.assertEqual(refused.returncode, 1, refused.stderr)
        # Every joint never given, at once.
        self.assertIn("no accepted sensor_msgs/JointState message or trajectory point gives "
                      "7 model joints: " + ", ".join("'%s'" % j for j in RIGHT_JOINTS),
                      refused.stderr)
        self.assertIn('joint_defaults', refused.stderr)
        # A gripper driver's NaN in every message of the right arm: the refusals are the cause,
        # and the error says so.
        nan_path = os.path.join(directory, 'right_nan.bag')
        with rosbag.Bag(nan_path, 'w') as bag:
            for k in range(3):
                for names, position in ((LEFT_JOINTS, 0.0), (RIGHT_JOINTS, float('nan'))):
                    msg = JointState(name=names, position=[position] * len(names))
                    msg.header.stamp = rospy.Time(100) + rospy.Duration(0.05 * k)
                    bag.write('/joint_states', msg, msg.header.stamp)
        refused = rosrun('replay', '--json', '--scene', self.bundled_scene, nan_path)
        self.assertEqual(refused.returncode, 1, refused.stderr)
        self.assertRegex(refused.stderr, r"gives 7 model joints: 'right_joint1', .*; 3 messages or "
                         r"planned points were refused \(3 non_finite\), the first stamped "
                         r"100\.000000 s: \S+/right_nan\.bag: sensor_msgs/JointState on "
                         r"/joint_states at bag time 100\.000000: non_finite")
        # The same scene with the right arm held at 0.
        scene_path = os.path.join(directory, 'scene.yaml')
        with open(self.bundled_scene) as f:
            scene = f.read()
        with open(scene_path, 'w') as f:
            f.write(scene + '\njoint_defaults: {%s}\n' %
                    ', '.join('%s: 0.0' % joint for joint in RIGHT_JOINTS))
        result = rosrun('replay', '--json', '--scene', scene_path, bag_path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual(report['cycles'], 20)
        self.assertEqual(report['incomplete_cycles'], 0)

    def test_json_lists_every_primitive_in_its_frame(self):
        # A Flexiv Rizon user, checking the distances with a reference of their own, had only
        # the fits' sizes: --json lists each primitive, the frame of its geometry and that
        # geometry. Here against the files: the bundled scene's solids and the URDF's cylinders.
        package = rospkg.RosPack().get_path(PKG)
        bag = os.path.join(package, 'test', 'bags', 'task1.bag')
        primitives = self.listed_primitives('--scene', self.bundled_scene, bag)
        with open(self.bundled_scene) as f:
            objects = yaml.safe_load(f)['objects']
        for obj in objects:
            p = primitives[obj['name']]
            # The bundled URDF's root, the fixed frame, is 'world'.
            self.assertEqual((p['owner'], p['variant'], p['frame'], p['follows_frame'],
                              p['attachable']),
                             (obj['name'], '', 'world', obj.get('frame', ''),
                              obj.get('attachable', False)))
            self.assertEqual(p['box']['center_m'], obj['pose']['xyz_m'])
            self.assertEqual(p['box']['half_extents_m'], [size / 2 for size in obj['size_m']])
            roll, pitch, yaw = obj['pose'].get('rpy', [0.0, 0.0, 0.0])
            for axis, expected in zip(p['box']['axes'], rotation_columns(roll, pitch, yaw)):
                for got, want in zip(axis, expected):
                    self.assertAlmostEqual(got, want, delta=1e-12, msg=obj['name'])
        urdf = ElementTree.parse(os.path.join(package, 'urdf', 'workcell.urdf'))
        checked = {'cylinder': 0, 'box': 0}
        for link in urdf.getroot().iter('link'):
            if link.get('name') not in primitives:
                continue  # a base link, whose geometry the scene ignores (links:)
            p = primitives[link.get('name')]
            self.assertEqual(p['frame'], link.get('name'))
            self.assertNotIn('follows_frame', p)
            for collision in link.findall('collision'):
                self.assertEqual(collision.find('origin').get('rpy').split(), ['0', '0', '0'])
                x, y, z = (float(v) for v in collision.find('origin').get('xyz').split())
                cylinder = collision.find('geometry/cylinder')
                if cylinder is not None:  # a capsule along the cylinder's axis, z
                    half_m = float(cylinder.get('length')) / 2
                    self.assertEqual(p['capsule']['radius_m'], float(cylinder.get('radius')))
                    for end, dz in (('p0_m', -half_m), ('p1_m', half_m)):
                        for got, want in zip(p['capsule'][end], (x, y, z + dz)):
                            self.assertAlmostEqual(got, want, delta=1e-12, msg=link.get('name'))
                    checked['cylinder'] += 1
                box = collision.find('geometry/box')
                if box is not None:  # a pedestal, on a fixed joint
                    self.assertEqual(p['box']['center_m'], [x, y, z])
                    self.assertEqual(p['box']['half_extents_m'],
                                     [float(v) / 2 for v in box.get('size').split()])
                    checked['box'] += 1
        # The two arms' links, a cylinder each, and their pedestals.
        self.assertEqual(checked, {'cylinder': 14, 'box': 2})
        # A model whose root is not named 'world': objects are in its frame.
        csv_path = os.path.join(temp_dir(self, 'acm_primitives_'), 'home.csv')
        with open(csv_path, 'w') as f:
            f.write('shoulder,elbow,spin,slide\n0,0,0,0\n')
        primitives = self.listed_primitives(
            '--urdf', os.path.join(package, 'test', 'data', 'three_link_arm.urdf'), '--scene',
            os.path.join(package, 'test', 'data', 'three_link_scene.yaml'), csv_path)
        self.assertEqual(primitives['table']['frame'], 'base_link')
        self.assertEqual(primitives['table']['box']['center_m'], [0.7, 0.0, 0.3])

    def listed_primitives(self, *args):
        """replay --json's primitives by name (each name once)."""
        result = rosrun('replay', '--json', *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        listed = json.loads(result.stdout)['primitives']
        primitives = {p['name']: p for p in listed}
        self.assertEqual(len(primitives), len(listed), 'names not unique')
        return primitives

    def test_unknown_joint_names_are_shown_with_the_models(self):
        # Two drivers of alike arms, each publishing the same unprefixed names on its own topic
        # (an ALOHA's 'waist', 'shoulder', ...): none is a model joint. The error names what the
        # input gave, the model's prefixed joints and the option that prefixes them (a Flexiv
        # Rizon user's per-arm topics).
        bag_path = os.path.join(temp_dir(self, 'acm_unprefixed_'), 'unprefixed.bag')
        names = [joint.replace('left_', '') for joint in LEFT_JOINTS]
        with rosbag.Bag(bag_path, 'w') as bag:
            for k in range(4):
                msg = JointState(name=names, position=[0.0] * len(names))
                msg.header.stamp = rospy.Time(100) + rospy.Duration(0.05 * k)
                bag.write('/%s_arm/joint_states' % ('left', 'right')[k % 2], msg,
                          msg.header.stamp)
        result = rosrun('replay', '--scene', self.bundled_scene, bag_path)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("; the input gives these names that are no joints of the model: %s; the "
                      "model has 'joint1' as 'left_joint1', 'right_joint1'; 'joint2' as "
                      "'left_joint2', 'right_joint2'; 'joint3' as 'left_joint3', 'right_joint3' "
                      "(publish the model's joint names, or give each topic's prefix: "
                      "--joint-prefix TOPIC=PREFIX)" % ', '.join("'%s'" % n for n in names),
                      result.stderr)
        # With a prefix per topic, as the node's ~input_joint_prefixes: the model's two arms (the
        # first message, of the left arm alone, does not complete the model).
        prefixes = ['--joint-prefix', '/left_arm/joint_states=left_',
                    '--joint-prefix', '/right_arm/joint_states=right_']
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, *prefixes, bag_path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual((report['incomplete_cycles'], report['cycles']), (1, 3))
        result = rosrun('replay', '--scene', self.bundled_scene, '--joint-prefix', 'left_',
                        bag_path)
        self.assertEqual(result.returncode, 2)
        self.assertIn("--joint-prefix expects topic=prefix, got 'left_'", result.stderr)
        result = rosrun('replay', '--scene', self.bundled_scene, '--joint-prefix',
                        '/left_arm/states=left_', bag_path)
        self.assertEqual(result.returncode, 1)
        self.assertIn('--joint-prefix /left_arm/states: no ', result.stderr)
        result = rosrun('replay', '--scene', self.bundled_scene, '--topic',
                        '/left_arm/joint_states', *(prefixes + [bag_path]))
        self.assertEqual(result.returncode, 1)
        self.assertIn('--joint-prefix /right_arm/joint_states: not among the topics read (--topic)',
                      result.stderr)

    def test_a_refused_cycle_names_its_joint(self):
        # Five rows at 20 Hz, the third with left_joint2 far outside its limits.
        directory = temp_dir(self, 'acm_refusal_')
        csv_path = os.path.join(directory, 'refused.csv')
        rows = [[0.01 * k] * 14 for k in range(5)]
        rows[2][1] = 10.0
        write_csv(csv_path, LEFT_JOINTS + RIGHT_JOINTS, rows)
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, csv_path)
        report = json.loads(result.stdout)
        self.assertEqual(report['refused_cycles'], 1, result.stderr)
        self.assertEqual(report['first_refusal']['cycle'], 2)
        self.assertIn("joint 'left_joint2' at 10, outside its limits [",
                      report['first_refusal']['reason'])
        text = rosrun('replay', '--scene', self.bundled_scene, csv_path).stdout
        self.assertIn("1 cycle refused by the monitor (the first, cycle 2 at 0.100 s: joint "
                      "'left_joint2' at 10, outside its limits [", text)
        # The summary never reads clear over refused cycles.
        self.assertIn("summary: no warning in 5 cycles; 1 cycle refused, not checked (the "
                      "monitor asks a stop on each;", text)
        # Every row refused (say, angles in degrees): no cycle was checked.
        write_csv(csv_path, LEFT_JOINTS + RIGHT_JOINTS, [[90] * 14] * 5)
        text = rosrun('replay', '--scene', self.bundled_scene, csv_path).stdout
        self.assertIn("summary: no cycle checked: all 5 refused (the monitor asks a stop on "
                      "each;", text)
        self.assertNotIn('no warning', text)

    def test_a_step_beyond_max_step_is_a_stop_in_the_summary(self):
        # Five rows at 20 Hz; left_joint1 turns 2.2 rad at the third and back at the fifth,
        # far beyond its velocity limit and moving the arm more than max_step_m (1 m).
        directory = temp_dir(self, 'acm_jump_')
        csv_path = os.path.join(directory, 'jump.csv')
        write_csv(csv_path, LEFT_JOINTS + RIGHT_JOINTS,
                  [[-2.5 if k in (2, 3) else -0.3] + [0.0] * 13 for k in range(5)])
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, csv_path)
        self.assertEqual(json.loads(result.stdout)['jumped_cycles'], 2, result.stderr)
        text = rosrun('replay', '--scene', self.bundled_scene, csv_path).stdout
        summary = [line for line in text.splitlines() if line.startswith('summary:')]
        self.assertEqual(len(summary), 1, text)
        self.assertIn('; 2 steps beyond max_step_m (input_jumped: the monitor asks a stop on '
                      'each)', summary[0])

    def test_steps_the_samples_do_not_cover_are_counted_apart(self):
        # Without the swept check (cycle_period_s 0.001 s, which start-up's tolerance check
        # needs), the left arm leaning over turns its base 0.1 rad a row at 20 Hz: each step
        # moves it beyond its tolerance, which the samples alone do not cover. Those stops were
        # counted as steps beyond max_step_m, which none of them is.
        directory = temp_dir(self, 'acm_beyond_samples_')
        config = os.path.join(directory, 'samples_only.yaml')
        with open(config, 'w') as f:
            f.write('swept_check: false\ncycle_period_s: 0.001\n')
        csv_path = os.path.join(directory, 'turn.csv')
        write_csv(csv_path, LEFT_JOINTS + RIGHT_JOINTS,
                  [[0.1 * k, 0.5] + [0.0] * 12 for k in range(5)])
        args = ['--scene', self.bundled_scene, '--config', config, csv_path]
        result = rosrun('replay', '--json', *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertFalse(report['swept_check'])
        self.assertEqual((report['jumped_cycles'], report['beyond_samples_cycles']), (4, 4))
        summary = [line for line in rosrun('replay', *args).stdout.splitlines()
                   if line.startswith('summary:')]
        self.assertEqual(len(summary), 1)
        self.assertIn('; 4 steps the samples do not cover, each moving a primitive farther than '
                      'its tolerance (swept_check false; input_jumped: the monitor asks a stop on '
                      'each)', summary[0])
        self.assertNotIn('max_step_m', summary[0])

    def test_every_nth_cycle_is_the_same_path_sampled_sparser(self):
        # The bundled real robot's bag (20 Hz) with --every 10: cycles 0, 10, 20, ..., numbered and
        # timed as in the full run, each warning at its sample as the full run does at that
        # cycle, to the bit (with fixed tolerances a sample's warnings depend on its q alone; its
        # step is swept from the kept cycle before), none refused; and at --every 40 none a jump
        # (each joint's sample times are thinned with it: 2 s steps each timed 0.05 s gave 5).
        package = rospkg.RosPack().get_path(PKG)
        files = ['--urdf', os.path.join(package, 'urdf', 'dual_arm_shelf.urdf'),
                 '--scene', os.path.join(package, 'config', 'dual_arm_shelf', 'scene.yaml'),
                 os.path.join(package, 'test', 'bags', 'dual_arm_shelf.bag')]
        reports = {}
        for every in (1, 10, 40):
            result = rosrun('replay', '--json', '--every', str(every), *files)
            self.assertEqual(result.returncode, 0, result.stderr)
            reports[every] = json.loads(result.stdout)
            self.assertEqual(reports[every]['every'], every)
        full, sparse = reports[1]['per_cycle'], reports[10]['per_cycle']
        self.assertEqual(len(sparse), (len(full) + 9) // 10)
        for key in ('cycle', 'time_s'):
            self.assertEqual([c[key] for c in sparse], [c[key] for c in full[::10]], key)
        self.assertEqual(reports[10]['first_warning']['cycle'] % 10, 0)
        self.assertEqual(reports[10]['refused_cycles'], 0)
        self.assertEqual((reports[40]['refused_cycles'], reports[40]['jumped_cycles']), (0, 0))
        self.assertEqual([c['warnings'] for c in sparse], [c['warnings'] for c in full[::10]])
        self.assertTrue(any(c['warnings'] for c in sparse), 'no warning at the kept samples')
        text = rosrun('replay', '--every', '10', *files).stdout
        self.assertIn(': method auto (swept check on), %d cycles of %d (--every 10: cycles 0, 10, '
                      '20, ...) from 682 messages' % (len(sparse), len(full)),
                      text.splitlines()[0])
        for bad in ('0', '-1', '1.5', 'x', '1000001', '4294967297'):
            result = rosrun('replay', '--every', bad, files[-1])
            self.assertEqual(result.returncode, 2, bad)
            self.assertIn("--every expects a whole number of cycles from 1 to 1000000, got '%s'"
                          % bad, result.stderr)

    def test_a_csv_is_read_as_the_node_reads_joint_states(self):
        # A column of no model joint (a gripper the driver publishes) is ignored and listed, as
        # is one of a joint the URDF holds fixed, marked so; a nan position is a refused cycle,
        # named, not the end of the run; the peers refuse it too.
        directory = temp_dir(self, 'acm_csv_as_node_')
        csv_path = os.path.join(directory, 'driver.csv')
        rows = [[0.01 * k] * 15 + [0] for k in range(5)]
        rows[3][2] = 'nan'
        write_csv(csv_path, LEFT_JOINTS + ['gripper_x'] + RIGHT_JOINTS + ['left_tool_joint'], rows)
        methods = ['auto']
        if 'fcl' in rosrun('replay', '--help').stdout:
            methods += ['fcl', 'bullet']
        for method in methods:
            result = rosrun('replay', '--json', '--method', method, '--scene', self.bundled_scene,
                            csv_path)
            self.assertEqual(result.returncode, 0, result.stderr)
            report = json.loads(result.stdout)
            self.assertEqual(report['ignored_columns'], ['gripper_x', 'left_tool_joint'], method)
            self.assertEqual(report['cycles'], 5, method)
            self.assertEqual(report['refused_cycles'], 1, method)
            self.assertEqual(report['first_refusal']['cycle'], 3, method)
            if method == 'auto':
                self.assertIn("joint 'left_joint3' at nan", report['first_refusal']['reason'])
        text = rosrun('replay', '--scene', self.bundled_scene, csv_path).stdout
        self.assertIn("input: 2 columns ignored, not joints of the model: 'gripper_x', "
                      "'left_tool_joint' (a fixed joint of the URDF)\n", text)

    def test_a_csv_column_of_a_mimic_joint_is_listed_not_read(self):
        # A small arm's URDF mimic joint follows the joint it mimics: its column is not read (a
        # value that disagrees changes nothing) and is listed apart from columns of no joint.
        data = os.path.join(rospkg.RosPack().get_path(PKG), 'test', 'data')
        csv_path = os.path.join(temp_dir(self, 'acm_csv_mimic_'), 'mimic.csv')
        with open(csv_path, 'w') as f:
            f.write('shoulder,slide,finger_mimic,elbow,spin,gripper_x\n')
            f.write('0,0.01,0.5,0,0,0\n0.1,0.02,0.5,0.1,0,0\n')
        args = ['--urdf', os.path.join(data, 'three_link_arm.urdf'), '--scene',
                os.path.join(data, 'three_link_scene.yaml'), csv_path]
        result = rosrun('replay', '--json', *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual(report['mimic_columns'], ['finger_mimic'])
        self.assertEqual(report['ignored_columns'], ['gripper_x'])
        self.assertEqual(report['cycles'], 2)
        self.assertIn("input: 1 column of mimic joints not read (their positions follow from the "
                      "joints they mimic in the URDF): 'finger_mimic'\n",
                      rosrun('replay', *args).stdout)

    def test_a_bags_names_of_no_model_joint_are_listed(self):
        # A recording of the small arm also naming its URDF mimic joint (a joint_state_publisher
        # publishes it), a gripper joint the URDF lacks and a joint the URDF holds fixed: none is
        # read, all are listed, mimic joints apart, as a CSV's columns are (a Reachy 2 user's
        # extra joint went unmentioned), the fixed one marked (a Sawyer's driver publishes its
        # fixed torso_t0).
        data = os.path.join(rospkg.RosPack().get_path(PKG), 'test', 'data')
        path = os.path.join(temp_dir(self, 'acm_bag_names_'), 'names.bag')
        with rosbag.Bag(path, 'w') as bag:
            for k in range(2):
                msg = JointState(name=['shoulder', 'slide', 'finger_mimic', 'elbow', 'spin',
                                       'gripper_x', 'tool_joint'],
                                 position=[0.1 * k, 0.01, 0.5, 0.0, 0.0, 0.0, 0.0])
                msg.header.stamp = rospy.Time(10) + rospy.Duration(0.05 * k)
                bag.write('/joint_states', msg, msg.header.stamp)
        args = ['--urdf', os.path.join(data, 'three_link_arm.urdf'), '--scene',
                os.path.join(data, 'three_link_scene.yaml'), path]
        result = rosrun('replay', '--json', *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual((report['ignored_names'], report['mimic_names'], report['cycles']),
                         (['gripper_x', 'tool_joint'], ['finger_mimic'], 2))
        text = rosrun('replay', *args).stdout
        self.assertIn("input: joint names in the messages that are no joints of the model, "
                      "ignored: 'gripper_x', 'tool_joint' (a fixed joint of the URDF)\n", text)
        self.assertIn("input: mimic joints in the messages, not read (their positions follow from "
                      "the joints they mimic in the URDF): 'finger_mimic'\n", text)
        self.assertEqual((report['more_ignored_names'], report['more_mimic_names']),
                         (False, False))

    def test_a_bags_names_beyond_those_listed_are_said_to_be(self):
        # Ten names of no model joint, one new per message after the first (a Baxter trial's
        # head and gripper joints): the first 8 are listed, and that there were more.
        data = os.path.join(rospkg.RosPack().get_path(PKG), 'test', 'data')
        path = os.path.join(temp_dir(self, 'acm_bag_more_names_'), 'names.bag')
        extra = ['extra_%d' % i for i in range(10)]
        with rosbag.Bag(path, 'w') as bag:
            for k in range(3, 11):
                msg = JointState(name=['shoulder', 'slide', 'elbow', 'spin'] + extra[:k],
                                 position=[0.0] * (4 + k))
                msg.header.stamp = rospy.Time(10) + rospy.Duration(0.05 * k)
                bag.write('/joint_states', msg, msg.header.stamp)
        args = ['--urdf', os.path.join(data, 'three_link_arm.urdf'), '--scene',
                os.path.join(data, 'three_link_scene.yaml'), path]
        report = json.loads(rosrun('replay', '--json', *args).stdout)
        self.assertEqual((report['ignored_names'], report['more_ignored_names']),
                         (extra[:8], True))
        text = rosrun('replay', *args).stdout
        self.assertIn("ignored: %s, and more\n" % ', '.join("'%s'" % n for n in extra[:8]), text)

    def test_between_samples_lines_say_what_they_are(self):
        # Home, both arms swung into each other in one step, home again (20 Hz).
        directory = temp_dir(self, 'acm_between_')
        csv_path = os.path.join(directory, 'swing.csv')
        write_csv(csv_path, LEFT_JOINTS + RIGHT_JOINTS,
                  [list(left) + list(right) for left, right in
                   ((HOME, HOME), (LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT), (HOME, HOME))])
        text = rosrun('replay', '--scene', self.bundled_scene, csv_path).stdout
        lines = [line for line in text.splitlines() if 'between samples at' in line]
        # The way back starts within the zone of the pairs the swing ended in: their warnings
        # at its start say so; a contact on the way, strictly between the samples, does not.
        starts = [line for line in lines if line.startswith('cycle 2 ') and
                  'at 0.000 of the step' in line]
        self.assertTrue(starts, text)
        for line in starts:
            self.assertTrue(line.endswith("(the step starts within: the previous sample's "
                                          "warning)"), line)
        inside = [line for line in lines if 'at 0.000' not in line and 'at 1.000' not in line]
        self.assertTrue(inside, text)
        for line in inside:
            self.assertTrue(line.endswith('m)'), line)
        self.assertIn('swept check: 2 cycles warn between samples: 2 with a pair within its '
                      'threshold strictly between them, 0 only where the step starts within, 0 '
                      'only within swept_resolution_m, 0 with both of those; ', text)
        # The summary counts the cycles that warn only between samples (the node stops on them;
        # an ALOHA and a dual FR3 user read it as a count of all).
        self.assertIn('summary: 2 of 3 cycles warn (1 at their sample, 1 only between samples); '
                      'first at cycle 1 ', text)
        report = json.loads(rosrun('replay', '--json', '--scene', self.bundled_scene,
                                   csv_path).stdout)
        self.assertEqual((report['warning_cycles'], report['between_samples_cycles'],
                          report['warned_cycles']), (1, 2, 2))
        self.assertEqual(report['first_between_samples']['cycle'], 1)
        self.assertEqual(report['first_between_samples']['kind'], 'strictly_between')
        # Each JSON entry has its kind, as each line has: those at the way back's start start
        # within.
        entries = [entry for cycle in report['per_cycle'] for entry in cycle['between_samples']]
        self.assertTrue(any(entry[3] == 0.0 for entry in entries), entries)
        for entry in entries:
            self.assertEqual(entry[4], 'step_starts_within' if entry[3] == 0.0
                             else 'strictly_between', entry)

    def test_a_contact_only_between_samples_is_the_first_warning(self):
        # The left arm, leaning over, swings its base joint from 0.6 to -2.9 rad in one step past
        # the right arm turned towards it: clear at both samples, in contact between them. The
        # summary's first warning is that contact (it said the run had none at the samples).
        csv_path = os.path.join(temp_dir(self, 'acm_between_first_'), 'swing.csv')
        towards = [1.5708, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0]
        write_csv(csv_path, LEFT_JOINTS + RIGHT_JOINTS,
                  [list(left) + list(right) for left, right in
                   ((HOME, HOME), ([0.6, 0.5] + [0.0] * 5, towards),
                    ([-2.9, 0.5] + [0.0] * 5, towards))])
        text = rosrun('replay', '--scene', self.bundled_scene, csv_path).stdout
        self.assertRegex(text, r'summary: 1 of 3 cycles warn \(0 at their sample, 1 only between '
                               r'samples\); first at cycle 2 \(0\.10 s\): left_link\d -- '
                               r'right_link\d at 0\.0000 m between samples, at 0\.\d+ of the step')

    def test_json_cycle_times_are_the_inputs_to_the_nanosecond(self):
        # An iiwa user's 1 kHz bag: times rounded to the millisecond made cycles share a time.
        csv_path = os.path.join(temp_dir(self, 'acm_csv_times_'), 'times.csv')
        times = [0.0, 0.000504, 0.001, 0.001503217]
        write_csv(csv_path, ['time_s'] + LEFT_JOINTS + RIGHT_JOINTS,
                  [[t] + [0.001 * k] * 14 for k, t in enumerate(times)])
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, csv_path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual([c['time_s'] for c in report['per_cycle']], times)

    def test_the_first_refused_message_is_named(self):
        # A recording whose second message holds a NaN: refused and counted, and named (a
        # Kinova Gen3 user read "1 messages refused (non_finite: 1)" and looked for it).
        path = os.path.join(temp_dir(self, 'acm_refused_'), 'nan.bag')
        with rosbag.Bag(path, 'w') as bag:
            for k in range(3):
                msg = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=[0.0] * 14)
                msg.header.stamp = rospy.Time(100) + rospy.Duration(0.05 * k)
                if k == 1:
                    msg.position[1] = float('nan')
                bag.write('/joint_states', msg, msg.header.stamp)
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual(report['refused_messages'], {'non_finite': 1})
        first = ("stamped 100.050000 s: %s: sensor_msgs/JointState on /joint_states at bag time "
                 "100.050000: non_finite (joint 'left_joint2' at nan)" % path)
        self.assertEqual(report['first_refused_message'], first)
        # The refused message makes no cycle (it made one of the last accepted q, marked not
        # refused, with its warnings: a dual FR3 user's bag), and the summary counts it.
        self.assertEqual([c['time_s'] for c in report['per_cycle']], [0.0, 0.1])
        text = rosrun('replay', '--scene', self.bundled_scene, path).stdout
        self.assertIn('input: 1 message refused (non_finite: 1) (the first %s), ' % first, text)
        self.assertIn('summary: no warning in 2 cycles; 1 message or planned point refused, no '
                      'cycle (the node asks a stop on a message;', text)

    def test_the_first_refused_message_is_the_first_met(self):
        # A NaN in the second message, then a message stamped before it (refused,
        # stamp_backwards): the NaN one came first and is named (the earliest stamp named the
        # later one: a Baxter trial's).
        path = os.path.join(temp_dir(self, 'acm_refused_order_'), 'order.bag')
        with rosbag.Bag(path, 'w') as bag:
            for k in range(5):
                recorded_at = rospy.Time(100) + rospy.Duration(0.05 * k)
                msg = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=[0.0] * 14)
                msg.header.stamp = recorded_at
                if k == 1:
                    msg.position[1] = float('nan')
                if k == 3:
                    msg.header.stamp = rospy.Time(100, 10000000)
                bag.write('/joint_states', msg, recorded_at)
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual(report['refused_messages'], {'non_finite': 1, 'stamp_backwards': 1})
        self.assertTrue(report['first_refused_message'].startswith(
            'stamped 100.050000 s: %s: sensor_msgs/JointState on /joint_states at bag time '
            '100.050000: non_finite' % path), report['first_refused_message'])
        # A planned point of the right arm refused at the time of a left arm's NaN message (6
        # positions for 7 names): the replay takes the recorded state first at equal times, and
        # names it first.
        path = os.path.join(temp_dir(self, 'acm_refused_tie_'), 'tie.bag')
        with rosbag.Bag(path, 'w') as bag:
            plan = JointTrajectory(joint_names=RIGHT_JOINTS)
            plan.header.stamp = rospy.Time(100)
            plan.points = [JointTrajectoryPoint(positions=[0.0] * (6 if k == 2 else 7),
                                                time_from_start=rospy.Duration(0.05 * k))
                           for k in range(5)]
            bag.write('/plan', plan, rospy.Time(99))
            for k in range(5):
                msg = JointState(name=LEFT_JOINTS, position=[0.0] * 7)
                msg.header.stamp = rospy.Time(100) + rospy.Duration(0.05 * k)
                msg.position[1] = float('nan') if k == 2 else 0.0
                bag.write('/joint_states', msg, msg.header.stamp)
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual(report['refused_messages'], {'non_finite': 1, 'wrong_size': 1})
        self.assertIn('100.100000: non_finite', report['first_refused_message'])

    def test_stamps_are_taken_as_the_node_takes_them(self):
        # Five messages 0.05 s apart: the second stamped 100 s further ahead of the time the
        # bag recorded it than the others (refused future_stamp, as the node refuses a stamp
        # ahead of its clock; accepted, it made each later message go backwards: a Techman
        # user's bag froze an arm for 4 s), the fourth unstamped (0: sampled when recorded, as
        # the node takes it; it was refused, stamp_backwards).
        path = os.path.join(temp_dir(self, 'acm_stamps_'), 'stamps.bag')
        with rosbag.Bag(path, 'w') as bag:
            for k in range(5):
                recorded_at = rospy.Time(100) + rospy.Duration(0.05 * k)
                msg = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=[0.01 * k] * 14)
                msg.header.stamp = recorded_at
                if k == 1:
                    msg.header.stamp += rospy.Duration(100)
                if k == 3:
                    msg.header.stamp = rospy.Time(0)
                bag.write('/joint_states', msg, recorded_at)
        result = rosrun('replay', '--json', '--scene', self.bundled_scene, path)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = json.loads(result.stdout)
        self.assertEqual(report['refused_messages'], {'future_stamp': 1})
        self.assertTrue(report['first_refused_message'].startswith(
            'stamped 200.050000 s: %s: sensor_msgs/JointState on /joint_states at bag time '
            '100.050000: future_stamp' % path), report['first_refused_message'])
        self.assertEqual([round(c['time_s'], 9) for c in report['per_cycle']],
                         [0.0, 0.1, 0.15, 0.2])
        # Stamps of a robot's clock, 2 s ahead of the recorder's, are read as they are, but for
        # one 100 s ahead of the others: first in the bag (a reviewer's: taken as the reference,
        # it froze the arm), or giving the left arm's joints alone (a source of its own, it was
        # its own reference); so is an unstamped message among stamps 0.1 s ahead (unordered,
        # as the node takes it).
        for ahead_s, unstamped, far, refused in ((2.0, None, 0, {'future_stamp': 1}),
                                                 (2.0, None, 6, {'future_stamp': 1}),
                                                 (0.1, 3, None, {})):
            with rosbag.Bag(path, 'w') as bag:
                for k in range(5):
                    recorded_at = rospy.Time(100) + rospy.Duration(0.05 * k)
                    msg = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=[0.01 * k] * 14)
                    msg.header.stamp = recorded_at + rospy.Duration(ahead_s)
                    if k == far:
                        msg.header.stamp += rospy.Duration(100)
                    if far is not None and k == far - 4:
                        left = JointState(name=LEFT_JOINTS, position=[0.0] * 7)
                        left.header.stamp = msg.header.stamp + rospy.Duration(100)
                        bag.write('/joint_states', left, recorded_at)
                    if k == unstamped:
                        msg.header.stamp = rospy.Time(0)
                    bag.write('/joint_states', msg, recorded_at)
            result = rosrun('replay', '--json', '--scene', self.bundled_scene, path)
            self.assertEqual(result.returncode, 0, result.stderr)
            report = json.loads(result.stdout)
            self.assertEqual(report['refused_messages'], refused, (ahead_s, far))
            self.assertEqual(len(report['per_cycle']), 5 - (far == 0), (ahead_s, far))
            # A clock off by more than the node's default input timeout is told of (a node on
            # the recorder's clock refuses such stamps).
            self.assertEqual(report['clock_offsets'],
                             {'/joint_states': ahead_s} if ahead_s > 0.25 else {}, ahead_s)
        text = rosrun('replay', '--scene', self.bundled_scene, path).stdout
        self.assertNotIn('is stamped', text)
        # The arms 5 s behind; a gripper driver on the same topic on the recorder's clock (no
        # model joint) does not hide them.
        with rosbag.Bag(path, 'w') as bag:
            for k in range(5):
                recorded_at = rospy.Time(100) + rospy.Duration(0.05 * k)
                msg = JointState(name=LEFT_JOINTS + RIGHT_JOINTS, position=[0.01 * k] * 14)
                msg.header.stamp = recorded_at - rospy.Duration(5.0)
                bag.write('/joint_states', msg, recorded_at)
                gripper = JointState(name=['gripper_finger'], position=[0.02])
                gripper.header.stamp = recorded_at
                bag.write('/joint_states', gripper, recorded_at)
        text = rosrun('replay', '--scene', self.bundled_scene, path).stdout
        self.assertIn('input: /joint_states is stamped 5.000 s behind the times the bag recorded '
                      'it, as a rule: read as it is (a robot\'s clock off the recorder\'s), where '
                      'a node on the recorder\'s clock refuses such stamps as stale beyond its '
                      'input_timeout_s (0.25 s by default)', text)
        # Nor does an arm's driver on the recorder's clock hide the other arm's, on one topic.
        with rosbag.Bag(path, 'w') as bag:
            for k in range(5):
                recorded_at = rospy.Time(100) + rospy.Duration(0.05 * k)
                for names, ahead_s in ((LEFT_JOINTS, 5.0), (RIGHT_JOINTS, 0.0)):
                    msg = JointState(name=names, position=[0.01 * k] * 7)
                    msg.header.stamp = recorded_at + rospy.Duration(ahead_s)
                    bag.write('/joint_states', msg, recorded_at)
        report = json.loads(rosrun('replay', '--json', '--scene', self.bundled_scene,
                                   path).stdout)
        self.assertEqual(report['clock_offsets'], {'/joint_states': 5.0})

    def test_between_samples_lines_past_the_first_20_are_counted(self):
        # The swing of test_between_samples_lines_say_what_they_are, there and back four times:
        # more warnings between samples than the text prints (a Kinova Gen3 user's plan printed
        # 20 and stopped without a word); --json has them all.
        csv_path = os.path.join(temp_dir(self, 'acm_between_'), 'swings.csv')
        write_csv(csv_path, LEFT_JOINTS + RIGHT_JOINTS,
                  [list(HOME) * 2 if k % 2 == 0 else
                   list(LEFT_TOWARDS_RIGHT) + list(RIGHT_TOWARDS_LEFT) for k in range(9)])
        report = json.loads(rosrun('replay', '--json', '--scene', self.bundled_scene,
                                   csv_path).stdout)
        total = sum(len(cycle['between_samples']) for cycle in report['per_cycle'])
        self.assertGreater(total, 20)
        text = rosrun('replay', '--scene', self.bundled_scene, csv_path).stdout
        lines = [line for line in text.splitlines() if 'between samples at' in line]
        self.assertEqual(len(lines), 20, text)
        self.assertIn('\n... and %d more between-samples warnings, not printed (--json lists '
                      'all)\nswept check: ' % (total - 20), text)

    def test_an_error_says_which_files_were_the_bundled_defaults(self):
        package = rospkg.RosPack().get_path(PKG)
        urdf = os.path.join(package, 'urdf', 'dual_arm_shelf.urdf')
        result = rosrun('replay', '--urdf', urdf, self.bag)
        self.assertEqual(result.returncode, 1)
        # The monitor options only where the error names them: here it does not.
        self.assertIn("replay: (not given, so the bundled workcell's: --scene %s)\n"
                      % self.bundled_scene, result.stderr)
        given = rosrun('replay', '--urdf', urdf, '--scene', self.bundled_scene, '--config',
                       self.default_config, self.bag)
        self.assertEqual(given.returncode, 1)
        self.assertNotIn('not given', given.stderr)

    def test_help_goes_to_stdout(self):
        for flag in ('--help', '-h'):
            result = rosrun('replay', flag)
            self.assertEqual(result.returncode, 0, flag)
            self.assertTrue(result.stdout.startswith('usage: replay'), result.stdout)
            self.assertIn('--config F', result.stdout)
            self.assertEqual(result.stderr, '', flag)

    def test_usage_errors_go_to_stderr(self):
        result = rosrun('replay', '--no-such-option', self.bag)
        self.assertEqual(result.returncode, 2)
        self.assertEqual(result.stdout, '')
        self.assertIn('unknown option --no-such-option', result.stderr)
        self.assertIn('usage: replay', result.stderr)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'replay_config', ReplayConfigTest)
