#!/usr/bin/python3
"""Headless rviz check (test/ros/rviz_screenshot.test): rviz with the package's config, under
Xvfb with software GL, shows the monitor's markers; with both arms home the warning colour is
(almost) absent from the screen, with the arms tilted into each other it covers many pixels.

Screenshots: xwd -root | convert. They are kept in ~screenshot_dir (default: a new temporary
directory, printed) as clear.png and warning.png."""
import os
import subprocess
import sys
import tempfile
import threading
import time
import unittest

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
START_TIMEOUT_S = 90.0
SHOT_TIMEOUT_S = 60.0
POLL_PERIOD_S = 0.5


def count_colours(rgb):
    r = rgb[:, 0].astype(numpy.int32)
    g = rgb[:, 1].astype(numpy.int32)
    b = rgb[:, 2].astype(numpy.int32)
    warning = (r > 100) & (g * 10 < r * 3) & (b * 10 < r * 3)
    clear = (g > 100) & (r * 10 < g * 7) & (b * 10 < g * 7)
    return int(warning.sum()), int(clear.sum())


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
        cls.xvfb = subprocess.Popen(
            ['Xvfb', '-displayfd', str(write_fd), '-screen', '0', '%dx%dx24' % (WIDTH, HEIGHT),
             '-nolisten', 'tcp'], pass_fds=(write_fd,), stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL)
        os.close(write_fd)
        with os.fdopen(read_fd) as f:
            number = f.readline().strip()  # written once the server accepts connections
        assert number, 'Xvfb did not start'
        return ':' + number

    @classmethod
    def start_rviz(cls):
        env = dict(os.environ, DISPLAY=cls.display, LIBGL_ALWAYS_SOFTWARE='1')
        config = os.path.join(rospkg.RosPack().get_path(PACKAGE), 'rviz', 'monitor.rviz')
        cls.rviz = subprocess.Popen(['rviz', '-d', config, '__name:=acm_test_rviz'], env=env,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def wait_rviz_subscribed(self):
        master = rosgraph.Master('/rviz_screenshot_test')
        deadline = time.time() + START_TIMEOUT_S
        while time.time() < deadline:
            self.assertIsNone(self.rviz.poll(), 'rviz exited early')
            _, subscribers, _ = master.getSystemState()
            for topic, nodes in subscribers:
                if topic == NODE + '/markers' and '/acm_test_rviz' in nodes:
                    return
            time.sleep(POLL_PERIOD_S)
        self.fail('rviz never subscribed to the markers')

    def screenshot(self, png_path):
        xwd = subprocess.run(['xwd', '-root', '-silent', '-display', self.display],
                             stdout=subprocess.PIPE, timeout=30, check=True).stdout
        raw = subprocess.run(['convert', 'xwd:-', '-depth', '8', 'rgb:-'], input=xwd,
                             stdout=subprocess.PIPE, timeout=30, check=True).stdout
        subprocess.run(['convert', 'xwd:-', png_path], input=xwd, timeout=30, check=True)
        return numpy.frombuffer(raw, dtype=numpy.uint8).reshape(-1, 3)

    def shoot_until(self, name, predicate):
        """Screenshots until predicate(warning_pixels, clear_pixels); returns the counts of the
        last one."""
        path = os.path.join(self.shot_dir, name + '.png')
        deadline = time.time() + SHOT_TIMEOUT_S
        counts = (0, 0)
        while time.time() < deadline:
            self.assertIsNone(self.rviz.poll(), 'rviz exited')
            counts = count_colours(self.screenshot(path))
            if predicate(*counts):
                break
            time.sleep(POLL_PERIOD_S)
        print('rviz_screenshot_test: %s: %d warning-coloured, %d clear-coloured pixels (%s)'
              % (name, counts[0], counts[1], path))
        return counts

    def test_warning_colour_on_screen(self):
        t0 = time.time()
        self.wait_rviz_subscribed()
        c = self.client
        self.assertIsNotNone(c.publish_until(lambda: None, lambda r: not r.warnings and not r.stop,
                                             timeout_s=20.0))
        warning, clear = self.shoot_until('clear', lambda w, g: g >= MIN_CLEAR_PIXELS)
        self.assertGreaterEqual(clear, MIN_CLEAR_PIXELS, 'the clear primitives are not drawn')
        self.assertLessEqual(warning, MAX_WARNING_PIXELS_CLEAR,
                             'warning colour on screen without a warning')

        RvizScreenshotTest.pose = (LEFT_TOWARDS_RIGHT, RIGHT_TOWARDS_LEFT)
        report = c.publish_until(lambda: None, lambda r: len(r.warnings) > 0, timeout_s=20.0)
        self.assertIsNotNone(report, 'no warning report in the warning pose')
        warning, _ = self.shoot_until('warning', lambda w, g: w >= MIN_WARNING_PIXELS)
        self.assertGreaterEqual(warning, MIN_WARNING_PIXELS,
                                'the warning colour is not on screen during a warning')
        print('rviz_screenshot_test: %.1f s from rviz start to the last screenshot'
              % (time.time() - t0))


if __name__ == '__main__':
    rostest.rosrun(PACKAGE, 'rviz_screenshot', RvizScreenshotTest, sys.argv)
