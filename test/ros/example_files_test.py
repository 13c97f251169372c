#!/usr/bin/python3
"""The bundled dual_arm_shelf example (test/ros/example_files.test): scripts/make_example.py
regenerates its files byte for byte; its meshes, read back from the committed files by this
test's own readers (binary STL, OBJ, COLLADA), are closed and outward; and `replay --json` on its
trajectory loads the example with no override and reports, cycle by cycle, the same warnings
for every broad phase, with some warning cycles and some clean ones."""
import filecmp
import json
import os
import shutil
import struct
import subprocess
import tempfile
import unittest
import xml.etree.ElementTree as ElementTree

import rospkg
import rostest

from acm_test_util import rosrun

PKG = 'arm_collision_monitor'
MESH_DIR = os.path.join('urdf', 'meshes', 'dual_arm_shelf')
GENERATED = [os.path.join('urdf', 'dual_arm_shelf.urdf'),
             os.path.join('test', 'bags', 'dual_arm_shelf.bag')]
METHODS = ['octree', 'naive', 'grid', 'rebuild', 'reinsert']
COLLADA_NS = '{http://www.collada.org/2005/11/COLLADASchema}'


def read_stl(path):
    """Binary STL: triangles as vertex-coordinate triples (vertices shared by equal coordinates)."""
    with open(path, 'rb') as f:
        data = f.read()
    count = struct.unpack_from('<I', data, 80)[0]
    if len(data) != 84 + 50 * count:
        raise ValueError('%s: %d bytes for %d facets' % (path, len(data), count))
    return [tuple(struct.unpack_from('<9f', data, 84 + 50 * k + 12)[3 * i:3 * i + 3]
                  for i in range(3)) for k in range(count)]


def read_obj(path):
    vertices, triangles = [], []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if fields and fields[0] == 'v':
                vertices.append(tuple(float(x) for x in fields[1:4]))
            elif fields and fields[0] == 'f':
                triangles.append(tuple(vertices[int(x.split('/')[0]) - 1] for x in fields[1:]))
    return triangles


def read_dae(path):
    root = ElementTree.parse(path).getroot()
    numbers = [float(x) for x in root.find('.//%sfloat_array' % COLLADA_NS).text.split()]
    vertices = [tuple(numbers[i:i + 3]) for i in range(0, len(numbers), 3)]
    indices = [int(x) for x in
               root.find('.//%striangles/%sp' % (COLLADA_NS, COLLADA_NS)).text.split()]
    return [tuple(vertices[i] for i in indices[k:k + 3]) for k in range(0, len(indices), 3)]


READERS = {'.stl': read_stl, '.obj': read_obj, '.dae': read_dae}


def closed_outward_problem(triangles):
    """None when every directed edge is matched by exactly one reversed edge and the enclosed
    volume is positive (divergence theorem); else what is wrong."""
    edges = {}
    volume = 0.0
    for a, b, c in triangles:
        if len({a, b, c}) != 3:
            return 'a degenerate facet %s' % ((a, b, c),)
        for edge in ((a, b), (b, c), (c, a)):
            edges[edge] = edges.get(edge, 0) + 1
        volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
    for (a, b), count in edges.items():
        if count != 1 or edges.get((b, a)) != 1:
            return 'edge %s-%s is used %d times, reversed %d times' % (a, b, count,
                                                                      edges.get((b, a), 0))
    if volume <= 0.0:
        return 'enclosed volume %g: facets face inward' % volume
    return None


class ExampleFilesTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.root = rospkg.RosPack().get_path(PKG)
        cls.meshes = sorted(os.listdir(os.path.join(cls.root, MESH_DIR)))

    def test_regenerated_files_are_identical(self):
        out = tempfile.mkdtemp(prefix='example_files_')
        try:
            result = subprocess.run(
                ['/usr/bin/python3', os.path.join(self.root, 'scripts', 'make_example.py'),
                 '--out', out], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                universal_newlines=True, timeout=600)
            self.assertEqual(result.returncode, 0, result.stderr)
            regenerated = sorted(os.listdir(os.path.join(out, MESH_DIR)))
            self.assertEqual(regenerated, self.meshes, 'the mesh files differ in name')
            for path in [os.path.join(MESH_DIR, name) for name in self.meshes] + GENERATED:
                self.assertTrue(filecmp.cmp(os.path.join(out, path), os.path.join(self.root, path),
                                            shallow=False),
                                '%s differs from the regenerated one' % path)
        finally:
            shutil.rmtree(out)

    def test_meshes_are_closed_and_outward(self):
        formats = set()
        for name in self.meshes:
            ext = os.path.splitext(name)[1]
            formats.add(ext)
            triangles = READERS[ext](os.path.join(self.root, MESH_DIR, name))
            self.assertGreaterEqual(len(triangles), 200, name)
            self.assertLessEqual(len(triangles), 5000, name)
            self.assertIsNone(closed_outward_problem(triangles), name)
        self.assertEqual(formats, {'.stl', '.obj', '.dae'})

    def test_every_method_reports_the_same_warnings(self):
        args = ['--urdf', os.path.join(self.root, 'urdf', 'dual_arm_shelf.urdf'),
                '--scene', os.path.join(self.root, 'config', 'dual_arm_shelf', 'scene.yaml'),
                '--json', os.path.join(self.root, 'test', 'bags', 'dual_arm_shelf.bag')]
        expected = None
        for method in METHODS:
            result = rosrun('replay', '--method', method, *args)
            self.assertEqual(result.returncode, 0, result.stderr)
            report = json.loads(result.stdout)
            self.assertEqual(report['incomplete_cycles'], 0, method)
            self.assertEqual(report['refused_messages'], {}, method)
            warnings = [c['warnings'] for c in report['per_cycle']]
            if expected is None:
                expected = warnings
                warning_cycles = sum(1 for w in warnings if w)
                print('dual_arm_shelf: %d cycles, %d with warnings' % (len(warnings),
                                                                       warning_cycles))
                self.assertGreater(warning_cycles, 0, 'the trajectory never warns')
                self.assertLess(warning_cycles, len(warnings), 'the trajectory is never clean')
            else:
                self.assertEqual(warnings, expected, method)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'example_files', ExampleFilesTest)
