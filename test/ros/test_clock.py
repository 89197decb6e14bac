#!/usr/bin/env python3
"""/clock from top_sim_node (docs/ros.md, "Time, /clock and replay"): a node with /use_sim_time true (this test)
follows it; tf lookups at its ROS time succeed; ~reset, with a spawned top too, never moves /clock or a stamp back.

clock.test runs the node with publish_clock and real_time_factor 0.5, so the simulated clock runs at half the wall
clock's rate: a listener on the wall clock would be seen at once."""
import sys
import time
import unittest

import rospy
import rostest
import tf2_ros
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger

from top_sim.msg import TopState
from top_sim.srv import Kill, Spawn

from clock_util import (NS, Stream, assert_follows, backward_steps, clock_value, header_stamp, not_in,
                        wait_for)

NODE = '/top_sim'
FACTOR = 0.5  # real_time_factor of clock.test
RATE = 200.0  # publish_rate of clock.test [Hz]
WINDOW = 4.0  # wall seconds of each observation
# TopState stamp - this node's clock at its arrival [simulated s]: state and clock come on separate connections to
# separate threads of this listener. Median of its size: 4 publish periods (a listener on the wall clock would be
# seconds off); at most this far in the future: 0.25 s (0.5 wall s: a thread starved on a loaded machine).
TYPICAL, TOLERANCE = 4.0 * FACTOR / RATE, 0.25
TF_WAIT = 0.25  # a tf lookup at rospy.Time.now() may wait this long [simulated s] (5 polls of tf2_ros's 20 Hz loop)
RESETS = 4


def state_fields(m):
    return header_stamp(m), m.sim_time, m.dissipated_work


class ClockFollower(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.start_wall = time.time()
        wait_for(lambda: rospy.Time.now() > rospy.Time(0), 60.0, "the node's /clock")

    def test_listener_follows_the_simulated_clock(self):
        state = Stream(NODE + '/top_state', TopState, state_fields)
        clock = Stream('/clock', Clock, clock_value)
        wait_for(lambda: len(state.values()) > 10, 30.0, 'top_state')
        c0, w0 = rospy.Time.now().to_sec(), time.time()
        time.sleep(WINDOW)
        c1, w1 = rospy.Time.now().to_sec(), time.time()
        state.close()
        clock.close()
        rate = (c1 - c0) / (w1 - w0)
        rospy.loginfo('rospy.Time.now() ran %.4f simulated s per wall s (real_time_factor %g)', rate, FACTOR)
        self.assertAlmostEqual(rate, FACTOR, delta=0.1 * FACTOR)
        # Under use_sim_time the node does not wait for a clock (it is the clock): stamps = wall time at start + t.
        stamp, t, _ = state.values()[0]
        origin = stamp * NS - t
        rospy.loginfo('stamp origin %.3f s, %.3f s from the wall time at the test start', origin,
                      origin - self.start_wall)
        self.assertLess(abs(origin - self.start_wall), 20.0)
        self.assertEqual(backward_steps(clock.values(), strict=True), [], '/clock does not go forward')
        # /clock is the launch-time top's stamp (rospy's /clock queue of 1 may skip some values, never add one).
        missing, inside = not_in(clock.values(), [s for s, _, _ in state.values()])
        rospy.loginfo('%d /clock values received in the span of %d TopStates', inside, len(state.values()))
        self.assertGreater(inside, 0.5 * RATE * WINDOW)  # one /clock per publish period
        self.assertEqual(missing, [], '/clock values that are not top_state stamps')
        assert_follows(self, state.ahead(), TYPICAL, TOLERANCE, 'top_state')

    def test_tf_lookup_at_now(self):
        buf = tf2_ros.Buffer()
        tf2_ros.TransformListener(buf)
        buf.lookup_transform('world', 'top', rospy.Time(0), rospy.Duration(10.0))
        at_once, waited, failed, lags = 0, 0, [], []
        end = time.time() + WINDOW
        while time.time() < end:
            now = rospy.Time.now()
            lags.append((now - buf.lookup_transform('world', 'top', rospy.Time(0)).header.stamp).to_sec())
            try:
                buf.lookup_transform('world', 'top', now)
                at_once += 1
            except tf2_ros.ExtrapolationException:
                try:
                    buf.lookup_transform('world', 'top', now, rospy.Duration(TF_WAIT))
                    waited += 1
                except tf2_ros.TransformException as e:
                    failed.append(str(e))
            time.sleep(0.02)
        rospy.loginfo('tf world -> top at rospy.Time.now(): %d found at once, %d after waiting (up to %g s), %d '
                      'failed; the clock ahead of the latest tf by up to %.4f s', at_once, waited, TF_WAIT,
                      len(failed), max(lags))
        self.assertGreater(at_once + waited, 50)
        self.assertEqual(failed, [])

    def test_reset_keeps_clock_and_stamps_monotonic(self):
        r = rospy.ServiceProxy(NODE + '/spawn', Spawn)(name='b', scene='')
        self.assertTrue(r.success, r.message)
        self.addCleanup(rospy.ServiceProxy(NODE + '/kill', Kill), 'b')  # the other tests see the launch's tops only
        reset = rospy.ServiceProxy(NODE + '/reset', Trigger)
        clock = Stream('/clock', Clock, clock_value)
        tops = {name: Stream(NODE + '/' + prefix + 'top_state', TopState, state_fields)
                for name, prefix in (('top', ''), ('b', 'b/'))}
        wait_for(lambda: len(tops['b'].values()) > 10, 30.0, 'b/top_state')
        for _ in range(RESETS):
            time.sleep(WINDOW / (RESETS + 1))
            r = reset()
            self.assertTrue(r.success, r.message)
        time.sleep(WINDOW / (RESETS + 1))
        for s in [clock] + list(tops.values()):
            s.close()
        c = clock.values()
        rospy.loginfo('/clock through %d resets: %d values over %.3f s', RESETS, len(c), (c[-1] - c[0]) * NS)
        self.assertEqual(backward_steps(c, strict=True), [], '/clock does not go forward')
        self.assertGreater((c[-1] - c[0]) * NS, 0.8 * FACTOR * WINDOW)
        for name, s in tops.items():
            stamps, t, work = zip(*s.values())
            # dissipated_work restarts at 0 on each reset: the resets happened while time went on.
            drops = len(backward_steps(work))
            rospy.loginfo('%s through the resets: %d TopStates, dissipated_work dropped %d times, stamps back %d, '
                          'sim_time back %d', name, len(stamps), drops, len(backward_steps(stamps)),
                          len(backward_steps(t)))
            self.assertEqual(drops, RESETS, name)
            self.assertEqual(backward_steps(stamps), [], name + ': stamps go back')
            self.assertEqual(backward_steps(t), [], name + ': sim_time goes back')
            assert_follows(self, s.ahead(), TYPICAL, TOLERANCE, name + ' through resets')


if __name__ == '__main__':
    rospy.init_node('test_clock')
    rostest.rosrun('top_sim', 'test_clock', ClockFollower, sys.argv)
