#!/usr/bin/env python3
"""Replaying a recorded run gives the simulation's stamps (docs/ros.md, "Time, /clock and replay").

Everything runs with /use_sim_time true (replay.test): top_sim.launch publish_clock:=true is the clock while
`rosbag record` writes top_state, /tf and /clock, so the bag's record times are simulated times too. Then the node
is stopped and the bag is played three ways against this listener:
  1. `rosbag play BAG`: the recorded /clock is replayed as it was; clock and stamps must be the recorded ones.
  2. `rosbag play --clock BAG --topics top_state /tf`: rosbag's own clock, from the record times.
  3. `rosbag play --clock BAG`: both clocks on /clock at once; the docs warn against it because it goes back."""
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
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

from top_sim.msg import TopState

import clock_util
from clock_util import NS, Stream, assert_follows, backward_steps, not_in, wait_for

NODE = 'top_sim_replay'
STATE = '/%s/top_state' % NODE
TOP_FRAME = 'top'
RATE = 200.0  # publish rate [Hz]
# Simulated seconds per wall second: away from 1, so a clock from the wall time (or from wall record times) would be
# off by seconds instead of milliseconds.
FACTOR = 0.5
SECONDS = 4.0  # wall seconds of recording
# TopState stamp - the listener's clock at its arrival [simulated s]: the replayed topics come on separate connections
# to separate threads of the listener, rosbag's own clock ticks at 100 Hz. Median of its size: 0.02 s (a clock from
# the wall time or from wall record times would be 0.5 s off or more); at most this far in the future: 0.25 s.
# (Late messages are only logged: rosbag record starved of CPU gives a stretch of messages one late record time.)
TYPICAL, TOLERANCE = 0.02, 0.25


def stop(proc):
    """SIGINT to the process group (so rosbag closes its bag), then wait."""
    os.killpg(proc.pid, signal.SIGINT)
    proc.wait(timeout=30.0)


def value_of(topic):
    return {STATE: clock_util.header_stamp, '/clock': clock_util.clock_value,
            '/tf': clock_util.tf_stamp(TOP_FRAME)}[topic]


def read_bag(path):
    """Per topic, the recorded values in the bag's order (record time); under 'late', record time - stamp of each
    TopState [ns]."""
    out = {STATE: [], '/clock': [], '/tf': []}
    late = []
    with rosbag.Bag(path) as b:
        for topic, m, t in b.read_messages(topics=list(out)):
            v = value_of(topic)(m)
            if v is not None:
                out[topic].append(v)
            if topic == STATE:
                late.append(t.to_nsec() - v)
    return out, late


