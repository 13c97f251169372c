#!/usr/bin/python3
"""Writes the bundled dual_arm_shelf example's generated files, deterministically:

  urdf/meshes/dual_arm_shelf/*.stl|obj|dae   the robot's collision meshes (closed, outward)
  urdf/dual_arm_shelf.urdf                   the robot (its collision geometry: those meshes)
  test/bags/dual_arm_shelf.bag               a short trajectory of both arms (see WAYPOINTS)

The SRDF, planning scene and scene file (config/dual_arm_shelf/) are written by hand.
Regenerating must give byte-identical files (test/ros/example_files.test checks it), so every
number written is rounded first (vertices to 1e-6 of their unit, joint positions to 1e-9 rad)
and the bag's stamps are fixed.

  scripts/make_example.py [--out ROOT]     (default ROOT: the repository; files go under it)
"""
import argparse
import math
import os
import struct

import numpy as np

MESH_DIR = os.path.join('urdf', 'meshes', 'dual_arm_shelf')
BAG_PATH = os.path.join('test', 'bags', 'dual_arm_shelf.bag')
URDF_PATH = os.path.join('urdf', 'dual_arm_shelf.urdf')
PACKAGE_URL = 'package://arm_collision_monitor/urdf/meshes/dual_arm_shelf/'
SEGMENTS = 24         # facets around every surface of revolution
ARC_STEPS = 4         # profile points per quarter arc (rounded ends and edges)
DIGITS = 6            # vertices rounded to 1e-6 of the file's unit


# ----------------------------------------------------------------------------------------------
# Meshes: vertices (n x 3 float) and triangles (m x 3 int), counter-clockwise seen from outside.
# A part is the union of closed shells (they may overlap, as real CAD exports do).
# ----------------------------------------------------------------------------------------------
class Mesh(object):
    def __init__(self, vertices=None, triangles=None):
        self.vertices = np.zeros((0, 3)) if vertices is None else np.asarray(vertices, float)
        self.triangles = (np.zeros((0, 3), int) if triangles is None
                          else np.asarray(triangles, int))

    def __add__(self, other):
        return Mesh(np.vstack([self.vertices, other.vertices]),
                    np.vstack([self.triangles, other.triangles + len(self.vertices)]))

    def transformed(self, rotation=np.eye(3), translation=(0.0, 0.0, 0.0)):
        return Mesh(self.vertices @ np.asarray(rotation).T + translation, self.triangles)


