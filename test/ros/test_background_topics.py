#!/usr/bin/env python3
"""~topics_at_start (docs/ros.md, "Many tops: start-up"): the node starts with 8 tops, the own topics of the
launch-time top and `a` at start, those of b..g on the background thread. In the end every top's top_state and path
are advertised by the node, its inclination, spin and command subscribed, a command to a background top reaches it,
and the diagnostics count no top still waiting; a background top can be killed and its topics go."""
import sys
import threading
import unittest

import rosgraph
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from std_msgs.msg import Float64

from top_sim.msg import TopState
from top_sim.srv import Kill, ListTops, Spawn

NODE = '/top_sim'
TOPS = ['top', 'a', 'b', 'c', 'd', 'e', 'f', 'g']
PENDING = 'tops whose topics are not yet advertised'


def prefix(name):
    return NODE + '/' + ('' if name == 'top' else name + '/')


def node_topics():
    """(topics the node publishes, topics it subscribes) as the master knows them."""
    pubs, subs, _ = rosgraph.Master('/test_background_topics').getSystemState()
    node = NODE
    return ({t for t, nodes in pubs if node in nodes}, {t for t, nodes in subs if node in nodes})


def wait_for(pred, timeout):
    deadline = rospy.get_time() + timeout
    while not rospy.is_shutdown() and rospy.get_time() < deadline:
        if pred():
            return True
        rospy.sleep(0.2)
    return pred()


class BackgroundTopics(unittest.TestCase):
    """Any order: the kill test spawns its top again, so the others see every top of the launch."""

    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service(NODE + '/list', timeout=60.0)
        cls.list = rospy.ServiceProxy(NODE + '/list', ListTops)
        cls.kill = rospy.ServiceProxy(NODE + '/kill', Kill)
        cls.spawn = rospy.ServiceProxy(NODE + '/spawn', Spawn)
        cls.pending = None
        cls.lock = threading.Lock()
        cls.diag = rospy.Subscriber('/diagnostics', DiagnosticArray, cls.on_diag, queue_size=10)

    @classmethod
    def on_diag(cls, m):
        for st in m.status:
            if 'simulation' in st.name:
                with cls.lock:
                    cls.pending = int({kv.key: kv.value for kv in st.values}[PENDING])

    def missing(self, names):
        pubs, subs = node_topics()
        want_pubs = {prefix(n) + t for n in names for t in ('top_state', 'path')}
        want_subs = {prefix(n) + t for n in names for t in ('inclination', 'spin', 'command')}
        return sorted((want_pubs - pubs) | (want_subs - subs))

    def test_every_top_gets_its_topics(self):
        self.assertEqual(sorted(self.list().names), sorted(TOPS))
        self.assertTrue(wait_for(lambda: not self.missing(TOPS), 60.0), 'never advertised: %s' % self.missing(TOPS))
        self.assertTrue(wait_for(lambda: self.pending == 0, 30.0), 'diagnostics: %s = %s' % (PENDING, self.pending))

    def test_background_top_takes_commands(self):
        self.assertTrue(wait_for(lambda: not self.missing(['g']), 60.0))
        got = threading.Event()
        sub = rospy.Subscriber(prefix('g') + 'top_state', TopState,
                               lambda m: got.set() if abs(m.alpha - 0.13) < 1e-12 else None, queue_size=10)
        pub = rospy.Publisher(prefix('g') + 'inclination', Float64, queue_size=1)
        try:
            self.assertTrue(wait_for(lambda: pub.get_num_connections() > 0 and sub.get_num_connections() > 0, 30.0))
            deadline = rospy.get_time() + 20.0
            while not got.is_set() and rospy.get_time() < deadline:
                pub.publish(Float64(0.13))
                got.wait(0.5)
            self.assertTrue(got.is_set(), 'top g never published alpha 0.13 on its own top_state')
        finally:
            sub.unregister()
            pub.unregister()

    def test_kill_background_top_unregisters_its_topics(self):
        self.assertTrue(wait_for(lambda: not self.missing(['f']), 60.0))
        r = self.kill('f')
        self.assertTrue(r.success, r.message)
        gone = lambda: not (set(self.missing(['f'])) ^ set(prefix('f') + t for t in (
            'top_state', 'path', 'inclination', 'spin', 'command')))
        self.assertTrue(wait_for(gone, 20.0), 'still registered: %s' % sorted(
            set(prefix('f') + t for t in ('top_state', 'path', 'inclination', 'spin', 'command')) -
            set(self.missing(['f']))))
        self.assertNotIn('f', self.list().names)
        r = self.spawn(name='f', scene='')  # back, for the tests that run after this one
        self.assertTrue(r.success, r.message)


if __name__ == '__main__':
    rospy.init_node('test_background_topics')
    rostest.rosrun('top_sim', 'test_background_topics', BackgroundTopics, sys.argv)