class Replay(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix='top_sim_replay_')
        cls.bag = os.path.join(cls.work, 'run.bag')
        node = subprocess.Popen(['roslaunch', 'top_sim', 'top_sim.launch', 'rviz:=false', 'publish_clock:=true',
                                 'node_name:=' + NODE, 'publish_rate:=%g' % RATE,
                                 'real_time_factor:=%g' % FACTOR],
                                stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            wait_for(lambda: rospy.Time.now() > rospy.Time(0), 60.0, "the node's /clock")
            rec = subprocess.Popen(['rosbag', 'record', '-O', cls.bag, STATE, '/tf', '/clock',
                                    '__name:=replay_recorder'],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT, start_new_session=True)
            try:
                wait_for(lambda: os.path.exists(cls.bag + '.active'), 30.0, 'rosbag record')
                time.sleep(SECONDS)
            finally:
                stop(rec)
        finally:
            stop(node)
        cls.recorded, cls.late = read_bag(cls.bag)

    def play(self, *args):
        """Plays the bag with `args`; per topic, what this listener received (Stream)."""
        streams = {t: Stream(t, kind, value_of(t)) for t, kind in
                   ((STATE, TopState), ('/clock', Clock), ('/tf', TFMessage))}
        try:
            # stdin: rosbag play reads keys from it; --wait-for-subscribers: nothing is sent before we listen.
            p = subprocess.run(['rosbag', 'play', '--wait-for-subscribers', '-d', '1', self.bag] + list(args),
                               stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               universal_newlines=True, timeout=120.0)
            self.assertEqual(p.returncode, 0, p.stdout)
            time.sleep(0.5)  # the last messages in flight
        finally:
            for s in streams.values():
                s.close()
        return streams

    def assert_stamps_follow_clock(self, got, what):
        # Before the first replayed /clock the listener still has the live run's last time: those are not counted.
        ahead = got[STATE].ahead(since=got['/clock'].first_arrival())
        early = len(got[STATE].values()) - len(ahead)
        rospy.loginfo('%s: %d top_state before the first /clock', what, early)
        self.assertLessEqual(early, 5, what)
        assert_follows(self, ahead, TYPICAL, TOLERANCE, what)

    def test_bag_holds_the_simulation_clock(self):
        rec = self.recorded
        n = {t: len(v) for t, v in rec.items()}
        rospy.loginfo('bag: %s; TopState record time - stamp from %.4f to %.4f s', n, min(self.late) * NS,
                      max(self.late) * NS)
        for topic, values in rec.items():
            self.assertGreaterEqual(len(values), 0.5 * RATE * SECONDS, topic)  # the recorder starts in about 1 s
            self.assertEqual(backward_steps(values, strict=True), [], topic + ' does not go forward in the bag')
        # /clock is the launch-time top's stamp: one clock value per TopState stamp, where both were recorded.
        for values, reference, what in ((rec[STATE], rec['/clock'], 'TopState stamps not on /clock'),
                                        (rec['/clock'], rec[STATE], '/clock values not TopState stamps')):
            missing, inside = not_in(values, reference)
            rospy.loginfo('bag: %d %s of %d', len(missing), what, inside)
            self.assertGreaterEqual(inside, 0.5 * RATE * SECONDS)
            self.assertEqual(missing, [], what)

    def test_play_replays_the_recorded_clock_and_stamps(self):
        got = self.play()
        for topic in (STATE, '/tf'):
            self.assertEqual(got[topic].values(), self.recorded[topic], topic + ': replayed values differ')
        rospy.loginfo('rosbag play: %d top_state and %d tf stamps replayed identical', len(self.recorded[STATE]),
                      len(self.recorded['/tf']))
        # rosbag sends the bag's /clock through its own clock publisher, whose queue holds one message: of clock
        # messages it sends at once (recorded at one instant, or late when rosbag was starved of CPU) it drops some.
        clock, recorded = got['/clock'].values(), self.recorded['/clock']
        kept = set(clock)
        self.assertEqual([v for v in recorded if v in kept], clock, 'replayed /clock: not recorded values in order')
        gap = max(b - a for a, b in zip(clock, clock[1:]))
        rospy.loginfo('rosbag play: %d of %d recorded /clock values replayed, largest step %.4f s', len(clock),
                      len(recorded), gap * NS)
        self.assertGreaterEqual(len(clock), 0.5 * len(recorded))
        self.assert_stamps_follow_clock(got, 'rosbag play')

    def test_play_clock_without_the_recorded_clock(self):
        got = self.play('--clock', '--topics', STATE, '/tf')
        self.assertEqual(got[STATE].values(), self.recorded[STATE])
        clock = got['/clock'].values()
        # rosbag's clock ticks at its default 100 Hz while it replays SECONDS * FACTOR simulated seconds
        self.assertGreaterEqual(len(clock), 0.5 * 100.0 * SECONDS * FACTOR)
        self.assertEqual(backward_steps(clock), [], "rosbag's clock went back")
        self.assert_stamps_follow_clock(got, 'rosbag play --clock, /clock not played')

    def test_play_clock_with_the_recorded_clock_goes_back(self):
        # The pitfall the docs describe: rosbag's clock (record times) interleaved with the recorded one.
        clock = self.play('--clock')['/clock'].values()
        back = backward_steps(clock)
        rospy.loginfo('rosbag play --clock with /clock in the bag: %d of %d clock steps go back, by up to %.4f s',
                      len(back), len(clock), max([d for _, d in back] or [0]) * NS)
        self.assertGreater(len(back), 0)


if __name__ == '__main__':
    rospy.init_node('test_replay')
    rostest.rosrun('top_sim', 'test_replay', Replay, sys.argv)