def rot_x(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def lathe(profile, segments=SEGMENTS):
    """The surface of revolution about z of `profile`, a list of (radius, z) from the bottom
    pole (radius 0) to the top pole (radius 0), the solid on the axis side. Facets are ordered
    so that normals point outward."""
    assert profile[0][0] == 0.0 and profile[-1][0] == 0.0, 'the profile must start and end on z'
    angles = [2.0 * math.pi * k / segments for k in range(segments)]
    vertices = [(0.0, 0.0, profile[0][1])]
    rings = []  # index of each interior profile point's first vertex
    for radius, z in profile[1:-1]:
        rings.append(len(vertices))
        vertices.extend((radius * math.cos(a), radius * math.sin(a), z) for a in angles)
    top = len(vertices)
    vertices.append((0.0, 0.0, profile[-1][1]))
    triangles = []
    for j in range(segments):
        k = (j + 1) % segments
        triangles.append((0, rings[0] + k, rings[0] + j))
        for lower, upper in zip(rings[:-1], rings[1:]):
            triangles.append((lower + j, lower + k, upper + k))
            triangles.append((lower + j, upper + k, upper + j))
        triangles.append((rings[-1] + j, rings[-1] + k, top))
    return Mesh(vertices, triangles)


def rounded_cylinder(radius, z0, z1, edge_radius):
    """A cylinder along z from z0 to z1 whose rim edges are rounded by edge_radius (a capsule
    when edge_radius equals radius)."""
    e = edge_radius
    profile = [(0.0, z0)]
    for i in range(ARC_STEPS + 1):  # bottom rim: from the flat face round to the side
        t = 0.5 * math.pi * i / ARC_STEPS
        profile.append((radius - e + e * math.sin(t), z0 + e - e * math.cos(t)))
    for i in range(ARC_STEPS + 1):  # top rim
        t = 0.5 * math.pi * i / ARC_STEPS
        profile.append((radius - e + e * math.cos(t), z1 - e + e * math.sin(t)))
    profile.append((0.0, z1))
    # A capsule's arcs meet the axis themselves: drop the duplicated pole points.
    unique = [profile[0]]
    for p in profile[1:]:
        if abs(p[0] - unique[-1][0]) > 1e-12 or abs(p[1] - unique[-1][1]) > 1e-12:
            unique.append(p)
    unique = [unique[0]] + [p for p in unique[1:-1] if p[0] > 1e-12] + [unique[-1]]
    return lathe(unique)


def rounded_box(size, edge_radius, cells=4):
    """A box of full edge lengths `size`, centred on the origin, its edges and corners rounded
    by edge_radius: each face a grid, every grid point projected onto the rounded surface."""
    half = 0.5 * np.asarray(size, float)
    inner = half - edge_radius

    def samples(h, i):  # coordinates along one axis: the rounded band, then the flat part
        band = [-h + edge_radius * (1.0 - math.cos(0.5 * math.pi * s / 3)) for s in range(3)]
        flat = [-i + 2.0 * i * c / cells for c in range(cells + 1)]
        return band + flat + [-b for b in reversed(band)]

    axes = [samples(half[a], inner[a]) for a in range(3)]
    index = {}
    vertices, triangles = [], []

    def vertex(p):
        key = tuple(round(c, 12) for c in p)
        if key not in index:
            q = np.clip(p, -inner, inner)
            d = np.asarray(p) - q
            index[key] = len(vertices)
            vertices.append(q + edge_radius * d / np.linalg.norm(d))
        return index[key]

    for axis in range(3):
        u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
        for sign in (-1.0, 1.0):
            us, vs = axes[u_axis], axes[v_axis]
            for a in range(len(us) - 1):
                for b in range(len(vs) - 1):
                    corners = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = sign * half[axis]
                        p[u_axis] = us[a + du]
                        p[v_axis] = vs[b + dv]
                        corners.append(vertex(p))
                    # (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
                    if sign < 0:
                        corners.reverse()
                    triangles.append((corners[0], corners[1], corners[2]))
                    triangles.append((corners[0], corners[2], corners[3]))
    return Mesh(vertices, triangles)


def check_closed_outward(name, mesh):
    """Every edge used once in each direction (closed, consistently oriented), no degenerate
    facet, and a positive enclosed volume (outward normals)."""
    edges = {}
    for tri in mesh.triangles:
        assert len(set(tri)) == 3, name + ': degenerate facet'
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            edges[(a, b)] = edges.get((a, b), 0) + 1
    for (a, b), count in edges.items():
        assert count == 1 and edges.get((b, a)) == 1, '%s: edge %d-%d not closed' % (name, a, b)
    v = mesh.vertices[mesh.triangles]
    volume = np.einsum('ij,ij->i', v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0
    assert volume > 0.0, name + ': inward facets'


# ----------------------------------------------------------------------------------------------
# The robot's parts, each in its link frame (metres unless said otherwise). The arm links are
# alike: a rounded body along z from the joint to the next joint, and where the next joint
# pitches (axis y) a housing across it.
# ----------------------------------------------------------------------------------------------
# (length to the next joint, body radius, next joint pitches?) for links 1..7 of either arm.
ARM_LINKS = [(0.17, 0.070, True), (0.12, 0.070, False), (0.28, 0.060, True),
             (0.12, 0.060, False), (0.26, 0.050, True), (0.08, 0.050, False),
             (0.07, 0.040, False)]


def arm_link(length, radius, pitch):
    body = rounded_cylinder(radius, 0.0, length, 0.4 * radius)
    if not pitch:
        return body
    housing = rounded_cylinder(radius, -1.1 * radius, 1.1 * radius, 0.3 * radius)
    return body + housing.transformed(rot_x(-0.5 * math.pi), (0.0, 0.0, length))


def parts():
    """name -> (mesh, file format): the parts the URDF names."""
    result = {}
    # The pedestal: a foot plate and a column up to the torso (base_link, z 0 .. 0.75).
    foot = rounded_box((0.50, 0.50, 0.10), 0.03).transformed(translation=(0.0, 0.0, 0.05))
    column = rounded_cylinder(0.12, 0.09, 0.75, 0.02)
    result['pedestal'] = (foot + column, 'stl')
    # The torso, authored in millimetres as CAD exports often are (the URDF scales it by 1e-3):
    # a box 300 x 420 x 500 mm with a neck.
    torso = rounded_box((300.0, 420.0, 500.0), 40.0).transformed(translation=(0.0, 0.0, 250.0))
    neck = rounded_cylinder(60.0, 480.0, 580.0, 15.0)
    result['torso'] = (torso + neck, 'stl')
    # The camera head on the neck (OBJ).
    head = rounded_box((0.14, 0.24, 0.10), 0.03).transformed(translation=(0.02, 0.0, 0.05))
    result['head'] = (head, 'obj')
    # Each arm's base housing on its mounting plate.
    result['arm_base'] = (rounded_cylinder(0.075, 0.0, 0.12, 0.02), 'stl')
    for i, (length, radius, pitch) in enumerate(ARM_LINKS):
        result['arm_link%d' % (i + 1)] = (arm_link(length, radius, pitch), 'stl')
    # The gripper: a coupling on the flange and a palm (DAE); fingers (OBJ).
    coupling = rounded_cylinder(0.045, 0.0, 0.03, 0.005)
    palm = rounded_box((0.07, 0.18, 0.08), 0.015).transformed(translation=(0.0, 0.0, 0.065))
    result['gripper_palm'] = (coupling + palm, 'dae')
    finger = rounded_box((0.022, 0.016, 0.07), 0.005).transformed(translation=(0.0, 0.008, 0.035))
    result['gripper_finger'] = (finger, 'obj')
    return result


# ----------------------------------------------------------------------------------------------
# Writers. Every number is rounded first, so that the bytes do not depend on the last bits of
# the platform's trigonometry.
# ----------------------------------------------------------------------------------------------
def rounded(mesh):
    return np.round(mesh.vertices, DIGITS) + 0.0  # + 0.0 turns -0.0 into 0.0


def write_stl(path, name, mesh):
    v = rounded(mesh)
    with open(path, 'wb') as f:
        f.write(('arm_collision_monitor dual_arm_shelf ' + name).ljust(80).encode('ascii'))
        f.write(struct.pack('<I', len(mesh.triangles)))
        for tri in mesh.triangles:
            a, b, c = v[tri[0]], v[tri[1]], v[tri[2]]
            normal = np.cross(b - a, c - a)
            normal = np.round(normal / np.linalg.norm(normal), DIGITS) + 0.0
            f.write(struct.pack('<12fH', *normal, *a, *b, *c, 0))


def number(x):
    return ('%.6f' % x).rstrip('0').rstrip('.')


def write_obj(path, name, mesh):
    v = rounded(mesh)
    with open(path, 'w') as f:
        f.write('# arm_collision_monitor dual_arm_shelf %s (scripts/make_example.py)\n' % name)
        f.write('o %s\n' % name)
        for p in v:
            f.write('v %s %s %s\n' % tuple(number(c) for c in p))
        for tri in mesh.triangles:
            f.write('f %d %d %d\n' % tuple(i + 1 for i in tri))


def write_dae(path, name, mesh):
    """COLLADA 1.4.1 with one triangle mesh in metres. No up_axis: Y_UP is COLLADA's default,
    which readers (assimp) leave unrotated, so the vertices are the link frame's as written."""
    v = rounded(mesh)
    positions = ' '.join(number(c) for c in v.ravel())
    indices = ' '.join(str(i) for i in mesh.triangles.ravel())
    with open(path, 'w') as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n'
                '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">\n'
                '  <asset>\n'
                '    <contributor><authoring_tool>arm_collision_monitor scripts/make_example.py'
                '</authoring_tool></contributor>\n'
                '    <created>2026-01-01T00:00:00</created>\n'
                '    <modified>2026-01-01T00:00:00</modified>\n'
                '    <unit name="meter" meter="1"/>\n'
                '  </asset>\n'
                '  <library_geometries>\n'
                '    <geometry id="{n}-mesh" name="{n}">\n'
                '      <mesh>\n'
                '        <source id="{n}-positions">\n'
                '          <float_array id="{n}-positions-array" count="{c}">{p}</float_array>\n'
                '          <technique_common>\n'
                '            <accessor source="#{n}-positions-array" count="{vc}" stride="3">\n'
                '              <param name="X" type="float"/>\n'
                '              <param name="Y" type="float"/>\n'
                '              <param name="Z" type="float"/>\n'
                '            </accessor>\n'
                '          </technique_common>\n'
                '        </source>\n'
                '        <vertices id="{n}-vertices">\n'
                '          <input semantic="POSITION" source="#{n}-positions"/>\n'
                '        </vertices>\n'
                '        <triangles count="{tc}">\n'
                '          <input semantic="VERTEX" source="#{n}-vertices" offset="0"/>\n'
                '          <p>{i}</p>\n'
                '        </triangles>\n'
                '      </mesh>\n'
                '    </geometry>\n'
                '  </library_geometries>\n'
                '  <library_visual_scenes>\n'
                '    <visual_scene id="scene" name="scene">\n'
                '      <node id="{n}" name="{n}">\n'
                '        <instance_geometry url="#{n}-mesh"/>\n'
                '      </node>\n'
                '    </visual_scene>\n'
                '  </library_visual_scenes>\n'
                '  <scene>\n'
                '    <instance_visual_scene url="#scene"/>\n'
                '  </scene>\n'
                '</COLLADA>\n'.format(n=name, c=v.size, p=positions, vc=len(v),
                                      tc=len(mesh.triangles), i=indices))


WRITERS = {'stl': write_stl, 'obj': write_obj, 'dae': write_dae}


# ----------------------------------------------------------------------------------------------
# The URDF: a pedestal, a torso with a camera head, two 7-DOF arms on mounting plates on the
# torso's sides (their base z axis pointing outward, left +y, right -y), each with a parallel
# gripper (one actuated finger, the other its mimic). Geometry all meshes (visual = collision); the
# frames a real robot's URDF has without geometry (world, base_footprint, mounting plates, camera
# frames, flanges, tool0) are there too.
# ----------------------------------------------------------------------------------------------
SHOULDER_XYZ = {'left': (0.0, 0.21, 0.40), 'right': (0.0, -0.21, 0.40)}  # in torso_link
SHOULDER_ROLL = {'left': -0.5 * math.pi, 'right': 0.5 * math.pi}
# Per arm joint: (lower, upper rad, velocity rad/s, effort N m), after the larger 7-DOF arms.
ARM_JOINT_LIMITS = [(-2.9, 2.9, 1.7, 176.0), (-2.0, 2.0, 1.7, 176.0), (-2.9, 2.9, 1.7, 110.0),
                    (-2.2, 2.2, 2.2, 110.0), (-2.9, 2.9, 2.6, 40.0), (-2.0, 2.0, 3.1, 40.0),
                    (-3.0, 3.0, 3.1, 40.0)]
FINGER_TRAVEL_M = 0.04


def urdf_text():
    out = []

    def link(name, mesh=None, scale=None, rpy=None):
        if mesh is None:
            out.append('  <link name="%s"/>' % name)
            return
        origin = '' if rpy is None else '\n      <origin xyz="0 0 0" rpy="%s"/>' % rpy
        scale = '' if scale is None else ' scale="%s"' % scale
        body = ('%s\n      <geometry>\n        <mesh filename="%s%s"%s/>\n      </geometry>'
                % (origin, PACKAGE_URL, mesh, scale))
        out.append('  <link name="%s">\n    <visual>%s\n    </visual>\n    <collision>%s\n'
                   '    </collision>\n  </link>' % (name, body, body))

    def joint(name, kind, parent, child, xyz, rpy='0 0 0', axis=None, limit=None, mimic=None):
        text = ('  <joint name="%s" type="%s">\n    <parent link="%s"/>\n    <child link="%s"/>\n'
                '    <origin xyz="%s" rpy="%s"/>' % (name, kind, parent, child, xyz, rpy))
        if axis:
            text += '\n    <axis xyz="%s"/>' % axis
        if limit:
            text += ('\n    <limit lower="%s" upper="%s" velocity="%s" effort="%s"/>'
                     % tuple(number(x) for x in limit))
        if mimic:
            text += '\n    <mimic joint="%s" multiplier="1" offset="0"/>' % mimic
        out.append(text + '\n  </joint>')

    half_pi = number(0.5 * math.pi)
    out.append('<?xml version="1.0"?>\n<!-- A dual-arm robot (the bundled example dual_arm_shelf), '
               'written by scripts/make_example.py:\n     do not edit, regenerate. Visual and '
               'collision geometry: the same meshes; no inertias. -->\n'
               '<robot name="dual_arm_shelf">')
    link('world')
    joint('world_joint', 'fixed', 'world', 'base_footprint', '0 0 0')
    link('base_footprint')
    joint('base_footprint_joint', 'fixed', 'base_footprint', 'base_link', '0 0 0')
    link('base_link', 'pedestal.stl')
    joint('torso_joint', 'fixed', 'base_link', 'torso_link', '0 0 0.75')
    link('torso_link', 'torso.stl', scale='0.001 0.001 0.001')
    joint('head_joint', 'fixed', 'torso_link', 'head_link', '0 0 0.58')
    link('head_link', 'head.obj')
    joint('head_camera_joint', 'fixed', 'head_link', 'head_camera_link', '0.09 0 0.05')
    link('head_camera_link')
    joint('head_camera_optical_joint', 'fixed', 'head_camera_link', 'head_camera_optical_frame',
          '0 0 0', rpy='-%s 0 -%s' % (half_pi, half_pi))
    link('head_camera_optical_frame')
    for side in ('left', 'right'):
        p = side + '_'
        joint(p + 'mount_joint', 'fixed', 'torso_link', p + 'mount_plate',
              '%s %s %s' % tuple(number(x) for x in SHOULDER_XYZ[side]),
              rpy='%s 0 0' % number(SHOULDER_ROLL[side]))
        link(p + 'mount_plate')
        joint(p + 'base_joint', 'fixed', p + 'mount_plate', p + 'base_link', '0 0 0.01')
        link(p + 'base_link', 'arm_base.stl')
        parent, offset = p + 'base_link', 0.12
        for i, (length, _, _) in enumerate(ARM_LINKS):
            axis = '0 1 0' if i % 2 == 1 else '0 0 1'
            joint('%sjoint%d' % (p, i + 1), 'revolute', parent, '%slink%d' % (p, i + 1),
                  '0 0 %s' % number(offset), axis=axis, limit=ARM_JOINT_LIMITS[i])
            link('%slink%d' % (p, i + 1), 'arm_link%d.stl' % (i + 1))
            parent, offset = '%slink%d' % (p, i + 1), length
        joint(p + 'flange_joint', 'fixed', parent, p + 'flange', '0 0 %s' % number(offset))
        link(p + 'flange')
        joint(p + 'hand_joint', 'fixed', p + 'flange', p + 'hand', '0 0 0')
        link(p + 'hand', 'gripper_palm.dae')
        joint(p + 'finger_joint', 'prismatic', p + 'hand', p + 'finger_left', '0 0 0.105',
              axis='0 1 0', limit=(0.0, FINGER_TRAVEL_M, 0.2, 20.0))
        link(p + 'finger_left', 'gripper_finger.obj')
        joint(p + 'finger_mimic_joint', 'prismatic', p + 'hand', p + 'finger_right', '0 0 0.105',
              axis='0 -1 0', limit=(0.0, FINGER_TRAVEL_M, 0.2, 20.0), mimic=p + 'finger_joint')
        link(p + 'finger_right', 'gripper_finger.obj', rpy='0 0 %s' % number(math.pi))
        joint(p + 'tool0_joint', 'fixed', p + 'hand', p + 'tool0', '0 0 0.16')
        link(p + 'tool0')
    out.append('</robot>\n')
    return '\n'.join(out)


# ----------------------------------------------------------------------------------------------
# The trajectory: joint-space waypoints of both arms, frozen, blended by minimum-jerk segments
# and sampled every 50 ms. Each arm publishes on its own topic (the node's default inputs), left
# first in each cycle. The poses were found by inverse kinematics for the tool0 points below
# (m, in world; the gripper pointing +x), the right arm's as mirror images of the left's.
# ----------------------------------------------------------------------------------------------
CYCLE_S = 0.05
START_STAMP_S = 1700000000
ARM_JOINTS = ['joint%d' % i for i in range(1, 8)] + ['finger_joint']
# Left arm joint1..7 (rad).
READY = [0.727, 0.716, -0.178, 2.143, 0.620, -1.267, 1.500]          # tool0 (0.62, 0.45, 0.95)
BEFORE_SHELF = [0.215, 1.465, -0.459, 1.918, 0.147, -1.726, 2.055]   # (0.64, 0.22, 1.24)
AT_CAN = [0.196, 1.494, -0.375, 1.218, 0.175, -1.081, 1.867]         # (0.88, 0.22, 1.17)
INTO_SHELF = [0.179, 1.382, -0.407, 1.482, 0.096, -1.240, 1.941]     # (0.82, 0.25, 1.21)
HAND_OVER = [0.443, 1.621, -0.282, 1.686, 0.439, -1.599, 1.896]      # (0.66, 0.13, 1.10)
OPEN_M, HALF_OPEN_M = 0.04, 0.02


def mirrored(q):
    """The right arm's joint angles for the mirror image (in the plane y = 0) of the left arm's
    pose q: the mounts mirror each other, so roll joints change sign and pitch joints keep it."""
    return [-a if i % 2 == 0 else a for i, a in enumerate(q)]


# (time s, left joints + finger, right joints + finger)
WAYPOINTS = [
    (0.0, READY + [HALF_OPEN_M], mirrored(READY) + [HALF_OPEN_M]),
    (1.5, READY + [HALF_OPEN_M], mirrored(READY) + [HALF_OPEN_M]),          # clean
    (3.5, BEFORE_SHELF + [OPEN_M], mirrored(BEFORE_SHELF) + [OPEN_M]),
    (5.5, AT_CAN + [OPEN_M], mirrored(INTO_SHELF) + [OPEN_M]),  # left around can_left, right
    (6.5, AT_CAN + [OPEN_M], mirrored(INTO_SHELF) + [OPEN_M]),  # into the shelf by box_right
    (8.0, BEFORE_SHELF + [OPEN_M], mirrored(BEFORE_SHELF) + [OPEN_M]),
    (10.0, READY + [HALF_OPEN_M], mirrored(READY) + [HALF_OPEN_M]),
    (11.0, READY + [HALF_OPEN_M], mirrored(READY) + [HALF_OPEN_M]),         # clean
    (13.0, HAND_OVER + [HALF_OPEN_M], mirrored(HAND_OVER) + [HALF_OPEN_M]),  # hands meet
    (14.0, HAND_OVER + [HALF_OPEN_M], mirrored(HAND_OVER) + [HALF_OPEN_M]),
    (16.0, READY + [HALF_OPEN_M], mirrored(READY) + [HALF_OPEN_M]),
    (17.0, READY + [HALF_OPEN_M], mirrored(READY) + [HALF_OPEN_M]),         # clean
]


def min_jerk(s):
    return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)


