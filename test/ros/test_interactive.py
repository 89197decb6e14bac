#!/usr/bin/env python3
"""top_sim_interactive: per top a marker on /top_sim_interactive/update; releasing the ring turned 0.1 rad about the
plane's x axis tilts the plane by 0.1 rad, the arrow dragged 1 cm adds 20 rad/s of spin, the menu's Pause pauses;
a turn past pi/2 is refused (nothing sent). Every control of every top's marker, the launch-time top's and a spawned
one's, has a description: rviz logs an ERROR for an empty one (and draws a MENU control's as its text)."""
import math
import sys
import time
import unittest

import rospy
import rostest
from visualization_msgs.msg import InteractiveMarkerFeedback, InteractiveMarkerInit, InteractiveMarkerUpdate
from visualization_msgs.msg import Marker

from top_sim.srv import Kill, Spawn

from top_sim.msg import TopState


def empty_texts(marker):
    """Where rviz would show an empty text for this interactive marker: its description, a control's description
    (rviz's tooltip, and the text of a MENU control without markers), a text marker of a control."""
    empty = [] if marker.description.strip() else [marker.name]
    for i, c in enumerate(marker.controls):
        if not c.description.strip():
            empty.append('%s control %d (%s)' % (marker.name, i, c.name))
        empty += ['%s control %s marker %d' % (marker.name, c.name, j) for j, m in enumerate(c.markers)
                  if m.type in (Marker.TEXT_VIEW_FACING,) and not m.text.strip()]
    return empty

MARKER = 'top/controls'


class Interactive(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.state = None
        rospy.Subscriber('/top_sim/top_state', TopState, cls.on_state, queue_size=10)
        cls.feedback = rospy.Publisher('/top_sim_interactive/feedback', InteractiveMarkerFeedback, queue_size=10)

    @classmethod
    def on_state(cls, m):
        cls.state = m

    def wait(self, pred, timeout=10.0):
        end = time.time() + timeout
        while time.time() < end:
            if self.state is not None and pred(self.state):
                return True
            time.sleep(0.02)
        return False

    def send(self, control, event=InteractiveMarkerFeedback.MOUSE_UP, turn=0.0, lift=0.0, menu=0):
        f = InteractiveMarkerFeedback()
        f.client_id = 'test'
        f.marker_name = MARKER
        f.control_name = control
        f.event_type = event
        f.menu_entry_id = menu
        f.pose.orientation.w, f.pose.orientation.x = math.cos(turn / 2), math.sin(turn / 2)
        f.pose.position.x = 0.05
        f.pose.position.z = 0.03 + lift  # the rest pose (0.05, 0, 0.03) + the drag
        self.feedback.publish(f)

    def markers_when(self, pred, timeout=30.0):
        """The server's full set of markers (update_full, latched, sent on every change) once pred holds."""
        end = time.time() + timeout
        while time.time() < end:
            init = rospy.wait_for_message('/top_sim_interactive/update_full', InteractiveMarkerInit, timeout=timeout)
            markers = {m.name: m for m in init.markers}
            if pred(markers):
                return markers
            time.sleep(0.2)
        self.fail('no update_full with the markers wanted within %g s' % timeout)

    def test_every_control_has_a_description(self):
        markers = self.markers_when(lambda ms: MARKER in ms)
        self.assertEqual(len(markers[MARKER].controls), 3)
        self.assertEqual(empty_texts(markers[MARKER]), [])
        rospy.wait_for_service('/top_sim/spawn', timeout=30.0)
        self.assertTrue(rospy.ServiceProxy('/top_sim/spawn', Spawn)(name='second', scene='').success)
        try:
            markers = self.markers_when(lambda ms: 'second/controls' in ms)
            self.assertEqual(empty_texts(markers['second/controls']), [])
        finally:
            rospy.ServiceProxy('/top_sim/kill', Kill)('second')
        self.markers_when(lambda ms: 'second/controls' not in ms)

    def test_marker_then_ring_arrow_menu(self):
        update = rospy.wait_for_message('/top_sim_interactive/update', InteractiveMarkerUpdate, timeout=30.0)
        self.assertIsNotNone(update)
        self.assertTrue(self.wait(lambda s: True), 'no TopState')
        while self.feedback.get_num_connections() == 0:
            time.sleep(0.05)
        self.send('tilt', turn=0.1)
        self.assertTrue(self.wait(lambda s: abs(s.alpha - 0.2) < 1e-9), 'alpha %g, wanted 0.2' % self.state.alpha)
        self.send('tilt', turn=1.5)  # 0.2 + 1.5 > pi/2: refused
        time.sleep(1.0)
        self.assertAlmostEqual(self.state.alpha, 0.2, places=9)
        spin = self.state.spin
        self.send('spin', lift=0.01)
        self.assertTrue(self.wait(lambda s: abs(s.spin - (spin + 20.0)) < 1.0),
                        'spin %g, wanted %g + 20' % (self.state.spin, spin))
        self.send('menu', event=InteractiveMarkerFeedback.MENU_SELECT, menu=1)  # Pause
        self.assertTrue(self.wait(lambda s: s.paused), 'not paused by the menu')
        self.send('menu', event=InteractiveMarkerFeedback.MENU_SELECT, menu=2)  # Resume
        self.assertTrue(self.wait(lambda s: not s.paused), 'not resumed by the menu')


if __name__ == '__main__':
    rospy.init_node('test_interactive')
    rostest.rosrun('top_sim', 'test_interactive', Interactive, sys.argv)
