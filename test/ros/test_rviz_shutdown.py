#!/usr/bin/env python3
"""rviz, the control panel and top_sim_interactive stop cleanly on SIGINT (issue 46): for each body scene the node
and top_sim_interactive run, rviz with rviz/top_sim.rviz (its MarkerArray and InteractiveMarkers displays and the
Top control panel) is started RUNS times, draws the node's markers for a few seconds and gets SIGINT, as roslaunch
stops it on Ctrl-C while the node still publishes; every rviz exit status must be 0 (a crash at shutdown is -11 or
-6). Then top_sim_interactive and the node get SIGINT and must exit 0 too.

rviz needs an X display with GLX: the test starts its own Xvfb (Debian package xvfb; Mesa's software renderer), so
it runs the same with or without a desktop, in CI included."""
import os
import signal
import subprocess
import sys
import time
import unittest

import rospkg
import rospy
import rostest
from visualization_msgs.msg import MarkerArray

SCENES = os.environ.get('TOP_SIM_RVIZ_SCENES', 'default tippe_top_stem top_life euler_disk').split()
RUNS = int(os.environ.get('TOP_SIM_RVIZ_RUNS', '5'))
DRAW_SECONDS = 2.0      # wall seconds rviz draws the markers after it has subscribed to them
START_TIMEOUT = 40.0    # wall seconds for a process to come up (rviz under Mesa on a loaded machine)
STOP_TIMEOUT = 20.0     # roslaunch's SIGINT grace is 15 s; longer than this is a hang, not a clean exit


def start_xvfb():
    """Xvfb on the first free display (-displayfd writes its number once it accepts clients)."""
    read, write = os.pipe()
    xvfb = subprocess.Popen(['Xvfb', '-displayfd', str(write), '-screen', '0', '1280x800x24', '-nolisten', 'tcp'],
                            pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as f:
        display = f.readline().strip()
    if not display:
        raise RuntimeError('Xvfb did not start')
    return xvfb, ':' + display


def stop(process, name):
    """SIGINT, as roslaunch and a terminal's Ctrl-C send it; the exit status, or None after STOP_TIMEOUT."""
    process.send_signal(signal.SIGINT)
    try:
        return process.wait(STOP_TIMEOUT)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
        rospy.logerr('%s did not stop within %g s of SIGINT', name, STOP_TIMEOUT)
        return None


def subscribed(node_prefix, topics):
    """Whether a node whose name starts with `node_prefix` (rviz makes its name anonymous) subscribes to every topic."""
    _, _, state = rospy.get_master().getSystemState()
    subscribers = dict(state[1])
    return all(any(n.startswith(node_prefix) for n in subscribers.get(t, [])) for t in topics)


# What rviz/top_sim.rviz subscribes to: the markers display, the interactive markers display, the control panel.
RVIZ_TOPICS = ['/top_sim/markers', '/top_sim_interactive/update', '/top_sim/top_states']


class RvizShutdown(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.xvfb, display = start_xvfb()
        cls.env = dict(os.environ, DISPLAY=display, LIBGL_ALWAYS_SOFTWARE='1')
        cls.config = os.path.join(rospkg.RosPack().get_path('top_sim'), 'rviz', 'top_sim.rviz')
        cls.log_dir = os.environ.get('ROS_LOG_DIR', '/tmp')

    @classmethod
    def tearDownClass(cls):
        cls.xvfb.terminate()
        cls.xvfb.wait()

    def wait_for(self, predicate, timeout, what):
        end = time.time() + timeout
        while time.time() < end:
            if predicate():
                return
            time.sleep(0.1)
        self.fail('%s within %g s' % (what, timeout))

    def start(self, args, name):
        log = open(os.path.join(self.log_dir, 'rviz_shutdown_%s.log' % name), 'w')
        return subprocess.Popen(args, env=self.env, stdout=log, stderr=subprocess.STDOUT)

    def rviz_once(self, scene, run):
        """One rviz: up, drawing the node's markers with the panel loaded, SIGINT; its exit status."""
        name = 'rviz_%s_%d' % (scene, run)
        rviz = self.start(['rosrun', 'rviz', 'rviz', '-d', self.config, '__name:=' + name], name)
        self.wait_for(lambda: rviz.poll() is not None or subscribed('/' + name, RVIZ_TOPICS), START_TIMEOUT,
                      '%s subscribing to %s (its displays and the panel)' % (name, RVIZ_TOPICS))
        if rviz.poll() is not None:
            return rviz.returncode
        time.sleep(DRAW_SECONDS)
        return stop(rviz, name)

    def test_every_exit_is_clean(self):
        statuses = {}
        for scene in SCENES:
            node = self.start(['rosrun', 'top_sim', 'top_sim_node', '__name:=top_sim', '_scene_file:=' + scene],
                              'node_' + scene)
            interactive = self.start(['rosrun', 'top_sim', 'top_sim_interactive', '_node:=/top_sim'],
                                     'interactive_' + scene)
            rospy.wait_for_message('/top_sim/markers', MarkerArray, START_TIMEOUT)
            for run in range(RUNS):
                statuses['rviz %s %d' % (scene, run + 1)] = self.rviz_once(scene, run + 1)
            # As roslaunch stops them: top_sim_interactive, then the node.
            statuses['top_sim_interactive ' + scene] = stop(interactive, 'top_sim_interactive')
            statuses['top_sim_node ' + scene] = stop(node, 'top_sim_node')
        bad = {k: v for k, v in statuses.items() if v != 0}
        rviz_bad = [k for k in bad if k.startswith('rviz')]
        print('rviz: %d of %d exits not 0; exit statuses: %s' % (len(rviz_bad), len(SCENES) * RUNS, statuses))
        self.assertEqual(bad, {}, 'not a clean exit on SIGINT (negative: killed by that signal, None: hung), %d of %d: '
                         '%s' % (len(bad), len(statuses), bad))


if __name__ == '__main__':
    rospy.init_node('test_rviz_shutdown')
    rostest.rosrun('top_sim', 'test_rviz_shutdown', RvizShutdown, sys.argv)
