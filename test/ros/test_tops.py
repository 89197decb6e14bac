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
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber(topic, kind, self.on_msg, queue_size=10)

    def on_msg(self, m):
        with self.cond:
            self.msg = m
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
    @classmethod
    def setUpClass(cls):
        for s in ('spawn', 'kill', 'list'):
            rospy.wait_for_service(NODE + '/' + s, timeout=60.0)
        cls.spawn = rospy.ServiceProxy(NODE + '/spawn', Spawn)
        cls.kill = rospy.ServiceProxy(NODE + '/kill', Kill)
        cls.list = rospy.ServiceProxy(NODE + '/list', ListTops)

    def names(self):
        return list(self.list().names)

    def test_1_spawn_list_topics_frames(self):
        self.assertEqual(self.names(), ['top'])
        r = self.spawn('a', '')
        self.assertTrue(r.success, r.message)
        r = self.spawn('b', 'top: aluminium\nfriction: pmma\ninitial: {spin: 150.0, position: [0.2, 0.0]}\n')
        self.assertTrue(r.success, r.message)
        self.assertEqual(self.names(), ['top', 'a', 'b'])
        a = Latest(NODE + '/a/top_state', TopState).wait()
        b = Latest(NODE + '/b/top_state', TopState).wait()
        top = Latest(NODE + '/top_state', TopState).wait()
        self.assertIsNotNone(a, 'no a/top_state')
        self.assertIsNotNone(b, 'no b/top_state')
        self.assertEqual(a.header.frame_id, 'a/plane')
        self.assertEqual(b.header.frame_id, 'b/plane')
        self.assertAlmostEqual(a.spin, top.spin, delta=1e-6 * abs(top.spin) + 1.0)  # 'a' runs the node's scene
        self.assertAlmostEqual(b.spin, 150.0, delta=1.0)
        buf = tf2_ros.Buffer()
        tf2_ros.TransformListener(buf)
        for frame in ('a/top', 'b/top', 'top'):
            t = buf.lookup_transform('world', frame, rospy.Time(0), rospy.Duration(10.0))
            self.assertTrue(abs(t.transform.rotation.w) <= 1.0)
        # b starts 0.2 m across the slope from a (the scenes' initial positions), in frames that coincide at equal alpha
        ta = buf.lookup_transform('a/plane', 'a/top', rospy.Time(0), rospy.Duration(5.0)).transform.translation
        tb = buf.lookup_transform('b/plane', 'b/top', rospy.Time(0), rospy.Duration(5.0)).transform.translation
        self.assertAlmostEqual(tb.x - ta.x, 0.2, delta=0.05)

    def test_2_array_and_markers_carry_every_top(self):
        arr = Latest(NODE + '/top_states', TopStateArray).wait(lambda m: len(m.names) == len(self.names()))
        self.assertIsNotNone(arr, 'no top_states with every top')
        self.assertEqual(list(arr.names), self.names())
        self.assertEqual(len(arr.states), len(arr.names))
        for name, s in zip(arr.names, arr.states):
            self.assertEqual(s.header.frame_id, 'plane' if name == 'top' else name + '/plane')
        markers = Latest(NODE + '/markers', MarkerArray).wait(
            lambda m: any(k.ns.startswith('b/') for k in m.markers))
        self.assertIsNotNone(markers, 'no markers of spawned top b')
        spaces = set(k.ns.split('/')[0] for k in markers.markers if '/' in k.ns)
        self.assertTrue({'a', 'b'} <= spaces, spaces)

    def test_3_commands_reach_only_their_top(self):
        top = Latest(NODE + '/top_state', TopState)
        before = top.wait().spin
        pub = rospy.Publisher(NODE + '/a/spin', Float64, queue_size=1, latch=True)
        pub.publish(Float64(333.0))
        a = Latest(NODE + '/a/top_state', TopState).wait(lambda m: abs(m.spin - 333.0) < 1.0)
        self.assertIsNotNone(a, 'a/spin not applied')
        self.assertAlmostEqual(top.wait().spin, before, delta=1e-3 * abs(before))

    def test_4_bad_names_and_scenes_are_refused_others_untouched(self):
        names = self.names()
        cases = [('', 'empty'), ('top', 'taken'), ('a', 'taken'), ('1x', 'not a base ROS name'),
                 ('x/y', 'not a base ROS name'), ('c', 'given twice'), ('d', 'not valid YAML'),
                 ('e', 'unknown key')]
        scenes = {'c': 'top: aluminium\ntop: steel\nfriction: pmma\n', 'd': 'top: [unclosed',
                  'e': 'top: aluminium\nfriction: pmma\nspin: 3\n'}
        for name, part in cases:
            r = self.spawn(name, scenes.get(name, ''))
            self.assertFalse(r.success, name)
            self.assertIn(part, r.message, name)
        self.assertEqual(self.names(), names)
        self.assertIsNotNone(Latest(NODE + '/a/top_state', TopState).wait(), 'a stopped publishing')

    def test_5_kill(self):
        r = self.kill('top')
        self.assertFalse(r.success)
        self.assertIn('launch-time top', r.message)
        r = self.kill('zzz')
        self.assertFalse(r.success)
        self.assertIn('no top named', r.message)
        r = self.kill('a')
        self.assertTrue(r.success, r.message)
        self.assertEqual(self.names(), ['top', 'b'])
        r = self.spawn('a', '')  # the name is free again
        self.assertTrue(r.success, r.message)


if __name__ == '__main__':
    rospy.init_node('test_tops')
    rostest.rosrun('top_sim', 'test_tops', Tops, sys.argv)
