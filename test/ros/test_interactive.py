#!/usr/bin/env python3
"""top_sim_interactive: per top a marker on /top_sim_interactive/update; releasing the ring turned 0.1 rad about the
plane's x axis tilts the plane by 0.1 rad, the arrow dragged 1 cm adds 20 rad/s of spin, the menu's Pause pauses;
a turn past pi/2 is refused (nothing sent)."""
import math
import sys
import time
import unittest

import rospy
import rostest
from visualization_msgs.msg import InteractiveMarkerFeedback, InteractiveMarkerUpdate

from top_sim.msg import TopState

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

    def test_1_marker_then_ring_arrow_menu(self):
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
