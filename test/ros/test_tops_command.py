#!/usr/bin/env python3
"""Many tops through one topic (docs/ros.md, "Many tops"; issue 49): ~tops/command acts on the top its name names and
on no other (inclination, reset, pause of one top); an unknown or empty name, a field out of range or another top's
name on a top's own ~NAME/command applies nothing and warns naming the top and the field; ~per_top_topics both ways
(a node with it false: no own topics; the spawn service asking per top; the default rule by the node's count); the
batch spawn (copies, a list with scenes, all-or-nothing); a top stopped by its end refuses commands until a reset; a ~per_top_topics that is not a bool stops the node at
start. Waits are on messages, never fixed sleeps."""
import os
import subprocess
import sys
import threading
import unittest

import rosgraph
import rospy
import rostest
from rosgraph_msgs.msg import Log

from top_sim.msg import TopCommand, TopStateArray
from top_sim.srv import Kill, ListTops, Spawn, SpawnRequest

NODE = '/top_sim'
FLAT = '/top_sim_flat'  # started with per_top_topics false and two tops from ~tops
TIMEOUT = 20.0


class States(object):
    """Every top_states message's (name -> TopState) after construction, with a condition to wait on."""

    def __init__(self, node):
        self.seen = []
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber(node + '/top_states', TopStateArray, self.on_msg, queue_size=50)

    def on_msg(self, m):
        with self.cond:
            self.seen.append(dict(zip(m.names, m.states)))
            self.cond.notify_all()

    def wait(self, pred, timeout=TIMEOUT):
        """The first message from now on (or already seen since `start`) for which pred holds, or None."""
        deadline = rospy.get_time() + timeout
        with self.cond:
            start = len(self.seen)
            while True:
                for s in self.seen[start:]:
                    if pred(s):
                        return s
                start = len(self.seen)
                left = deadline - rospy.get_time()
                if left <= 0 or rospy.is_shutdown():
                    return None
                self.cond.wait(min(left, 0.2))

    def values(self, name, field):
        with self.cond:
            return [getattr(s[name], field) for s in self.seen if name in s]


class RosoutWatch(object):
    """The node's /rosout lines, to wait for a warning that contains every given part."""

    def __init__(self):
        self.lines = []
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber('/rosout', Log, self.on_msg, queue_size=100)

    def on_msg(self, m):
        with self.cond:
            self.lines.append(m.msg)
            self.cond.notify_all()

    def wait(self, *parts, timeout=TIMEOUT):
        deadline = rospy.get_time() + timeout
        with self.cond:
            while True:
                for line in self.lines:
                    if all(p in line for p in parts):
                        return line
                left = deadline - rospy.get_time()
                if left <= 0 or rospy.is_shutdown():
                    return None
                self.cond.wait(min(left, 0.2))


def command(name, **fields):
    c = TopCommand()
    c.name = name
    for key, value in fields.items():
        setattr(c, key, value)
        if hasattr(c, 'set_' + key):
            setattr(c, 'set_' + key, True)
    return c


def connected_publisher(topic):
    pub = rospy.Publisher(topic, TopCommand, queue_size=100)
    deadline = rospy.get_time() + TIMEOUT
    while pub.get_num_connections() == 0 and rospy.get_time() < deadline:
        rospy.rostime.wallsleep(0.05)  # polls the connection count: no message to wait on
    return pub


def graph():
    """(published topics, subscribed topics) as the master has them."""
    pubs, subs, _ = rosgraph.Master('/test_tops_command').getSystemState()
    return {t for t, _ in pubs}, {t for t, _ in subs}


def own_topics_present(node, top):
    pubs, subs = graph()
    return {node + '/' + top + '/' + leaf for leaf in ('top_state', 'path')} & pubs | \
        {node + '/' + top + '/' + leaf for leaf in ('inclination', 'spin', 'command')} & subs


