"""Helpers of the time rostests (test_clock.py, test_replay.py; docs/ros.md, "Time, /clock and replay").

Times are integer nanoseconds, so recorded and replayed stamps compare exactly. The listener runs with
/use_sim_time true: rospy.Time.now() is the last /clock it received."""
import threading
import time

import rospy

NS = 1e-9  # seconds per nanosecond, for the log lines


def clock_value(m):
    return m.clock.to_nsec()


def header_stamp(m):
    return m.header.stamp.to_nsec()


def tf_stamp(child):
    """The stamp of the transform to `child` in a TFMessage, or None when the message has none."""
    def value(m):
        for t in m.transforms:
            if t.child_frame_id == child:
                return t.header.stamp.to_nsec()
        return None
    return value


class Stream(object):
    """Every message of a topic as (value, this node's ROS time when it arrived, wall time when it arrived).
    value(m): the message's stamp [ns], or a tuple that starts with it; None skips the message."""

    def __init__(self, topic, kind, value):
        self.rows = []
        self._value = value
        self._lock = threading.Lock()
        # -1: unbounded for the connections made from now on. (rospy fixes a connection's queue when it connects:
        # its own /clock subscription, made at init, keeps 1 and may skip clock values when the listener lags.)
        self.sub = rospy.Subscriber(topic, kind, self._on_msg, queue_size=-1)

    def _on_msg(self, m):
        v = self._value(m)
        if v is not None:
            with self._lock:
                self.rows.append((v, rospy.Time.now().to_nsec(), time.monotonic()))

    def values(self):
        with self._lock:
            return [v for v, _, _ in self.rows]

    def first_arrival(self):
        with self._lock:
            return self.rows[0][2] if self.rows else None

    def ahead(self, since=float('-inf')):
        """Per message arrived after wall time `since`: value minus the listener's clock at its arrival [ns]
        (> 0: stamped in the clock's future)."""
        with self._lock:
            return [(v[0] if isinstance(v, tuple) else v) - now for v, now, arrival in self.rows if arrival > since]

    def close(self):
        self.sub.unregister()


def backward_steps(values, strict=False):
    """The steps of a sequence that go back (strict: that do not go forward): [(index, how far back)]."""
    return [(i, a - b) for i, (a, b) in enumerate(zip(values, values[1:]), 1) if b < a or (strict and b == a)]


def assert_follows(case, ahead, typical, tolerance, what):
    """Stamps on the listener's clock (`ahead`: Stream.ahead(), stamp - clock at arrival): the median of
    |stamp - clock| within `typical` (the clock is the stamps' time), none stamped more than `tolerance` [s] in the
    clock's future. Stamps behind the clock (late messages: a starved thread) are only logged."""
    case.assertGreater(len(ahead), 0, what + ': nothing received')
    apart = sorted(abs(a) * NS for a in ahead)
    median, q95 = apart[len(apart) // 2], apart[int(0.95 * (len(apart) - 1))]
    rospy.loginfo('%s: %d messages, stamp - clock at arrival from %.4f to %.4f s, |stamp - clock| median %.4f s, '
                  '95th percentile %.4f s (tolerances %.4f and %.4f s)', what, len(ahead), min(ahead) * NS,
                  max(ahead) * NS, median, q95, typical, tolerance)
    case.assertLessEqual(median, typical, what + ': the clock is not the stamps\' time')
    case.assertLessEqual(max(ahead) * NS, tolerance, what + ': a message from the clock\'s future')


def not_in(values, reference):
    """The values inside the span of `reference` that are not among its values, and how many are inside (e.g.
    /clock against the launch-time top's stamps: /clock is that top's stamp)."""
    known = set(reference)
    inside = [v for v in values if reference[0] <= v <= reference[-1]]
    return [v for v in inside if v not in known], len(inside)


def wait_for(pred, timeout, what):
    """Polls pred() on the wall clock (sim time may stand still); raises naming `what` after `timeout` s."""
    deadline = time.time() + timeout
    while not pred():
        if time.time() > deadline or rospy.is_shutdown():
            raise AssertionError('timed out after %g s waiting for %s' % (timeout, what))
        time.sleep(0.05)
