#!/usr/bin/python3
"""Headless rviz check (test/ros/rviz_screenshot.test): rviz with the package's config, under
Xvfb with software GL, shows the monitor's markers over the robot's own model (RobotModel on
robot_description); with both arms home the warning colour is (almost) absent from the screen,
with the arms tilted into each other it covers many pixels; the octree's cell lines are on
screen in both.

Screenshots: xwd -root | convert. They are kept in ~screenshot_dir (default: a new temporary
directory, printed) as clear.png and warning.png, beside rviz.log and xvfb.log (the output of
rviz and of Xvfb); a failure message quotes the end of both and rviz's exit status."""
import http.client
import os
import subprocess
import sys
import tempfile
import threading
import time
import unittest
import xmlrpc.client

import numpy
import rosgraph
import rospkg
import rospy
import rostest

from acm_test_util import (HOME, LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT, MonitorClient)

PACKAGE = 'arm_collision_monitor'
NODE = '/arm_collision_monitor'
WIDTH, HEIGHT = 1280, 800
# MarkerPalette::kWarningRgb is pure red; lit and blended with the background it stays red-
# dominant. Clear primitives are green-dominant (kClearRgb).
MIN_WARNING_PIXELS = 1000    # the tilted arms' warned links: ~2800 at 1280x800
MAX_WARNING_PIXELS_CLEAR = 150  # anti-aliased edges: ~30 seen
MIN_CLEAR_PIXELS = 2000
# The octree's cell lines (MarkerBuilder::AddIndexCells): leaves holding moving primitives are
# drawn in (0.1, 0.6, 1.0) at alpha 0.8, blue-dominant on screen (static leaves are grey, like
# the grid, and not counted). In the 3D view: ~450 at home, ~2300 in the warning pose; ~0 with
# the index_cells namespace switched off.
MIN_CELL_PIXELS = 200
# The 3D view's left edge in rviz/monitor.rviz's window layout (1280x800, Displays dock left).
VIEW_LEFT_PX = 364
START_TIMEOUT_S = 90.0
SHOT_TIMEOUT_S = 60.0
POLL_PERIOD_S = 0.5
TOOL_TIMEOUT_S = 30.0
LOG_TAIL_LINES = 25


def count_colours(rgb):
    r = rgb[:, 0].astype(numpy.int32)
    g = rgb[:, 1].astype(numpy.int32)
    b = rgb[:, 2].astype(numpy.int32)
    warning = (r > 100) & (g * 10 < r * 3) & (b * 10 < r * 3)
    clear = (g > 100) & (r * 10 < g * 7) & (b * 10 < g * 7)
    # Counted in the 3D view only: the Displays dock's display names are blue too.
    cells = ((b > 150) & (g * 13 < b * 10) & (r * 10 < b * 3)).reshape(HEIGHT, WIDTH)
    return int(warning.sum()), int(clear.sum()), int(cells[:, VIEW_LEFT_PX:].sum())


class RvizScreenshotTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('rviz_screenshot_test')
        cls.client = MonitorClient(NODE)
        assert cls.client.wait_connected(), 'the monitor never subscribed to its input'
        cls.shot_dir = rospy.get_param('~screenshot_dir', '') or tempfile.mkdtemp(
            prefix='acm_rviz_')
        os.makedirs(cls.shot_dir, exist_ok=True)
        print('rviz_screenshot_test: screenshots in %s' % cls.shot_dir)
        cls.pose = (HOME, HOME)
        cls.publishing = True
        cls.publisher = threading.Thread(target=cls.publish_loop)
        cls.publisher.daemon = True
        cls.publisher.start()
        cls.xvfb = None
        cls.rviz = None
        cls.retried_error = 'none'
        cls.display = cls.start_xvfb()
        cls.start_rviz()

    @classmethod
    def tearDownClass(cls):
        cls.publishing = False
        for proc in (cls.rviz, cls.xvfb):
            if proc is not None and proc.poll() is None:
                proc.terminate()
                try:
                    proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    proc.kill()

    @classmethod
    def publish_loop(cls):
        # The monitor publishes markers on its cycles: keep it cycling at 20 Hz.
        while cls.publishing and not rospy.is_shutdown():
            cls.client.publish_pose(*cls.pose)
            time.sleep(0.05)

    @classmethod
    def start_xvfb(cls):
        read_fd, write_fd = os.pipe()
        with open(os.path.join(cls.shot_dir, 'xvfb.log'), 'w') as log:
            cls.xvfb = subprocess.Popen(
                ['Xvfb', '-displayfd', str(write_fd), '-screen', '0',
                 '%dx%dx24' % (WIDTH, HEIGHT), '-nolisten', 'tcp'],
                pass_fds=(write_fd,), stdout=log, stderr=subprocess.STDOUT)
        os.close(write_fd)
        with os.fdopen(read_fd) as f:
            number = f.readline().strip()  # written once the server accepts connections
        assert number, 'Xvfb did not start\n' + cls.diagnosis()
        return ':' + number

    @classmethod
    def start_rviz(cls):
        env = dict(os.environ, DISPLAY=cls.display, LIBGL_ALWAYS_SOFTWARE='1')
        config = os.path.join(rospkg.RosPack().get_path(PACKAGE), 'rviz', 'monitor.rviz')
        with open(os.path.join(cls.shot_dir, 'rviz.log'), 'w') as log:
            cls.rviz = subprocess.Popen(['rviz', '-d', config, '__name:=acm_test_rviz'],
                                        env=env, stdout=log, stderr=subprocess.STDOUT)

    @classmethod
    def diagnosis(cls):
        """For failure messages: how rviz and Xvfb stand, the last error retried, and the end
        of both programs' output."""
        lines = []
        for name, proc in (('rviz', cls.rviz), ('Xvfb', cls.xvfb)):
            code = None if proc is None else proc.poll()
            lines.append('%s: %s' % (name, 'not started' if proc is None else
                                     'running' if code is None else 'exited with %d' % code))
        lines.append('last error retried (screenshot tools, master): %s' % cls.retried_error)
        for log in ('rviz.log', 'xvfb.log'):
            try:
                with open(os.path.join(cls.shot_dir, log), errors='replace') as f:
                    tail = f.readlines()[-LOG_TAIL_LINES:]
            except OSError as e:
                tail = ['(unreadable: %s)\n' % e]
            lines.append('--- the end of %s ---\n%s' % (log, ''.join(tail).rstrip()))
        return '\n'.join(lines)

    def assert_rviz_running(self):
        if self.rviz.poll() is not None:
            self.fail('rviz exited\n' + self.diagnosis())

    def wait_rviz_subscribed(self):
        master = rosgraph.Master('/rviz_screenshot_test')
        deadline = time.time() + START_TIMEOUT_S
        while time.time() < deadline:
            self.assert_rviz_running()
            try:
                _, subscribers, _ = master.getSystemState()
            except (OSError, http.client.HTTPException, xmlrpc.client.Error,
                    rosgraph.MasterException) as e:  # a busy master may drop a call
                RvizScreenshotTest.retried_error = 'master: %s' % e
                subscribers = []
            for topic, nodes in subscribers:
                if topic == NODE + '/markers' and '/acm_test_rviz' in nodes:
                    return
            time.sleep(POLL_PERIOD_S)
        self.fail('rviz never subscribed to the markers\n' + self.diagnosis())

    def screenshot(self, png_path):
        """The screen's pixels (n x 3 RGB), also saved to png_path; None if xwd or convert
        failed or timed out (the error is kept for the failure message): a screenshot tool's
        hiccup on a loaded machine is not what this test examines, so the caller shoots again
        until its deadline."""
        def run(args, data=None):
            return subprocess.run(args, input=data, stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, timeout=TOOL_TIMEOUT_S,
                                  check=True).stdout
        try:
            xwd = run(['xwd', '-root', '-silent', '-display', self.display])
            raw = run(['convert', 'xwd:-', '-depth', '8', '-write', png_path, 'rgb:-'], xwd)
        except subprocess.CalledProcessError as e:
            RvizScreenshotTest.retried_error = '%s (stderr: %s)' % (
                e, e.stderr.decode(errors='replace').strip())
            return None
        except subprocess.TimeoutExpired as e:
            RvizScreenshotTest.retried_error = str(e)
            return None
        if len(raw) != WIDTH * HEIGHT * 3:
            RvizScreenshotTest.retried_error = 'convert gave %d bytes for %dx%d RGB' % (
                len(raw), WIDTH, HEIGHT)
            return None
        return numpy.frombuffer(raw, dtype=numpy.uint8).reshape(-1, 3)

    def shoot_until(self, name, predicate):
        """Screenshots until predicate(warning_pixels, clear_pixels, cell_pixels); returns the
        counts of the last one."""
        path = os.path.join(self.shot_dir, name + '.png')
        deadline = time.time() + SHOT_TIMEOUT_S
        counts = None
        while time.time() < deadline:
            self.assert_rviz_running()
            pixels = self.screenshot(path)
            if pixels is not None:
                counts = count_colours(pixels)
                if predicate(*counts):
                    break
            time.sleep(POLL_PERIOD_S)
        if counts is None:
            self.fail('no screenshot could be taken in %.0f s\n%s'
                      % (SHOT_TIMEOUT_S, self.diagnosis()))
        print('rviz_screenshot_test: %s: %d warning-coloured, %d clear-coloured, %d '
              'cell-coloured pixels (%s)' % (name, counts[0], counts[1], counts[2], path))
        return counts

    def test_warning_colour_on_screen(self):
        t0 = time.time()
        self.wait_rviz_subscribed()
        c = self.client
        self.assertIsNotNone(c.publish_until(lambda: None, lambda r: not r.warnings and not r.stop,
                                             timeout_s=20.0))
        warning, clear, cells = self.shoot_until(
            'clear', lambda w, g, cells: g >= MIN_CLEAR_PIXELS and cells >= MIN_CELL_PIXELS)
        self.assertGreaterEqual(clear, MIN_CLEAR_PIXELS,
                                'the clear primitives are not drawn\n' + self.diagnosis())
        self.assertLessEqual(warning, MAX_WARNING_PIXELS_CLEAR,
                             'warning colour on screen without a warning\n' + self.diagnosis())
        self.assertGreaterEqual(cells, MIN_CELL_PIXELS,
                                'the octree cell lines are not drawn\n' + self.diagnosis())

        RvizScreenshotTest.pose = (LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT)
        report = c.publish_until(lambda: None, lambda r: len(r.warnings) > 0, timeout_s=20.0)
        self.assertIsNotNone(report, 'no warning report in the warning pose')
        warning, _, cells = self.shoot_until(
            'warning', lambda w, g, cells: w >= MIN_WARNING_PIXELS and cells >= MIN_CELL_PIXELS)
        self.assertGreaterEqual(warning, MIN_WARNING_PIXELS,
                                'the warning colour is not on screen during a warning\n'
                                + self.diagnosis())
        self.assertGreaterEqual(cells, MIN_CELL_PIXELS,
                                'the octree cell lines are not drawn in the warning pose\n'
                                + self.diagnosis())
        print('rviz_screenshot_test: %.1f s from rviz start to the last screenshot'
              % (time.time() - t0))


if __name__ == '__main__':
    rostest.rosrun(PACKAGE, 'rviz_screenshot', RvizScreenshotTest, sys.argv)