def trajectory():
    """[(time s, left q, right q)] every CYCLE_S from the first waypoint to the last."""
    end_s = WAYPOINTS[-1][0]
    cycles = int(round(end_s / CYCLE_S)) + 1
    samples = []
    segment = 0
    for k in range(cycles):
        t = k * CYCLE_S
        while segment + 2 < len(WAYPOINTS) and t > WAYPOINTS[segment + 1][0]:
            segment += 1
        t0, left0, right0 = WAYPOINTS[segment]
        t1, left1, right1 = WAYPOINTS[min(segment + 1, len(WAYPOINTS) - 1)]
        s = 0.0 if t1 <= t0 else min_jerk(min(max((t - t0) / (t1 - t0), 0.0), 1.0))
        q = [[round(a + s * (b - a), 9) + 0.0 for a, b in zip(q0, q1)]
             for q0, q1 in ((left0, left1), (right0, right1))]
        samples.append((k, q[0], q[1]))
    return samples


def write_bag(path):
    # Imported here: the meshes need no ROS.
    import genpy
    import rosbag
    from sensor_msgs.msg import JointState
    with rosbag.Bag(path, 'w', compression=rosbag.Compression.NONE) as bag:
        for k, left, right in trajectory():
            stamp = genpy.Time(START_STAMP_S) + genpy.Duration(nsecs=k * int(CYCLE_S * 1e9))
            for side, q in (('left', left), ('right', right)):
                msg = JointState()
                msg.header.seq = k
                msg.header.stamp = stamp
                msg.name = ['%s_%s' % (side, j) for j in ARM_JOINTS]
                msg.position = q
                bag.write('%s_arm/joint_states' % side, msg, stamp)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--out', default=os.path.dirname(os.path.dirname(os.path.abspath(
        __file__))), help='the root the files are written under (default: the repository)')
    args = parser.parse_args()
    mesh_dir = os.path.join(args.out, MESH_DIR)
    os.makedirs(mesh_dir, exist_ok=True)
    for name, (mesh, fmt) in sorted(parts().items()):
        check_closed_outward(name, mesh)
        WRITERS[fmt](os.path.join(mesh_dir, '%s.%s' % (name, fmt)), name, mesh)
    with open(os.path.join(args.out, URDF_PATH), 'w') as f:
        f.write(urdf_text())
    bag_path = os.path.join(args.out, BAG_PATH)
    os.makedirs(os.path.dirname(bag_path), exist_ok=True)
    write_bag(bag_path)


if __name__ == '__main__':
    main()