class TopsCommand(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        for s in ('spawn', 'kill', 'list'):
            rospy.wait_for_service(NODE + '/' + s, timeout=60.0)
        rospy.wait_for_service(FLAT + '/list', timeout=60.0)
        cls.spawn = rospy.ServiceProxy(NODE + '/spawn', Spawn)
        cls.kill = rospy.ServiceProxy(NODE + '/kill', Kill)
        cls.list = rospy.ServiceProxy(NODE + '/list', ListTops)
        cls.states = States(NODE)
        cls.rosout = RosoutWatch()
        cls.pub = connected_publisher(NODE + '/tops/command')

    def batch(self, **request):
        r = self.spawn(SpawnRequest(**request))
        self.assertTrue(r.success, r.message)
        for name in r.names:
            self.addCleanup(self.kill, name)
        return list(r.names)

    def test_command_acts_on_the_named_top_only(self):
        names = self.batch(name='c', copies=2)
        self.assertEqual(names, ['c0', 'c1'])
        before = self.states.wait(lambda s: 'c1' in s)
        self.assertIsNotNone(before, 'no top_states with c1')
        self.pub.publish(command('c1', inclination=0.15))
        after = self.states.wait(lambda s: abs(s['c1'].alpha - 0.15) < 1e-12)
        self.assertIsNotNone(after, 'c1 never showed the inclination sent on ~tops/command')
        self.assertNotIn(0.15, self.states.values('c0', 'alpha'))
        self.assertNotIn(0.15, self.states.values('top', 'alpha'))
        # pause c1 alone: its time stops, c0's runs on; then resume
        self.pub.publish(command('c1', paused=True))
        paused = self.states.wait(lambda s: s['c1'].paused)
        self.assertIsNotNone(paused, 'c1 never showed paused')
        self.assertFalse(paused['c0'].paused)
        later = self.states.wait(lambda s: s['c0'].sim_time > paused['c0'].sim_time + 0.05)
        self.assertIsNotNone(later, 'c0 stopped with c1')
        self.assertEqual(later['c1'].sim_time, paused['c1'].sim_time)
        self.pub.publish(command('c1', paused=False))
        self.assertIsNotNone(self.states.wait(lambda s: not s['c1'].paused and s['c1'].sim_time > later['c1'].sim_time))
        # reset c1 alone: back to its scene's inclination (c0's, never changed), c0 keeps running
        self.pub.publish(command('c1', reset=True))
        reset = self.states.wait(lambda s: s['c1'].alpha == s['c0'].alpha)
        self.assertIsNotNone(reset, 'c1 never returned to its start')
        # reset with a field: the field applies after the reset
        self.pub.publish(command('c1', reset=True, spin=150.0))
        self.assertIsNotNone(self.states.wait(lambda s: abs(s['c1'].spin - 150.0) < 1.0))

    def test_bad_names_and_fields_apply_nothing(self):
        self.batch(name='d', copies=2)
        self.assertIsNotNone(self.states.wait(lambda s: 'd1' in s))
        own = connected_publisher(NODE + '/d0/command')
        # One at a time: rejections are throttled node-wide (the first in full, then the last of each second), so
        # each warning is awaited before the next bad command; it names the top and the field.
        for pub, bad, parts in (
                (self.pub, command('nosuch', inclination=0.21), ("tops/command rejected", "name = 'nosuch'",
                                                                  'no top of that name')),
                (self.pub, command('', inclination=0.22), ('tops/command rejected', 'name is empty')),
                (self.pub, command('d0', inclination=1.6), ("top 'd0'", 'inclination = 1.6')),
                (self.pub, command('d0', inclination=0.23, spin=float('nan')), ("top 'd0'", 'spin = ')),
                (own, command('d1', inclination=0.24), ("name = 'd1'", "top 'd0'", 'must be empty or'))):
            pub.publish(bad)
            self.assertIsNotNone(self.rosout.wait(*parts), 'no warning with %s' % (parts,))
        own.publish(command('d0', inclination=0.25))
        self.pub.publish(command('d1', inclination=0.26))
        done = self.states.wait(lambda s: abs(s['d0'].alpha - 0.25) < 1e-12 and abs(s['d1'].alpha - 0.26) < 1e-12)
        self.assertIsNotNone(done, 'the valid commands after the bad ones never showed')
        for name in ('top', 'd0', 'd1'):
            for bad in (0.21, 0.22, 0.23, 0.24):
                self.assertNotIn(bad, self.states.values(name, 'alpha'), (name, bad))

    def test_a_stopped_top_refuses_commands_until_reset(self):
        # Tipped over without spin, it falls past max_tilt within 0.04 s: the end state fallen stops it.
        falls = 'top: aluminium\nfriction: pmma\ninitial: {start: tilted, tilt: 1.0, spin: 0.0}\n'
        self.batch(names=['z0'], scenes=[falls])
        self.assertIsNotNone(self.states.wait(lambda s: 'z0' in s and s['z0'].end_state == 'fallen'), 'z0 never fell')
        self.pub.publish(command('z0', inclination=0.27))
        line = self.rosout.wait("top 'z0'", 'end state fallen', 'reset it before commanding it')
        self.assertIsNotNone(line, 'no warning that the ended top refuses the command')
        self.pub.publish(command('z0', reset=True, inclination=0.28))  # a reset first: taken, and the field with it
        self.assertIsNotNone(self.states.wait(lambda s: abs(s['z0'].alpha - 0.28) < 1e-12), 'reset + command not applied')
        self.assertNotIn(0.27, self.states.values('z0', 'alpha'))

    def test_per_top_topics_by_request_and_by_count(self):
        on = self.batch(name='e', copies=2)
        off = self.batch(names=['f0'], per_top_topics=SpawnRequest.PER_TOP_TOPICS_OFF)
        self.assertEqual(len(own_topics_present(NODE, on[0])), 5, 'a spawned top of a small node has its 5 topics')
        self.assertEqual(own_topics_present(NODE, off[0]), set())
        self.assertIsNotNone(self.states.wait(lambda s: 'f0' in s), 'f0 not on top_states')
        self.pub.publish(command('f0', inclination=0.17))
        self.assertIsNotNone(self.states.wait(lambda s: abs(s['f0'].alpha - 0.17) < 1e-12))
        forced = self.batch(names=['g0'], per_top_topics=SpawnRequest.PER_TOP_TOPICS_ON)
        self.assertEqual(len(own_topics_present(NODE, forced[0])), 5)
        # the default rule: beyond 100 tops in the node, new tops get none
        n = len(self.list().names)
        many = self.batch(name='h', copies=101 - n + 1)  # the node then holds 102 tops
        self.assertEqual(own_topics_present(NODE, many[-1]), set())
        self.assertEqual(own_topics_present(NODE, many[0]), set())

    def test_node_with_per_top_topics_false(self):
        flat = States(FLAT)
        s = flat.wait(lambda s: {'q1', 'q2'} <= set(s))
        self.assertIsNotNone(s, 'no top_states with q1 and q2 from ' + FLAT)
        self.assertEqual(own_topics_present(FLAT, 'q1'), set())
        self.assertEqual(own_topics_present(FLAT, 'q2'), set())
        pub = connected_publisher(FLAT + '/tops/command')
        pub.publish(command('q2', spin=120.0))
        after = flat.wait(lambda s: abs(s['q2'].spin - 120.0) < 1.0)
        self.assertIsNotNone(after, 'q2 never took the spin sent on ~tops/command')
        self.assertGreater(abs(after['q1'].spin - 120.0), 10.0)

    def test_batch_spawn_is_all_or_nothing(self):
        made = self.batch(names=['k0', 'k1'], scenes=['', 'top: aluminium\nfriction: pmma\ninitial: {spin: 150.0}\n'])
        self.assertEqual(made, ['k0', 'k1'])
        listed = list(self.list().names)
        self.assertLess(listed.index('k0'), listed.index('k1'))
        s = self.states.wait(lambda s: 'k1' in s)
        self.assertAlmostEqual(s['k1'].spin, 150.0, delta=1.0)
        for request, part in ((dict(names=['m0', 'k0']), "name 'k0' is taken"),
                              (dict(names=['m0', 'm0']), "name 'm0' is given twice"),
                              (dict(names=['m0', 'm1'], scenes=['']), '1 scenes for 2 tops'),
                              (dict(name='m', copies=2, names=['m9']), 'give copies or names, not both'),
                              (dict(name='m', copies=2, scene='top: [1'), 'bad scene'),
                              (dict(name='m', copies=2, per_top_topics=7), 'per_top_topics = 7')):
            r = self.spawn(SpawnRequest(**request))
            self.assertFalse(r.success, request)
            self.assertIn(part, r.message)
        self.assertEqual([n for n in self.list().names if n.startswith('m')], [])

    def test_per_top_topics_not_a_bool_is_refused_at_start(self):
        node = None
        for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
            candidate = os.path.join(prefix, 'lib', 'top_sim', 'top_sim_node')
            node = node or (candidate if os.path.isfile(candidate) else None)
        self.assertIsNotNone(node, 'top_sim_node not found under CMAKE_PREFIX_PATH')
        for value in ('maybe', '1'):
            p = subprocess.run([node, '__name:=bad_flag', '_per_top_topics:=' + value], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, timeout=30, universal_newlines=True)
            self.assertEqual(p.returncode, 2, p.stdout)
            self.assertIn('/bad_flag/per_top_topics', p.stdout)
            self.assertIn('must be true or false', p.stdout)


if __name__ == '__main__':
    rospy.init_node('test_tops_command')
    rostest.rosrun('top_sim', 'test_tops_command', TopsCommand, sys.argv)
