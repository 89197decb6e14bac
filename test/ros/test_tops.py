#!/usr/bin/env python3
"""Many tops per node (docs/ros.md, "Many tops"): ~spawn, ~kill, ~list; each top's NAME/top_state, NAME/spin,
frames NAME/plane and NAME/top; the top_states array and the markers carry every top; bad names and bad scenes
are refused with a message and leave the other tops untouched."""
import sys
import threading
import unittest

import rospy
import rostest
import tf2_ros
from std_msgs.msg import Float64
from visualization_msgs.msg import MarkerArray

from top_sim.msg import TopState, TopStateArray
from top_sim.srv import Kill, ListTops, Spawn

NODE = '/top_sim'


class Latest(object):
    """The last message of a topic, with a condition to wait on."""

    def __init__(self, topic, kind):
        self.msg = None
        self.count = 0
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber(topic, kind, self.on_msg, queue_size=10)

    def on_msg(self, m):
        with self.cond:
            self.msg = m
            self.count += 1
            self.cond.notify_all()

    def wait(self, pred=lambda m: True, timeout=20.0):
        deadline = rospy.get_time() + timeout
        with self.cond:
            while not (self.msg is not None and pred(self.msg)):
                left = deadline - rospy.get_time()
                if left <= 0 or rospy.is_shutdown():
                    return None
                self.cond.wait(min(left, 0.2))
            return self.msg


