#!/usr/bin/python3
"""The task bags and the replay tool (test/ros/task_bags.test): regenerating the bags reproduces
test/bags/ byte for byte, and `replay --json` reports, cycle by cycle, the same warnings (names
and distances) for every broad phase (and the FCL / Bullet peers when replay is built with
them), with each task's expected outcome."""
import filecmp
import json
import os
import shutil
import tempfile
import unittest

import rosbag
import rospkg
import rostest

from acm_test_util import rosrun

PKG = 'arm_collision_monitor'
# Cycles per task (the seed's counts) and the grasp targets replay must declare.
TASKS = {'task1': (1000, []), 'task2': (150, []), 'task3': (2000, ['--task', '3'])}
METHODS = ['octree', 'naive', 'grid', 'rebuild', 'reinsert']
OPTIONAL_METHODS = ['fcl', 'bullet']


def moving_cycles(path):
    """Read independently of replay: its cycles (messages with equal header stamps, merged by
    joint name) whose joint positions differ from the previous cycle's, the first one included."""
    state, previous, stamp, count = {}, None, None, 0
    with rosbag.Bag(path) as bag:
        for _, msg, _ in bag.read_messages():
            if stamp is not None and msg.header.stamp != stamp:
                count += sorted(state.items()) != previous
                previous = sorted(state.items())
            stamp = msg.header.stamp
            state.update(zip(msg.name, msg.position))
    return count + (sorted(state.items()) != previous)


class TaskBagsTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.bags = os.path.join(rospkg.RosPack().get_path(PKG), 'test', 'bags')

    def test_regenerated_bags_are_identical(self):
        out = tempfile.mkdtemp(prefix='task_bags_')
        try:
            result = rosrun('generate_task_bags', out)
            self.assertEqual(result.returncode, 0, result.stderr)
            for name in TASKS:
                self.assertTrue(
                    filecmp.cmp(os.path.join(out, name + '.bag'),
                                os.path.join(self.bags, name + '.bag'), shallow=False),
                    '%s.bag differs from the regenerated one' % name)
        finally:
            shutil.rmtree(out)

    def replay(self, name, method):
        args = TASKS[name][1] + ['--method', method, '--json',
                                 os.path.join(self.bags, name + '.bag')]
        result = rosrun('replay', *args)
        if method in OPTIONAL_METHODS and 'unknown method' in result.stderr:
            return None
        self.assertEqual(result.returncode, 0, result.stderr)
        return json.loads(result.stdout)

    def test_each_warning_gives_its_threshold_to_the_bit(self):
        """per_cycle's entries end with their threshold: the two primitives' tolerance_m (as
        the JSON's primitives give them, to the bit) summed. The distance given is below it (or
        at most 0), at a sample and between samples but for kind within_resolution; and to the
        bit, more than 9 digits (some distance differs from its 9-digit rounding)."""
        for name in ('task2', 'task3'):
            report = self.replay(name, 'naive')
            tolerance = {p['name']: p['tolerance_m'] for p in report['primitives']}
            entries, finer_than_9_digits = 0, 0
            for cycle in report['per_cycle']:
                found = [(w[0], w[1], w[2], w[3], None) for w in cycle['warnings']]
                found += [(w[0], w[1], w[2], w[5], w[4]) for w in cycle['between_samples']]
                for a, b, distance, threshold, kind in found:
                    where = (name, cycle['cycle'], a, b, distance, threshold, kind)
                    self.assertEqual(threshold, tolerance[a] + tolerance[b], where)
                    if kind != 'within_resolution':
                        self.assertTrue(distance < threshold or distance <= 0.0, where)
                    finer_than_9_digits += float('%.9g' % distance) != distance
                entries += len(found)
            self.assertGreater(entries, 0, name)
            self.assertGreater(finer_than_9_digits, 0, name)

    def test_every_method_reports_the_same_warnings(self):
        for name, (cycles, _) in sorted(TASKS.items()):
            reference = self.replay(name, 'naive')
            self.assertEqual(reference['cycles'], cycles, name)
            self.assertEqual(reference['messages'], 2 * cycles, name)
            self.assertEqual(reference['refused_messages'], {}, name)
            self.assertEqual(reference['incomplete_cycles'], 0, name)
            expected = [c['warnings'] for c in reference['per_cycle']]
            # Timing statistics apart for the moving cycles (the seed's tasks dwell: fewer).
            moving = moving_cycles(os.path.join(self.bags, name + '.bag'))
            self.assertEqual(reference['moving_cycles'], moving, name)
            self.assertLess(moving, cycles, name)
            self.assertLessEqual(reference['moving_cycle_time_s']['p50'],
                                 reference['moving_cycle_time_s']['max'], name)
            for method in METHODS + OPTIONAL_METHODS:
                result = self.replay(name, method)
                if result is None:
                    print('%s: replay built without the peers, %s skipped' % (name, method))
                    continue
                actual = [c['warnings'] for c in result['per_cycle']]
                if method in OPTIONAL_METHODS:
                    # The peers' own distances can differ in the last bits; names must not.
                    expected_pairs = [[w[:2] for w in c] for c in expected]
                    self.assertEqual([[w[:2] for w in c] for c in actual], expected_pairs,
                                     '%s %s' % (name, method))
                else:
                    self.assertEqual(actual, expected, '%s %s' % (name, method))
                print('%s %s: %d cycles, %d with warnings, cycle time p50 %.1f us p99 %.1f us' % (
                    name, method, result['cycles'], result['warning_cycles'],
                    result['cycle_time_s']['p50'] * 1e6, result['cycle_time_s']['p99'] * 1e6))
            # The outcomes (the core test checks them against the brute force too).
            first = reference['first_warning']
            if name == 'task1':
                self.assertIsNone(first)
            elif name == 'task2':
                self.assertTrue(first['a'].startswith('left_') or first['b'].startswith('left_'))
                self.assertIn('front_table_top', (first['a'], first['b']))
                self.assertGreater(first['distance_m'], 0.0)
            else:
                self.assertIn('front_table_top', (first['a'], first['b']))
                for cycle in reference['per_cycle']:
                    for w in cycle['warnings']:
                        self.assertNotIn('front_box', w[:2])


if __name__ == '__main__':
    rostest.rosrun(PKG, 'task_bags', TaskBagsTest)
