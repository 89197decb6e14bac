#!/usr/bin/env python3
"""Markers attached to the top (docs/ros.md, "Watching in rviz"): looked up at the newest tf, as rviz draws them,
no marker of a top is farther from tf's top origin than its own offset, whatever marker_rate:
- in the top frame: its points' distance from the frame origin (exact, 1 um for rounding);
- in the contact frame: that plus the contact frame's distance from the top origin, itself at most f + R;
- in any other frame: the distance the node meant (looked up at the marker's own stamp) plus 1 mm.
The plane's grid and square and the trail are the plane's, not the top's, and are left out."""
import math
import os
import sys
import threading
import unittest

import rospy
import rostest
import tf2_ros
import yaml
from visualization_msgs.msg import MarkerArray

PLANE_MARKERS = ('plane', 'grid', 'trail')
TOP_MARKERS = ('body', 'stripe', 'stem', 'tip', 'spin', 'velocity', 'label')
WINDOW = 5.0  # [s] of checks per node


def rotate(q, v):
    """v rotated by the unit quaternion q (x, y, z, w)."""
    x, y, z, w = q
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz, v[2] + w * tz + x * ty - y * tx)


def apply(t, p):
    """Point p of the child frame in the parent frame of TransformStamped t."""
    r = t.transform.rotation
    q = (r.x, r.y, r.z, r.w)
    a = rotate(q, p)
    o = t.transform.translation
    return (a[0] + o.x, a[1] + o.y, a[2] + o.z)


def dist(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def marker_points(m):
    """The marker's points in its frame: its points through its pose, else its pose's position."""
    class Pose(object):
        transform = type('T', (), {'rotation': m.pose.orientation, 'translation': m.pose.position})
    pts = [(p.x, p.y, p.z) for p in m.points] or [(0.0, 0.0, 0.0)]
    return [apply(Pose, p) for p in pts]


def tip_bound(config_dir, scene):
    """f + R of the scene's top: the farthest the contact point can be from the centre of mass."""
    with open(os.path.join(config_dir, 'scenes', scene)) as f:
        top = yaml.safe_load(f)['top']
    with open(os.path.join(config_dir, 'tops', top + '.yaml')) as f:
        t = yaml.safe_load(f)
    return t['com_offset'] + t['tip_radius']


class Attached(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.buf = tf2_ros.Buffer(rospy.Duration(30.0))
        cls.listener = tf2_ros.TransformListener(cls.buf)
        cls.config = rospy.get_param('~config_dir')

    def check(self, node, scene):
        prefix = node + '/'
        plane, top, contact = prefix + 'plane', prefix + 'top', prefix + 'contact'
        bound = tip_bound(self.config, scene)
        latest, lock = {}, threading.Lock()

        def on_markers(a):
            with lock:
                for m in a.markers:
                    latest[m.ns] = m
        sub = rospy.Subscriber('/%s/markers' % node, MarkerArray, on_markers, queue_size=5)
        checks, worst, start, end = 0, {}, None, rospy.get_time() + 30.0
        while rospy.get_time() < end and not rospy.is_shutdown():
            rospy.sleep(0.02)
            with lock:
                markers = [m for m in latest.values() if m.ns in TOP_MARKERS]
            if len(markers) < len(TOP_MARKERS):
                continue
            try:
                newest = self.buf.lookup_transform(plane, top, rospy.Time(0))
            except tf2_ros.TransformException:
                continue
            stamp, origin = newest.header.stamp, newest.transform.translation
            origin = (origin.x, origin.y, origin.z)
            if start is None:
                start, end = origin, rospy.get_time() + WINDOW
            for m in markers:
                frame = m.header.frame_id
                try:
                    now = self.buf.lookup_transform(plane, frame, stamp)
                    then = self.buf.lookup_transform(plane, frame, m.header.stamp)
                    top_then = self.buf.lookup_transform(plane, top, m.header.stamp)
                except tf2_ros.TransformException:
                    continue  # the marker is newer than this tf: the next round sees it
                self.assertTrue(m.frame_locked, m.ns)
                pts = marker_points(m)
                frame_offset = dist(apply(now, (0.0, 0.0, 0.0)), origin)
                for p in pts:
                    seen = dist(apply(now, p), origin)
                    if frame == top:
                        allowed = dist(p, (0, 0, 0)) + 1e-6
                    elif frame == contact:
                        self.assertLessEqual(frame_offset, bound + 1e-6, 'contact frame off the tip')
                        allowed = dist(p, (0, 0, 0)) + frame_offset + 1e-6
                    else:
                        top_t = top_then.transform.translation
                        allowed = dist(apply(then, p), (top_t.x, top_t.y, top_t.z)) + 1e-3
                    worst[m.ns] = max(worst.get(m.ns, 0.0), seen - allowed)
                    self.assertLessEqual(seen, allowed, '%s marker %s (frame %s) is %.4f m from the top, its own '
                                         'offset %.4f m' % (node, m.ns, frame, seen, allowed))
                checks += 1
        sub.unregister()
        rospy.loginfo('%s: %d marker checks, worst excess per marker %s', node, checks, worst)
        self.assertIsNotNone(start, 'no markers and tf of %s' % node)
        self.assertGreater(checks, 100, 'too few checks of %s' % node)
        return start, origin

    def test_sliding_top_at_2_hz(self):
        start, end = self.check('sliding', 'supercritical.yaml')
        # The test can fail: a plane-frame marker 0.5 s old would be this far behind.
        self.assertGreater(dist(start, end), 0.5, 'the sliding top must slide for the check to mean something')

    def test_hopping_top(self):
        self.check('hopping', 'hopping.yaml')


if __name__ == '__main__':
    rospy.init_node('test_markers')
    rostest.rosrun('top_sim', 'test_markers', Attached, sys.argv)
