#!/usr/bin/env python3
"""A disc at its end: once the dropped disc lies flat its simulated time stops, and ~markers keeps coming: every
marker tick (10 Hz) an array, within marker_refresh (1 s) the body drawn from its rim with the touching tyre, the
label saying the end state, and no tip sphere or stem drawn; a tf listener started after the end gets its frames."""
import threading
import time
import unittest

import rospy
import rostest
import tf2_ros
from top_sim.msg import TopState
from visualization_msgs.msg import Marker, MarkerArray


class DiscEnd(unittest.TestCase):
    def test_markers_go_on_after_the_end(self):
        lock = threading.Lock()
        states, arrays = [], []
        rospy.Subscriber('/top_sim/top_state', TopState, lambda m: states.append(m.sim_time))
        rospy.Subscriber('/top_sim/markers', MarkerArray, lambda m: (lock.acquire(), arrays.append(m), lock.release()))
        deadline = time.time() + 30.0
        while time.time() < deadline and (len(states) < 2 or states[-1] < 0.08):
            time.sleep(0.1)
        self.assertGreaterEqual(states[-1], 0.08, 'the disc did not reach its end within 30 s')
        time.sleep(0.5)
        ended = states[-1]
        with lock:
            del arrays[:]
        time.sleep(2.5)
        self.assertEqual(states[-1], ended, 'simulated time moved after the end')
        with lock:
            seen = list(arrays)
        self.assertGreaterEqual(len(seen), 15, 'about 25 marker arrays in 2.5 s at 10 Hz')
        last = {}
        for a in seen:
            for m in a.markers:
                last[m.ns] = m
        for ns in ('body', 'touching', 'stripe', 'label'):
            self.assertIn(ns, last, ns + ' not sent again after the end')
            self.assertEqual(last[ns].action, Marker.ADD, ns)
        self.assertGreater(len(last['touching'].points), 0)
        self.assertIn('end: lying_flat at t = ', last['label'].text)
        self.assertNotIn('phi', last['label'].text)  # nothing of the motion that stopped
        for ns in ('tip', 'stem'):
            self.assertEqual(last[ns].action, Marker.DELETE, ns + ': not on a disc')
        # A tf listener started after the end (rviz opened on an ended run) gets the disc's frames: /tf_static
        # holds the frames of a top whose time stopped (before, it got none and rviz drew nothing).
        late = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(late)
        for parent, child in (('world', 'top'), ('plane', 'contact'), ('plane', 'grid')):
            self.assertTrue(late.can_transform(parent, child, rospy.Time(0), rospy.Duration(5.0)),
                            'a late listener has no %s -> %s' % (parent, child))
        del listener


if __name__ == '__main__':
    rospy.init_node('test_disc_end')
    rostest.rosrun('top_sim', 'test_disc_end', DiscEnd)
