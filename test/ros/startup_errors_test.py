#!/usr/bin/python3
"""Start-up tier: the monitor node given a bad URDF, scene, options file or parameter exits
non-zero with a message naming the file (or parameter) (test/ros/startup_errors.test)."""
import os
import select
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

import rospkg
import roslib.packages
import rostest

PACKAGE = 'arm_collision_monitor'
TIMEOUT_S = 60.0


class StartupErrorsTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.root = rospkg.RosPack().get_path(PACKAGE)
        nodes = roslib.packages.find_node(PACKAGE, 'monitor_node')
        assert nodes, 'monitor_node executable not found'
        cls.node = nodes[0]
        cls.tmp = tempfile.mkdtemp(prefix='acm_startup_')
        cls.runs = 0

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def write(self, name, text):
        path = os.path.join(self.tmp, name)
        with open(path, 'w') as f:
            f.write(text)
        return path

    def run_node(self, urdf=None, scene=None, config=None, extra=()):
        StartupErrorsTest.runs += 1
        args = [self.node, '__name:=startup_probe_%d' % self.runs]
        for key, value in (('urdf', urdf), ('scene', scene), ('config', config)):
            if value is not None:
                args.append('_%s:=%s' % (key, value))
        args += list(extra)
        proc = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=TIMEOUT_S, universal_newlines=True)
        return proc.returncode, proc.stdout

    def defaults(self):
        return dict(urdf=os.path.join(self.root, 'urdf', 'workcell.urdf'),
                    scene=os.path.join(self.root, 'config', 'scene.yaml'),
                    config=os.path.join(self.root, 'config', 'monitor.yaml'))

    def assert_fails_naming(self, needle, **files):
        args = self.defaults()
        args.update(files)
        code, output = self.run_node(**args)
        self.assertNotEqual(code, 0, 'the node started anyway:\n' + output)
        self.assertIn('cannot start', output)
        self.assertIn(needle, output, 'the message does not name %s:\n%s' % (needle, output))

    def test_missing_urdf_file(self):
        path = os.path.join(self.tmp, 'no_such_dir', 'workcell.urdf')
        self.assert_fails_naming(path, urdf=path)

    def test_malformed_urdf(self):
        path = self.write('broken.urdf', '<robot name="broken"><link name="a"></robot>')
        self.assert_fails_naming(path, urdf=path)

    def test_missing_scene_file(self):
        path = os.path.join(self.tmp, 'no_such_scene.yaml')
        self.assert_fails_naming(path, scene=path)

    def test_scene_with_a_bad_object(self):
        with open(self.defaults()['scene']) as f:
            text = f.read()
        # The bundled scene with one object given a negative size.
        bad = text.replace('size_m: [0.25, 0.25, 0.2]', 'size_m: [0.25, -0.25, 0.2]', 1)
        self.assertNotEqual(bad, text, 'the bundled scene changed: update this test')
        path = self.write('bad_object_scene.yaml', bad)
        self.assert_fails_naming(path, scene=path)

    def test_scene_not_yaml(self):
        path = self.write('not_yaml.yaml', 'objects: [ {name: a, size_m: [1, 2\n')
        self.assert_fails_naming(path, scene=path)

    def test_config_with_unknown_key(self):
        path = self.write('bad_monitor.yaml', 'broad_phase: octree\nno_such_option: 3\n')
        self.assert_fails_naming(path, config=path)

    def test_missing_parameter(self):
        code, output = self.run_node(scene=self.defaults()['scene'],
                                     config=self.defaults()['config'])
        self.assertNotEqual(code, 0)
        self.assertIn('urdf', output)

    def test_bad_parameter_value(self):
        # A double and an integer that must be positive, a double that may be zero.
        for param, value, expected in (('input_timeout_s', '-1.0', 'a positive number'),
                                       ('queue_size', '0', 'a positive number'),
                                       ('stop_hold_s', '-0.5', 'a non-negative number')):
            code, output = self.run_node(extra=['_%s:=%s' % (param, value)], **self.defaults())
            self.assertNotEqual(code, 0, 'started with %s = %s:\n%s' % (param, value, output))
            self.assertIn(param, output)
            self.assertIn(expected, output)
        # One joint prefix for the two default input topics.
        code, output = self.run_node(extra=['_input_joint_prefixes:=[left_]'], **self.defaults())
        self.assertNotEqual(code, 0, 'started with one prefix for two topics:\n' + output)
        self.assertIn('input_joint_prefixes: expected a list of one prefix per input topic (2, as '
                      '~input_topics), or none', output)

    def test_fixed_frame_a_link_away_from_the_root(self):
        # fixed_frame only renames the URDF root's frame: a moving link, or a link fixed beside
        # the root, has a pose of its own (TF poses looked up in it were misplaced).
        for link in ('left_link3', 'left_pedestal'):
            code, output = self.run_node(extra=['_fixed_frame:=' + link], **self.defaults())
            self.assertNotEqual(code, 0, 'started with fixed_frame %s:\n%s' % (link, output))
            self.assertIn('cannot start', output)
            self.assertIn("/fixed_frame: '%s' is a link of the URDF %s away from its root "
                          "'world'" % (link, self.defaults()['urdf']), output)
        path = self.write('link_frame.yaml', 'fixed_frame: left_link3\n')
        self.assert_fails_naming(path + ": fixed_frame: 'left_link3' is a link", config=path)
        # The frame an SRDF's floating virtual joint moves the root in (a mobile base's odom).
        with open(os.path.join(self.root, 'test', 'data', 'moveit', 'workcell.srdf')) as f:
            srdf = f.read()
        fixed = ('<virtual_joint name="virtual_joint" type="fixed" parent_frame="world" '
                 'child_link="world"/>')
        self.assertIn(fixed, srdf)
        srdf_path = self.write('floating.srdf', srdf.replace(fixed, fixed.replace(
            'type="fixed" parent_frame="world"', 'type="floating" parent_frame="odom"')))
        with open(self.defaults()['scene']) as f:
            scene_path = self.write('floating_scene.yaml', f.read() + '\nsrdf: %s\n' % srdf_path)
        code, output = self.run_node(extra=['_fixed_frame:=odom'],
                                     **dict(self.defaults(), scene=scene_path))
        self.assertNotEqual(code, 0, 'started with fixed_frame odom:\n' + output)
        self.assertIn("/fixed_frame: 'odom' is the parent_frame of %s:69: <virtual_joint "
                      "name='virtual_joint' type='floating'>, which moves the URDF root 'world'"
                      % srdf_path, output)
        # tf2 refuses a frame id with a leading '/' (and logs each time it is asked about one).
        code, output = self.run_node(extra=['_fixed_frame:=/odom'], **self.defaults())
        self.assertNotEqual(code, 0, 'started with fixed_frame /odom:\n' + output)
        self.assertIn("/fixed_frame: '/odom': a TF frame id has no leading '/'", output)

    def test_fixed_frame_a_link_fixed_at_the_root(self):
        # The same frame under another name: the node starts (its start-up line names the frame).
        with open(self.defaults()['urdf']) as f:
            urdf = f.read().replace(
                '</robot>', '<link name="world_alias"/><joint name="alias_joint" type="fixed">'
                '<parent link="world"/><child link="world_alias"/></joint></robot>')
        args = self.defaults()
        args['urdf'] = self.write('alias.urdf', urdf)
        StartupErrorsTest.runs += 1
        command = [self.node, '__name:=startup_probe_%d' % self.runs, '_fixed_frame:=world_alias']
        command += ['_%s:=%s' % item for item in sorted(args.items())]
        proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        # The pipe read as it comes (os.read: no reader-side buffer that select cannot see).
        output = ''
        deadline = time.time() + TIMEOUT_S
        try:
            while time.time() < deadline:
                ready, _, _ = select.select([proc.stdout], [], [],
                                            max(0.0, deadline - time.time()))
                chunk = os.read(proc.stdout.fileno(), 65536) if ready else b''
                if not chunk:
                    break  # exited (or the deadline)
                output += chunk.decode('utf-8', 'replace')
                if "frame 'world_alias'; input from" in output:
                    return
            self.fail('no start-up line with fixed_frame world_alias:\n' + output)
        finally:
            proc.terminate()
            proc.communicate()


if __name__ == '__main__':
    rostest.rosrun(PACKAGE, 'startup_errors', StartupErrorsTest, sys.argv)
