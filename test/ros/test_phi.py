#!/usr/bin/env python3
"""phi measured through the node (fast real_time_factor) against the analytic phi* of physics.md section 5."""
import math
import sys
import threading
import unittest

import rospy
import rostest
from top_sim.msg import TopState

NODE = '/top_sim'


def paper_phi_star(alpha, mu_c, s_c, spin_positive=True):
    # physics.md section 5: s* = s_c (1 - sqrt(1 - tan(alpha)/mu_c)), phi* = 2 atan(s*) (pi - that for omega < 0)
    s = s_c * (1.0 - math.sqrt(1.0 - math.tan(alpha) / mu_c))
    phi = 2.0 * math.atan(s)
    return phi if spin_positive else math.pi - phi


class PhiThroughNode(unittest.TestCase):
    def test_phi_matches_phi_star(self):
        alpha = rospy.get_param('~alpha')
        mu_c = rospy.get_param('~mu_c')
        s_c = rospy.get_param('~s_c')
        t_from = rospy.get_param('~t_from')  # the relaxation time of the scene is well below this
        t_to = rospy.get_param('~t_to')
        tolerance = rospy.get_param('~tolerance')
        marks = {}
        last = {}
        done = threading.Event()

        def on_state(m):
            last['msg'] = m
            if 'from' not in marks and m.sim_time >= t_from:
                marks['from'] = m
            if 'from' in marks and m.sim_time >= t_to:
                marks['to'] = m
                done.set()

        sub = rospy.Subscriber(NODE + '/top_state', TopState, on_state, queue_size=1000)
        self.assertTrue(done.wait(120.0), 'simulated time did not reach %g s (last %s)' %
                        (t_to, last['msg'].sim_time if last else 'none'))
        sub.unregister()
        a, b = marks['from'], marks['to']
        self.assertGreater(b.sim_time - a.sim_time, 0.5 * (t_to - t_from), 'too few messages to measure a direction')
        dx = b.contact_point.x - a.contact_point.x
        dy = b.contact_point.y - a.contact_point.y
        # angle from h (plane x) towards downhill (-y), interfaces.md
        phi_measured = math.atan2(-dy, dx)
        phi_star = paper_phi_star(alpha, mu_c, s_c, b.spin > 0.0)
        rospy.loginfo('phi measured %.9f, phi* %.9f (analytic), difference %.3g rad, achieved real-time factor %.1f',
                      phi_measured, phi_star, phi_measured - phi_star, b.real_time_factor)
        self.assertAlmostEqual(b.alpha, alpha, delta=0.0)
        self.assertTrue(b.has_stationary_state)
        self.assertAlmostEqual(b.phi_star, phi_star, delta=1e-9)
        self.assertAlmostEqual(phi_measured, phi_star, delta=tolerance)
        self.assertEqual(b.regime, TopState.SLEEPING, 'regime %s' % b.regime_name)
        self.assertGreater(b.real_time_factor, 1.0, 'a fast real_time_factor must run faster than real time')


if __name__ == '__main__':
    rospy.init_node('test_phi')
    rostest.rosrun('top_sim', 'test_phi', PhiThroughNode, sys.argv)
