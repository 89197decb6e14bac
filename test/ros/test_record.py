#!/usr/bin/env python3
"""The record launch writes a bag holding top_state and tf in the expected counts (checked with the rosbag API).

Runs `roslaunch top_sim top_sim.launch record:=true` against the test's master for a few seconds, stops it
with SIGINT (so rosbag closes the bag) and reads the bag."""
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import rosbag
import rospy
import rostest


class RecordLaunch(unittest.TestCase):
    def test_bag_has_top_state_and_tf(self):
        rate = rospy.get_param('~publish_rate')
        seconds = rospy.get_param('~seconds')
        name = 'top_sim_rec'
        bag = os.path.join(tempfile.mkdtemp(prefix='top_sim_record_'), 'record.bag')
        proc = subprocess.Popen(['roslaunch', 'top_sim', 'top_sim.launch', 'rviz:=false', 'record:=true',
                                 'bag:=' + bag, 'node_name:=' + name, 'publish_rate:=%g' % rate],
                                stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            deadline = time.time() + 30.0
            while not os.path.exists(bag + '.active') and time.time() < deadline:
                time.sleep(0.1)
            self.assertTrue(os.path.exists(bag + '.active'), 'rosbag record did not start')
            time.sleep(seconds)
        finally:
            os.killpg(proc.pid, signal.SIGINT)
            proc.wait(timeout=30.0)
        self.assertTrue(os.path.exists(bag), 'no bag at %s' % bag)
        topic = '/%s/top_state' % name
        stamps, tf_stamps, tf_count = [], [], 0
        with rosbag.Bag(bag) as b:
            info = b.get_type_and_topic_info().topics
            self.assertIn(topic, info)
            self.assertIn('/tf', info)
            self.assertEqual(info[topic].msg_type, 'top_sim/TopState')
            for t, m, _ in b.read_messages(topics=[topic, '/tf']):
                if t == topic:
                    stamps.append(m.header.stamp.to_sec())
                else:
                    for tr in m.transforms:
                        if tr.child_frame_id in ('plane', 'top'):
                            tf_count += 1
                            tf_stamps.append(tr.header.stamp.to_sec())
        n = len(stamps)
        span = stamps[-1] - stamps[0]
        rospy.loginfo('bag: %d top_state over %.3f s of stamps, %d transforms', n, span, tf_count)
        # One TopState per publish period (real-time factor 1: stamps span the recording).
        self.assertGreaterEqual(n, 0.8 * rate * seconds)
        self.assertAlmostEqual((n - 1) / span, rate, delta=0.05 * rate)
        # Two transforms (world -> plane, plane -> top) per period; the two subscriptions may start a tick apart.
        self.assertLessEqual(abs(tf_count - 2 * n), 2 * 5)
        self.assertTrue(all(b > a for a, b in zip(stamps, stamps[1:])), 'top_state stamps strictly increase')


if __name__ == '__main__':
    rospy.init_node('test_record')
    rostest.rosrun('top_sim', 'test_record', RecordLaunch, sys.argv)
