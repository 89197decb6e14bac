#!/usr/bin/env python3
"""top_sim_node refuses at start what top_sim_run refuses, with exit status 2 and a message naming the key, and
scripts/top_sim_launch passes that status on (roslaunch exits 0); ~cpu_affinity, checked and applied before
roscpp's threads start. Each case starts its own node process."""
import os
import subprocess
import sys
import tempfile
import unittest

import rospkg
import rospy
import rostest
from top_sim.msg import TopState

PKG = rospkg.RosPack().get_path('top_sim')
DEFAULT_SCENE = os.path.join(PKG, 'config', 'scenes', 'default.yaml')


def node_binary():
    """top_sim_node of the workspace under test (catkin's devel space)."""
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
        candidate = os.path.join(prefix, 'lib', 'top_sim', 'top_sim_node')
        if os.path.isfile(candidate):
            return candidate
    raise RuntimeError('top_sim_node not found under CMAKE_PREFIX_PATH')


def scene_file(text):
    f = tempfile.NamedTemporaryFile('w', suffix='.yaml', delete=False)
    f.write(text)
    f.close()
    return f.name


def run_node(name, params, timeout=30.0):
    """Runs top_sim_node as ~name with private parameters (rosrun syntax); returns (status, output)."""
    args = [node_binary(), '__name:=' + name] + ['_%s:=%s' % kv for kv in params.items()]
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout,
                       universal_newlines=True)
    return p.returncode, p.stdout


class StartErrors(unittest.TestCase):
    def assert_refused(self, name, params, *parts):
        status, output = run_node(name, params)
        self.assertEqual(status, 2, output)
        for part in parts:
            self.assertIn(part, output)

    def test_duplicate_key_is_refused_as_by_top_sim_run(self):
        # rosparam took the last of two `top:` keys; the command line refused the file.
        path = scene_file('top: aluminium\ntop: steel\nfriction: pmma\n')
        self.assert_refused('start_dup', {'scene_file': path}, 'bad scene', path, 'top: given twice')

    def test_unknown_top_level_key_is_refused(self):
        # `spin: 300` at the top level was dropped silently (it is dynamic_reconfigure's name).
        with open(DEFAULT_SCENE) as f:
            path = scene_file(f.read() + 'spin: 300.0\n')
        self.assert_refused('start_unknown', {'scene_file': path}, 'spin: unknown key')

    def test_number_syntax_is_the_core_loader_s(self):
        # PyYAML (rosparam) reads 1e-3 as a string; the core's loader reads it as a number, as top_sim_run does.
        with open(DEFAULT_SCENE) as f:
            text = f.read().replace('dt: 1.0e-4', 'dt: 1e-300')
        self.assert_refused('start_dt', {'scene_file': scene_file(text)}, 'integrator.dt: 1e-300 is out of range')

    def test_scene_file_and_scene_parameter_together_are_refused(self):
        rospy.set_param('/start_both/scene/initial/spin', 300.0)
        self.assert_refused('start_both', {'scene_file': DEFAULT_SCENE}, 'the scene comes from one place',
                            '/start_both/scene')

    def test_scene_key_outside_the_scene_namespace_is_unknown(self):
        # As top_sim_run refuses an unknown key, the node refuses one under ~ (here a scene key put beside the scene).
        rospy.set_param('/start_stray/initial/spin', 300.0)
        self.assert_refused('start_stray', {'scene_file': DEFAULT_SCENE}, '/start_stray/initial: unknown parameter',
                            '/start_stray/scene')

    def test_scene_text_parameter_gets_the_loader_s_checks(self):
        # ~scene as YAML text is read like a file: a duplicate key is refused, as top_sim_run refuses it.
        rospy.set_param('/start_text/scene', 'top: aluminium\ntop: steel\nfriction: pmma\n')
        self.assert_refused('start_text', {}, 'bad scene', '/start_text/scene', 'top: given twice')

    def test_bad_dynamic_reconfigure_value_at_start_is_refused(self):
        rospy.set_param('/start_spin_big/spin', 1.0e308)
        self.assert_refused('start_spin_big', {'scene_file': DEFAULT_SCENE}, 'spin = 1e+308', '|spin| <= 1e+06')

    def test_dynamic_reconfigure_value_at_start_is_applied(self):
        # ~spin is dynamic_reconfigure's: at start it is the initial value, through the core's validation.
        rospy.set_param('/start_spin/spin', 300.0)
        rospy.set_param('/start_spin/scene_file', DEFAULT_SCENE)
        first = {}

        def on_state(m):
            first.setdefault('msg', m)
        sub = rospy.Subscriber('/start_spin/top_state', TopState, on_state)
        proc = subprocess.Popen([node_binary(), '__name:=start_spin'])
        try:
            deadline = rospy.Time.now() + rospy.Duration(30.0)
            while 'msg' not in first and rospy.Time.now() < deadline and proc.poll() is None:
                rospy.sleep(0.05)
        finally:
            proc.terminate()
            proc.wait(timeout=30.0)
            sub.unregister()
        self.assertIn('msg', first, 'no TopState from the node')
        self.assertAlmostEqual(first['msg'].spin, 300.0, delta=1.0)

    def test_cpu_affinity_out_of_range_is_refused(self):
        self.assert_refused('start_cpu_bad', {'scene_file': DEFAULT_SCENE, 'cpu_affinity': 4096},
                            '/start_cpu_bad/cpu_affinity = 4096', 'a CPU in [0, %d]' % (os.cpu_count() - 1))

    def test_cpu_affinity_pins_every_thread_of_the_node(self):
        # The kernel's account of each thread of the running node (roscpp's included) is the reference.
        cpu = os.cpu_count() - 1
        rospy.set_param('/start_cpu/scene_file', DEFAULT_SCENE)
        rospy.set_param('/start_cpu/cpu_affinity', cpu)
        first = {}
        sub = rospy.Subscriber('/start_cpu/top_state', TopState, lambda m: first.setdefault('msg', m))
        proc = subprocess.Popen([node_binary(), '__name:=start_cpu'])
        try:
            deadline = rospy.Time.now() + rospy.Duration(30.0)
            while 'msg' not in first and rospy.Time.now() < deadline and proc.poll() is None:
                rospy.sleep(0.05)
            tasks = '/proc/%d/task' % proc.pid
            allowed = {}
            for tid in os.listdir(tasks):
                with open(os.path.join(tasks, tid, 'status')) as f:
                    allowed[tid] = [l.split()[1] for l in f if l.startswith('Cpus_allowed_list:')][0]
        finally:
            proc.terminate()
            proc.wait(timeout=30.0)
            sub.unregister()
        self.assertIn('msg', first, 'no TopState from the node')
        self.assertGreater(len(allowed), 2, allowed)  # the loop and roscpp's threads
        self.assertEqual(set(allowed.values()), {str(cpu)}, allowed)

    def test_launch_wrapper_returns_the_node_s_status(self):
        path = scene_file('top: aluminium\ntop: steel\nfriction: pmma\n')
        launch = os.path.join(PKG, 'scripts', 'top_sim_launch')
        p = subprocess.run([sys.executable, launch, 'scene:=' + path, 'rviz:=false', 'node_name:=start_launch'],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120, universal_newlines=True)
        self.assertEqual(p.returncode, 2, p.stdout[-3000:])
        self.assertIn('top: given twice', p.stdout)
        self.assertIn('required process start_launch', p.stdout)


if __name__ == '__main__':
    rospy.init_node('test_start_errors')
    rostest.rosrun('top_sim', 'test_start_errors', StartErrors, sys.argv)
