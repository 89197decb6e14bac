#!/usr/bin/env python3
"""top_sim.launch's scene:= through scripts/top_sim_launch (which exits with the node's status): a shipped scene's
name runs that scene, an absolute and a relative path run their file (the relative one from the caller's
directory), an unknown name and a path that cannot be read stop the launch with status 2 and a message naming
what was asked for (and, for a name, every shipped scene)."""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import rospkg
import rospy
import rostest
import yaml
from top_sim.msg import TopState

PKG = rospkg.RosPack().get_path('top_sim')
SCENES = os.path.join(PKG, 'config', 'scenes')
LAUNCH = os.path.join(PKG, 'scripts', 'top_sim_launch')


def shipped():
    return sorted(f[:-len('.yaml')] for f in os.listdir(SCENES) if f.endswith('.yaml'))


def start_of(path):
    """The scene's start as TopState shows it: (alpha, spin)."""
    with open(path) as f:
        scene = yaml.safe_load(f)
    return scene['plane']['inclination'], scene['initial']['spin']


class SceneNames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='top_sim_scene_names_')
        with open(os.path.join(SCENES, 'tippe_top.yaml')) as f:
            text = f.read()
        # tippe_top is self-contained (no named tops or planes): a copy elsewhere loads; its spin marks it.
        assert 'spin: 100.0' in text
        cls.copy = os.path.join(cls.tmp, 'mine.yaml')
        with open(cls.copy, 'w') as f:
            f.write(text.replace('spin: 100.0', 'spin: 123.0'))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def launch(self, name, scene, cwd=None):
        return subprocess.Popen([sys.executable, LAUNCH, 'scene:=' + scene, 'rviz:=false', 'node_name:=' + name],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                cwd=cwd, start_new_session=True)

    def assert_runs(self, name, scene, alpha, spin, cwd=None):
        """The launch streams the scene's start state; Ctrl-C ends it with status 0."""
        first = {}
        sub = rospy.Subscriber('/%s/top_state' % name, TopState, lambda m: first.setdefault('msg', m))
        proc = self.launch(name, scene, cwd)
        try:
            deadline = time.time() + 60.0
            while 'msg' not in first and time.time() < deadline and proc.poll() is None:
                time.sleep(0.05)
        finally:
            sub.unregister()
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
            output, _ = proc.communicate(timeout=60.0)
        self.assertIn('msg', first, 'no TopState from %s; launch output:\n%s' % (scene, output[-3000:]))
        self.assertAlmostEqual(first['msg'].alpha, alpha, places=12)
        self.assertAlmostEqual(first['msg'].spin, spin, delta=1.0)
        self.assertEqual(proc.returncode, 0, output[-3000:])

    def assert_fails(self, name, scene, *parts):
        proc = self.launch(name, scene)
        output, _ = proc.communicate(timeout=120.0)
        self.assertEqual(proc.returncode, 2, output[-3000:])
        self.assertIn('required process %s' % name, output)
        for part in parts:
            self.assertIn(part, output)

    def test_shipped_scene_by_name(self):
        alpha, spin = start_of(os.path.join(SCENES, 'tippe_top.yaml'))
        self.assert_runs('scene_by_name', 'tippe_top', alpha, spin)

    def test_absolute_path(self):
        alpha, spin = start_of(self.copy)
        self.assertEqual(spin, 123.0)
        self.assert_runs('scene_absolute', self.copy, alpha, spin)

    def test_relative_path_is_the_caller_s(self):
        alpha, spin = start_of(self.copy)
        self.assert_runs('scene_relative', 'mine.yaml', alpha, spin, cwd=self.tmp)

    def test_unknown_name_lists_the_shipped_scenes(self):
        names = shipped()
        self.assertIn('tippe_top', names)
        self.assert_fails('scene_unknown', 'tippe_tap', 'tippe_tap: no shipped scene has this name', *names)

    def test_path_that_cannot_be_read_fails_the_launch(self):
        missing = os.path.join(self.tmp, 'no_such_dir', 'scene.yaml')
        self.assert_fails('scene_missing', missing, missing, 'cannot open the scene file')
        self.assert_fails('scene_dir', self.tmp + '/', 'is a directory')
        if os.geteuid() != 0:  # root reads any file: an unreadable file exists only for other users
            locked = os.path.join(self.tmp, 'locked.yaml')
            shutil.copy(self.copy, locked)
            os.chmod(locked, 0)
            self.assert_fails('scene_locked', locked, locked)


if __name__ == '__main__':
    rospy.init_node('test_scene_names')
    rostest.rosrun('top_sim', 'test_scene_names', SceneNames, sys.argv)
