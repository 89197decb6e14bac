#!/usr/bin/env python3
"""~reset returns to the start the user chose: top_sim.launch alpha:=0.2 spin:=150 (the scene file says 0.1 rad and
200 rad/s); after an inclination command and a reset the top is back at 0.2 rad and 150 rad/s. A node with no
parameters runs the default scene (docs/ros.md, "Parameters")."""
import sys
import unittest

import rospy
import rostest
from std_msgs.msg import Float64
from std_srvs.srv import Trigger

from top_sim.msg import TopState


def wait_state(topic, pred, timeout=20.0):
    """The first TopState on `topic` that satisfies pred, else None."""
    deadline = rospy.get_time() + timeout
    while rospy.get_time() < deadline and not rospy.is_shutdown():
        try:
            m = rospy.wait_for_message(topic, TopState, timeout=2.0)
        except rospy.ROSException:
            continue
        if pred(m):
            return m
    return None


class ResetStart(unittest.TestCase):
    def test_starts_at_the_launch_values(self):
        m = wait_state('/top_sim/top_state', lambda m: True)
        self.assertIsNotNone(m, 'no TopState')
        self.assertAlmostEqual(m.alpha, 0.2, places=12)

    def test_reset_returns_to_the_launch_values(self):
        pub = rospy.Publisher('/top_sim/inclination', Float64, queue_size=1, latch=True)
        pub.publish(Float64(0.05))
        self.assertIsNotNone(wait_state('/top_sim/top_state', lambda m: abs(m.alpha - 0.05) < 1e-12),
                             'the inclination command did not apply')
        rospy.wait_for_service('/top_sim/reset', timeout=10.0)
        r = rospy.ServiceProxy('/top_sim/reset', Trigger)()
        self.assertTrue(r.success, r.message)
        self.assertIn("reset top 'top' to its start", r.message)
        # The first state after the reset (the inclination is no longer 0.05): alpha is the launch value exactly, the
        # spin within 1 % of the launch value 150 rad/s (not the scene's 200; friction slows it by < 1 % in a second).
        m = wait_state('/top_sim/top_state', lambda m: abs(m.alpha - 0.05) > 1e-12)
        self.assertIsNotNone(m, 'no TopState just after the reset')
        self.assertAlmostEqual(m.alpha, 0.2, places=12)
        self.assertLess(abs(m.spin - 150.0), 1.5, 'spin %g after reset: must be the launch value 150' % m.spin)

    def test_no_parameters_runs_the_default_scene(self):
        m = wait_state('/bare/top_state', lambda m: m.sim_time > 0.1)
        self.assertIsNotNone(m, 'a node with no parameters must run the default scene')
        self.assertAlmostEqual(m.alpha, 0.1, places=12)  # config/scenes/default.yaml


if __name__ == '__main__':
    rospy.init_node('test_reset_start')
    rostest.rosrun('top_sim', 'test_reset_start', ResetStart, sys.argv)
