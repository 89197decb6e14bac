#!/usr/bin/env python3
"""The record launch writes a bag holding top_state and tf in the expected counts (checked with the rosbag API);
top_sim_bag turns a recorded bag into top_sim_run's CSV and summary, which agree with top_sim_run's own on the same
scene; top_sim_fit fits the bag; top_sim_bag's command line on synthetic bags (several tops, errors).

Runs `roslaunch top_sim top_sim.launch record:=true` against the test's master for a few seconds, stops it
with SIGINT (so rosbag closes the bag) and reads the bag."""
import csv
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np
import rosbag
import rospkg
import rospy
import rostest
from std_msgs.msg import String
from top_sim.msg import TopState, TopStateArray


PKG = rospkg.RosPack().get_path('top_sim')
REGIME_CADENCE = 0.1  # s, top_sim::Simulator::kRegimeCadence: top_sim_run's regime_seconds are classified there


def devel_binary(name):
    """A top_sim executable of the workspace under test (catkin's devel space)."""
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
        candidate = os.path.join(prefix, 'lib', 'top_sim', name)
        if os.path.isfile(candidate):
            return candidate
    raise RuntimeError('%s not found under CMAKE_PREFIX_PATH' % name)


class RecordLaunch(unittest.TestCase):
    def record(self, name, rate, seconds, *args):
        """Runs the launch file with record:=true for `seconds` of wall time; returns the bag's path."""
        bag = os.path.join(tempfile.mkdtemp(prefix='top_sim_record_'), 'record.bag')
        proc = subprocess.Popen(['roslaunch', 'top_sim', 'top_sim.launch', 'rviz:=false', 'record:=true',
                                 'bag:=' + bag, 'node_name:=' + name, 'publish_rate:=%g' % rate] + list(args),
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
        return bag

    def test_bag_fits_the_scene_s_friction_law(self):
        # Issue 12: a recorded run is fitted directly. The bag becomes top_sim_run's CSV (top_sim_bag);
        # top_sim_fit starts from a wrong law (mu_c 0.3, s_c 0.5) and must find PMMA's (0.25, 0.6) within 1 %.
        bag = self.record('top_sim_fit_rec', 200.0, 4.0)
        work = os.path.dirname(bag)
        data = os.path.join(work, 'run.csv')
        subprocess.run([devel_binary('top_sim_bag'), bag, '--top', 'top', '--csv', data], check=True)
        with open(os.path.join(PKG, 'config', 'scenes', 'default.yaml')) as f:
            scene = f.read().replace('friction: pmma', 'friction: {law: paper, mu_c: 0.3, s_c: 0.5}')
        self.assertIn('mu_c: 0.3', scene)
        guess = os.path.join(work, 'guess.yaml')
        with open(guess, 'w') as f:
            f.write(scene)
        result = os.path.join(work, 'fit.json')
        p = subprocess.run([devel_binary('top_sim_fit'), 'trajectory', data, '--scene', guess,
                            '--free', 'friction.mu_c,friction.s_c', '--json', result],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        self.assertEqual(p.returncode, 0, p.stdout)
        with open(result) as f:
            fit = json.load(f)
        rospy.loginfo('fit of the bag: %s', fit['parameters'])
        print('[ measured ] fit of the bag: %s, chi2 %.3g, %d evaluations' % (fit['parameters'], fit['chi2'],
                                                                          fit['evaluations']))
        self.assertAlmostEqual(fit['parameters']['friction.mu_c'], 0.25, delta=0.01 * 0.25)
        self.assertAlmostEqual(fit['parameters']['friction.s_c'], 0.6, delta=0.01 * 0.6)

    def test_bag_has_top_state_and_tf(self):
        rate = rospy.get_param('~publish_rate')
        seconds = rospy.get_param('~seconds')
        name = 'top_sim_rec'
        bag = self.record(name, rate, seconds)
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


    def test_bag_agrees_with_top_sim_run(self):
        # Issue 13: the node's states through a bag and top_sim_bag against top_sim_run on the same scene, at the
        # same simulated times; then the summaries' regime durations, phi_measured and phi_star.
        bag = self.record('top_sim_bag_rec', 200.0, 4.0)
        work = os.path.dirname(bag)
        out = lambda name: os.path.join(work, name)  # noqa: E731
        scene = os.path.join(PKG, 'config', 'scenes', 'default.yaml')
        tool = devel_binary('top_sim_bag')
        subprocess.run([tool, bag, '--csv', out('bag.csv'), '--json', out('bag.json'), '--plot', out('bag.png')],
                       check=True)
        subprocess.run([tool, bag, '--scene', scene, '--json', out('bag_scene.json')], check=True)
        with open(out('bag.json')) as f:
            bag_json = json.load(f)
        rate = 10000.0  # dense enough that interpolating it stays far below the node's publish period's motion
        end = math.ceil(bag_json['t_last'] * rate) / rate  # on top_sim_run's sample grid, at or after the bag's end
        subprocess.run([devel_binary('top_sim_run'), scene, '--duration', repr(end), '--rate', '%g' % rate, '--csv',
                        out('run.csv'), '--summary', out('run.json'), '--quiet'], check=True, stdout=subprocess.DEVNULL)
        with open(out('run.json')) as f:
            run_json = json.load(f)
        b, r = read_csv(out('bag.csv')), read_csv(out('run.csv'))
        self.assertEqual(len(b['t']), bag_json['samples'])
        self.assertGreaterEqual(b['t'][0], r['t'][0])
        self.assertLessEqual(b['t'][-1], r['t'][-1])
        self.check_states(b, r)
        self.check_regimes(b, r, bag_json, run_json, 1.0 / rate)
        self.check_phi_measured(b, r, bag_json, run_json, 1.0 / rate)
        # phi* depends on alpha and the friction law only (physics.md section 5), which the two runs share.
        with open(out('bag_scene.json')) as f:
            scene_json = json.load(f)
        for j, source in ((bag_json, 'TopState'), (scene_json, '--scene')):
            self.assertIn(source, j['phi_star_source'])
            self.assertAlmostEqual(j['phi_star'], run_json['phi_star'], delta=1e-12)
        self.assertEqual(scene_json['method'], run_json['method'])
        self.assertGreater(os.path.getsize(out('bag.png')), 10000, 'plot written')

    def check_states(self, b, r):
        """Each bag state against top_sim_run's CSV linearly interpolated at its sim_time. Tolerance per column: the
        interpolation error bound h^2/8 max|x''| (max|x''| h^2 from the CSV's second differences, doubled for their
        underestimate) plus 1e-12 relative (the CSVs are exact since they print shortest round-trip text; this floor
        was their 12-digit rounding before): the node and top_sim_run integrate the
        same scene with the same dense-output stepper, so they should differ by no more than that."""
        worst, allowed = {}, {}
        for group, columns in (('com', ('com_x', 'com_y', 'com_z')), ('f_hat', ('f_x', 'f_y', 'f_z')),
                               ('spin', ('spin',))):
            for c in columns:
                error = np.abs(np.interp(b['t'], r['t'], r[c]) - b[c])
                tolerance = 2.0 * np.abs(np.diff(r[c], 2)).max() / 8.0 + 1e-12 * np.abs(r[c]).max() + 1e-15
                i = int(np.argmax(error))
                self.assertLessEqual(error[i], tolerance, '%s at t = %.6f s: bag %.12g, top_sim_run %.12g'
                                     % (c, b['t'][i], b[c][i], np.interp(b['t'][i], r['t'], r[c])))
                worst[group] = max(worst.get(group, 0.0), error[i])
                allowed[group] = max(allowed.get(group, 0.0), tolerance)
        message = ('top_sim_bag vs top_sim_run: max abs error com %.3g m, f_hat %.3g, spin %.3g rad/s over %d states, '
                   't = %.4f to %.4f s (tolerances %.3g m, %.3g, %.3g rad/s)'
                   % (worst['com'], worst['f_hat'], worst['spin'], len(b['t']), b['t'][0], b['t'][-1],
                      allowed['com'], allowed['f_hat'], allowed['spin']))
        rospy.loginfo(message)
        print('[ measured ] ' + message)

    def check_regimes(self, b, r, bag_json, run_json, h):
        """The bag's regime_seconds against top_sim_run's, less the run's time outside the bag's window (the bag
        misses the start before rosbag subscribed). Each regime change is seen up to one sample interval late by
        each (the bag's largest, H, and h), and the window's edges are cut at h; top_sim_run's regime_seconds come
        from the simulator's regime cadence (REGIME_CADENCE), so each change of the whole run moves them by up to
        one cadence interval against the CSV's samples."""
        t0, t1, end = bag_json['t_first'], bag_json['t_last'], r['t'][-1]
        regimes = run_json['regime_seconds'].keys()
        in_window = [n for t, n in zip(r['t'], r['regime']) if t0 <= t <= t1]
        changes = max(count_changes(in_window), count_changes(b['regime']))
        tolerance = (changes * (np.diff(b['t']).max() + h) + count_changes(list(r['regime'])) * REGIME_CADENCE
                     + 2.0 * h + 1e-9)
        outside = {n: seconds_in(r, n, r['t'][0], t0) + seconds_in(r, n, t1, end) for n in regimes}
        self.assertAlmostEqual(sum(bag_json['regime_seconds'].values()), t1 - t0, delta=1e-9)
        for n in regimes:
            expected = run_json['regime_seconds'][n] - outside[n]
            self.assertAlmostEqual(bag_json['regime_seconds'][n], expected, delta=tolerance, msg=n)
        message = 'regime_seconds: bag %s, top_sim_run over the bag\'s window %s (tolerance %.3g s, %d changes)' % (
            bag_json['regime_seconds'], {n: round(run_json['regime_seconds'][n] - outside[n], 6) for n in regimes},
            tolerance, changes)
        rospy.loginfo(message)
        print('[ measured ] ' + message)

    def check_phi_measured(self, b, r, bag_json, run_json, h):
        """phi_measured is the chord direction of the contact point over the last 20 % of each one's window. The
        chord from top_sim_run's CSV reproduces top_sim_run's own value, then the bag's over the bag's window.
        Tolerance: the linear interpolation error bound of the mark's point (its sample interval, squared, / 8 x
        the contact point's largest acceleration, doubled) over the chord's length."""
        accel = 2.0 * max(np.abs(np.diff(r['contact_x'], 2)).max(), np.abs(np.diff(r['contact_y'], 2)).max()) / h**2
        H = np.diff(b['t']).max()
        for name, j, t0, t1, step in (('top_sim_run', run_json, r['t'][0], r['t'][-1], 0.0),
                                      ('top_sim_bag', bag_json, bag_json['t_first'], bag_json['t_last'], H)):
            phi, length = chord(r, t0, t1)
            tolerance = (step**2 + 2.0 * h**2) / 8.0 * accel / length + 1e-9
            self.assertAlmostEqual(j['phi_measured'], phi, delta=tolerance, msg=name)
            message = '%s phi_measured %.12f, from top_sim_run\'s CSV %.12f: difference %.3g (tolerance %.3g rad)' % (
                name, j['phi_measured'], phi, abs(j['phi_measured'] - phi), tolerance)
            rospy.loginfo(message)
            print('[ measured ] ' + message)



def state(t):
    """A sleeping top drifting along x at 1 mm/s (only what the tool reads needs to make sense)."""
    m = TopState()
    m.sim_time = t
    m.contact_point.x = 1e-3 * t
    m.figure_axis.z = 1.0
    m.pose.orientation.w = 1.0
    m.regime, m.regime_name = TopState.SLEEPING, 'sleeping'
    m.contact_mode, m.contact_mode_name = TopState.SLIPPING, 'slipping'
    return m


class BagTool(unittest.TestCase):
    """top_sim_bag's command line on synthetic bags: several tops, --top, --from/--to, file names, exit codes."""

    def setUp(self):
        self.work = tempfile.mkdtemp(prefix='top_sim_bag_tool_')

    def bag(self, topics, name='synthetic.bag'):
        """A bag with TopStates at the given sim_times per topic (a str value: one std_msgs/String)."""
        path = os.path.join(self.work, name)
        with rosbag.Bag(path, 'w') as b:
            for topic, times in topics.items():
                if isinstance(times, str):
                    b.write(topic, String(data=times), rospy.Time(1.0))
                    continue
                for k, t in enumerate(times):
                    b.write(topic, state(t), rospy.Time(1.0 + 1e-3 * k))
        return path

    def run_tool(self, *args):
        return subprocess.run([devel_binary('top_sim_bag')] + list(args), stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, universal_newlines=True, cwd=self.work)

    def out(self, name):
        return os.path.join(self.work, name)

    def test_several_tops_are_written_one_file_each(self):
        bag = self.bag({'/top_sim/top_state': [0.0, 0.1, 0.2, 0.2, 0.3], '/top_sim/spinner/top_state': [0.0, 0.5, 1.0],
                        '/chatter': 'not a top'})
        p = self.run_tool(bag, '--csv', self.out('run.csv'), '--json', self.out('run.json'))
        self.assertEqual(p.returncode, 0, p.stderr)
        for top, rows, skipped, seconds in (('top', 4, 1, 0.3), ('spinner', 3, 0, 1.0)):
            data = read_csv(self.out('run_%s.csv' % top))
            self.assertEqual(len(data['t']), rows, top)
            self.assertEqual(list(data['regime']), ['sleeping'] * rows)
            with open(self.out('run_%s.json' % top)) as f:
                j = json.load(f)
            self.assertEqual(j['top'], top)
            self.assertEqual(j['samples'], rows)
            self.assertEqual(j['skipped'], skipped, 'the repeated instant (a paused node) is skipped')
            self.assertAlmostEqual(j['regime_seconds']['sleeping'], seconds, delta=1e-12)
            self.assertAlmostEqual(j['phi_measured'], 0.0, delta=1e-12)  # along +x = h
            self.assertIn(top, p.stdout)
        self.assertFalse(os.path.exists(self.out('run.csv')))

    def test_top_selects_by_name_or_topic_and_from_to_by_sim_time(self):
        bag = self.bag({'/top_sim/top_state': [0.0, 0.1, 0.2, 0.3], '/top_sim/spinner/top_state': [0.0, 0.5, 1.0]})
        for wanted in ('spinner', '/top_sim/spinner/top_state'):
            p = self.run_tool(bag, '--top', wanted, '--csv', self.out('one.csv'))
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(len(read_csv(self.out('one.csv'))['t']), 3)
        # The launch-time top is 'top', as in the node's ~list and top_states.
        p = self.run_tool(bag, '--top', 'top', '--from', '0.1', '--to', '0.25', '--csv', self.out('window.csv'))
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(list(read_csv(self.out('window.csv'))['t']), [0.1, 0.2])

    def test_colliding_names_are_qualified_by_namespace(self):
        bag = self.bag({'/a/x/top_state': [0.0, 0.1], '/b/x/top_state': [0.0, 0.2]})
        p = self.run_tool(bag, '--json', self.out('s.json'))
        self.assertEqual(p.returncode, 0, p.stderr)
        for name in ('a.x', 'b.x'):
            with open(self.out('s_%s.json' % name)) as f:
                self.assertEqual(json.load(f)['top'], name)
        self.assertEqual(self.run_tool(bag, '--top', 'x').returncode, 2)
        # Two nodes' launch-time tops (both 'top') are named by their nodes.
        bag = self.bag({'/a/top_state': [0.0, 0.1], '/b/top_state': [0.0, 0.2]}, 'two_nodes.bag')
        p = self.run_tool(bag, '--json', self.out('n.json'))
        self.assertEqual(p.returncode, 0, p.stderr)
        for name in ('a', 'b'):
            with open(self.out('n_%s.json' % name)) as f:
                self.assertEqual(json.load(f)['top'], name)

    def test_tops_are_read_out_of_top_states(self):
        """Issue 49: a bag of /NS/top_states alone (what a user records for many tops) gives each top; a top with
        its own TopState topic in the bag is read from that; one present only between the first and last
        messages is read with --top."""
        path = os.path.join(self.work, 'array.bag')
        times = [0.0, 0.1, 0.2, 0.3]
        with rosbag.Bag(path, 'w') as b:
            for k, t in enumerate(times):
                names = ['top', 'a'] + (['mid'] if k in (1, 2) else []) + (['late'] if k >= 2 else [])
                arr = TopStateArray(names=names, states=[state(t) for _ in names])
                arr.states[1].contact_point.x = 2e-3 * t  # a's own path: twice as fast
                b.write('/top_sim/top_states', arr, rospy.Time(1.0 + 1e-3 * k))
            for k, t in enumerate(times[:2]):
                b.write('/top_sim/top_state', state(t), rospy.Time(1.0 + 1e-3 * k))
        p = self.run_tool(path, '--json', self.out('arr.json'))
        self.assertEqual(p.returncode, 0, p.stderr)
        for top, samples in (('top', 2), ('a', 4), ('late', 2)):
            with open(self.out('arr_%s.json' % top)) as f:
                self.assertEqual(json.load(f)['samples'], samples, top)
        self.assertFalse(os.path.exists(self.out('arr_mid.json')))
        p = self.run_tool(path, '--top', 'mid', '--csv', self.out('mid.csv'))
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(list(read_csv(self.out('mid.csv'))['t']), [0.1, 0.2])
        p = self.run_tool(path, '--top', 'a', '--csv', self.out('a.csv'))
        self.assertEqual(p.returncode, 0, p.stderr)
        np.testing.assert_allclose(read_csv(self.out('a.csv'))['contact_x'], [2e-3 * t for t in times], rtol=0,
                                   atol=1e-12)  # a's entry, not another's (1e-3 t)
        self.assertEqual(self.run_tool(path, '--top', 'nosuch').returncode, 2)

    def end_bag(self, end_state, name):
        """A disc's recording: in flight (touching 0), on its rim (touching 1), then stopped at `end_state`."""
        path = os.path.join(self.work, name)
        with rosbag.Bag(path, 'w') as b:
            for k, (t, touching) in enumerate(((0.0, 0), (0.1, 1), (0.2, 1))):
                m = state(t)
                m.touching = touching
                if k == 2:
                    m.end_state, m.end_state_message = end_state, 't = 0.2 s: end state %s: the rim lies flat' % end_state
                b.write('/top_sim/top_state', m, rospy.Time(1.0 + 1e-3 * k))
        return path

    def test_recorded_end_state_and_touching_reach_the_summary_and_csv(self):
        p = self.run_tool(self.end_bag('lying_flat', 'disc.bag'), '--json', self.out('disc.json'), '--csv',
                          self.out('disc.csv'))
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(self.out('disc.json')) as f:
            j = json.load(f)
        self.assertEqual(j['end_state'], 'lying_flat')
        self.assertEqual(j['end_state_message'], 't = 0.2 s: end state lying_flat: the rim lies flat')
        for key in ('end_state', 'end_state_message'):
            self.assertNotIn(key, j.get('unavailable', {}))
        self.assertIsNone(j['contact_fault'])  # an end state is no fault
        self.assertEqual(j['final']['touching'], 1)
        self.assertEqual(list(read_csv(self.out('disc.csv'))['touching']), [0.0, 1.0, 1.0])
        # A name the core does not know is bad input naming the field.
        p = self.run_tool(self.end_bag('lying_down', 'unknown.bag'), '--json', self.out('unknown.json'))
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertIn("end_state = 'lying_down': must be empty or one of lying_flat", p.stderr)

    def test_bad_input_exits_two_and_write_errors_one(self):
        two = self.bag({'/top_sim/top_state': [0.0, 0.1], '/top_sim/spinner/top_state': [0.0, 0.1]})
        chatter = self.bag({'/chatter': 'hello'}, 'chatter.bag')
        with open(self.out('text.bag'), 'w') as f:
            f.write('not a bag\n')
        for args, status, words in (
                ([self.out('missing.bag')], 2, 'no such file'),
                ([self.out('text.bag')], 2, 'text.bag'),
                ([chatter], 2, 'no top_sim/TopState or TopStateArray topic; the bag has: /chatter (std_msgs/String)'),
                ([two, '--top', 'nope'], 2, "--top = 'nope': no such top"),
                ([two, '--json', '-'], 2, 'standard output takes one top'),
                ([two, '--from', '5', '--to', '6'], 2, 'no TopState with sim_time in [5, 6]'),
                ([two, '--from', '1', '--to', '0'], 2, 'must be <= --to'),
                ([two, '--top', 'spinner', '--csv', self.out('no/such/dir.csv')], 1, 'cannot open for writing'),
                ([two, '--top', 'spinner', '--json', '/dev/full'], 1, 'writing failed')):
            p = self.run_tool(*args)
            self.assertEqual(p.returncode, status, '%s: %s' % (args, p.stderr))
            self.assertIn(words, p.stderr, args)
        p = self.run_tool(two, '--top', 'nope')
        for known in ('top (/top_sim/top_state)', 'spinner (/top_sim/spinner/top_state)'):
            self.assertIn(known, p.stderr)


def read_csv(path):
    """top_sim_run's CSV columns: numbers as arrays, regime and contact_mode as lists of names."""
    with open(path, newline='') as f:
        rows = list(csv.DictReader(f))
    text = ('regime', 'contact_mode')
    return {k: [row[k] for row in rows] if k in text else np.array([float(row[k]) for row in rows]) for k in rows[0]}


def count_changes(names):
    return sum(a != c for a, c in zip(names, names[1:]))


def seconds_in(r, regime, lo, hi):
    """Seconds of [lo, hi] that the CSV's samples give to `regime` (each interval counts for its first sample)."""
    t = r['t']
    overlap = np.clip(np.minimum(t[1:], hi) - np.maximum(t[:-1], lo), 0.0, None)
    return float(sum(o for o, name in zip(overlap, r['regime'][:-1]) if name == regime))


def chord(r, t0, t1):
    """Direction (from h towards downhill) and length of the contact point's displacement from the mark at 80 % of
    [t0, t1] to t1, on top_sim_run's CSV linearly interpolated."""
    mark = t0 + 0.8 * (t1 - t0)
    x0, y0, x1, y1 = (np.interp(t, r['t'], r[c]) for t, c in ((mark, 'contact_x'), (mark, 'contact_y'),
                                                             (t1, 'contact_x'), (t1, 'contact_y')))
    return math.atan2(-(y1 - y0), x1 - x0), math.hypot(x1 - x0, y1 - y0)


if __name__ == '__main__':
    rospy.init_node('test_record')
    rostest.rosrun('top_sim', 'test_record', '__main__', sys.argv)  # RecordLaunch and BagTool