class Tops(unittest.TestCase):
    """Each test spawns the tops it needs under its own names and kills them at its end: any order, any subset."""

    @classmethod
    def setUpClass(cls):
        for s in ('spawn', 'kill', 'list'):
            rospy.wait_for_service(NODE + '/' + s, timeout=60.0)
        cls.spawn = rospy.ServiceProxy(NODE + '/spawn', Spawn)
        cls.kill = rospy.ServiceProxy(NODE + '/kill', Kill)
        cls.list = rospy.ServiceProxy(NODE + '/list', ListTops)

    def names(self):
        return list(self.list().names)

    def spawned(self, name, scene=''):
        r = self.spawn(name=name, scene=scene)
        self.assertTrue(r.success, r.message)
        self.addCleanup(self.kill, name)  # a kill of a top already gone is refused, harmlessly
        return name

    def test_spawn_list_topics_frames(self):
        a = self.spawned('a1')
        b = self.spawned('b1', 'top: aluminium\nfriction: pmma\ninitial: {spin: 150.0, position: [0.2, 0.0]}\n')
        names = self.names()
        self.assertEqual(names[0], 'top')  # the launch-time top first, then the spawned ones in spawn order
        self.assertLess(names.index(a), names.index(b))
        sa = Latest(NODE + '/a1/top_state', TopState).wait()
        sb = Latest(NODE + '/b1/top_state', TopState).wait()
        top = Latest(NODE + '/top_state', TopState).wait()
        self.assertIsNotNone(sa, 'no a1/top_state')
        self.assertIsNotNone(sb, 'no b1/top_state')
        self.assertEqual(sa.header.frame_id, 'a1/plane')
        self.assertEqual(sb.header.frame_id, 'b1/plane')
        self.assertAlmostEqual(sa.spin, top.spin, delta=1e-6 * abs(top.spin) + 1.0)  # a1 runs the node's scene
        self.assertAlmostEqual(sb.spin, 150.0, delta=1.0)
        buf = tf2_ros.Buffer()
        tf2_ros.TransformListener(buf)
        for frame in ('a1/top', 'b1/top', 'top'):
            t = buf.lookup_transform('world', frame, rospy.Time(0), rospy.Duration(10.0))
            self.assertTrue(abs(t.transform.rotation.w) <= 1.0)
        # b1 starts 0.2 m across the slope from a1 (the scenes' initial positions), in frames that coincide at equal
        # alpha
        ta = buf.lookup_transform('a1/plane', 'a1/top', rospy.Time(0), rospy.Duration(5.0)).transform.translation
        tb = buf.lookup_transform('b1/plane', 'b1/top', rospy.Time(0), rospy.Duration(5.0)).transform.translation
        self.assertAlmostEqual(tb.x - ta.x, 0.2, delta=0.05)

    def test_array_and_markers_carry_every_top(self):
        self.spawned('a2')
        self.spawned('b2')
        names = self.names()
        arr = Latest(NODE + '/top_states', TopStateArray).wait(lambda m: list(m.names) == names)
        self.assertIsNotNone(arr, 'no top_states with every top')
        self.assertEqual(len(arr.states), len(arr.names))
        for name, s in zip(arr.names, arr.states):
            self.assertEqual(s.header.frame_id, 'plane' if name == 'top' else name + '/plane')
        markers = Latest(NODE + '/markers', MarkerArray).wait(
            lambda m: {'a2', 'b2'} <= set(k.ns.split('/')[0] for k in m.markers if '/' in k.ns))
        self.assertIsNotNone(markers, 'no markers of spawned tops a2 and b2')

    def test_dropped_disc_touching_and_end_state(self):
        """A thin disc (physics.md section 13) dropped 10 mm: TopState's touching is 0 in free fall (until
        sqrt(2 h / g)) and 1 on its rim, in the top_states array and on its own topic; after it falls flat,
        end_state is lying_flat and the node keeps publishing it."""
        scene = ('top: {mass: 0.4, inertia_axial: 3.2e-4, inertia_transverse: 1.6e-4, '
                 'shapes: [{rim: {offset: 0, radius: 0.04}}]}\n'
                 'plane: {inclination: 0}\nfriction: {law: coulomb, mu: 0.3, static: 0.3}\n'
                 'initial: {tilt: 0.5, spin: 0, angular_velocity_transverse: [0, 0], gap: 0.01}\n')
        t_touch = (2.0 * 0.01 / 9.81) ** 0.5
        seen, lock = [], threading.Lock()

        def on_array(m):
            with lock:
                seen.extend((s.sim_time, s.touching, s.contact_mode, s.end_state)
                            for n, s in zip(m.names, m.states) if n == 'disc6')
        sub = rospy.Subscriber(NODE + '/top_states', TopStateArray, on_array, queue_size=100)
        self.addCleanup(sub.unregister)
        own = Latest(NODE + '/disc6/top_state', TopState)
        self.spawned('disc6', scene)
        flat = own.wait(lambda m: m.end_state == 'lying_flat', timeout=30.0)
        self.assertIsNotNone(flat, 'disc6 never reported end_state lying_flat')
        self.assertIn('lying_flat', flat.end_state_message)
        self.assertEqual(flat.fault, '')  # a named end, no fault
        self.assertEqual(flat.touching, 1)
        n = own.count
        later = own.wait(lambda m: own.count >= n + 10, timeout=10.0)
        self.assertIsNotNone(later, 'the node stopped publishing disc6 after its end')
        self.assertEqual((later.end_state, later.sim_time), ('lying_flat', flat.sim_time))
        with lock:
            states = list(seen)
        for t, touching, mode, _ in states:
            self.assertEqual(touching, 0 if mode == TopState.FLIGHT else 1, 'sim_time %g' % t)
            if t < t_touch:
                self.assertEqual((touching, mode), (0, TopState.FLIGHT), 'sim_time %g: in free fall' % t)
        self.assertTrue(any(touching == 0 for _, touching, _, _ in states), 'no state in free fall in the array')
        self.assertTrue(any(touching == 1 and t >= t_touch for t, touching, _, _ in states), 'never on its rim')
        self.assertTrue(any(end == 'lying_flat' for _, _, _, end in states), 'the array has no end state')

    def test_commands_reach_only_their_top(self):
        self.spawned('a3')
        top = Latest(NODE + '/top_state', TopState)
        before = top.wait().spin
        pub = rospy.Publisher(NODE + '/a3/spin', Float64, queue_size=1, latch=True)
        pub.publish(Float64(333.0))
        a = Latest(NODE + '/a3/top_state', TopState).wait(lambda m: abs(m.spin - 333.0) < 1.0)
        self.assertIsNotNone(a, 'a3/spin not applied')
        self.assertAlmostEqual(top.wait().spin, before, delta=1e-3 * abs(before))

    def test_bad_names_and_scenes_are_refused_others_untouched(self):
        self.spawned('a4')
        names = self.names()
        cases = [('', 'empty'), ('top', 'taken'), ('a4', 'taken'), ('1x', 'not a base ROS name'),
                 ('x/y', 'not a base ROS name'), ('c4', 'given twice'), ('d4', 'not valid YAML'),
                 ('e4', 'unknown key')]
        scenes = {'c4': 'top: aluminium\ntop: steel\nfriction: pmma\n', 'd4': 'top: [unclosed',
                  'e4': 'top: aluminium\nfriction: pmma\nspin: 3\n'}
        for name, part in cases:
            r = self.spawn(name=name, scene=scenes.get(name, ''))
            self.assertFalse(r.success, name)
            self.assertIn(part, r.message, name)
        self.assertEqual(self.names(), names)
        self.assertIsNotNone(Latest(NODE + '/a4/top_state', TopState).wait(), 'a4 stopped publishing')

    def test_kill_refuses_the_launch_top_and_unknown_names_and_frees_the_name(self):
        k = self.spawned('k5')
        r = self.kill('top')
        self.assertFalse(r.success)
        self.assertIn('launch-time top', r.message)
        r = self.kill('zzz')
        self.assertFalse(r.success)
        self.assertIn('no top named', r.message)
        r = self.kill(k)
        self.assertTrue(r.success, r.message)
        self.assertNotIn(k, self.names())
        r = self.spawn(name=k, scene='')  # the name is free again (the first cleanup kills it)
        self.assertTrue(r.success, r.message)


if __name__ == '__main__':
    rospy.init_node('test_tops')
    rostest.rosrun('top_sim', 'test_tops', Tops, sys.argv)
