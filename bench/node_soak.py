#!/usr/bin/env python3
"""Soak and flood benchmark of top_sim_node (issue 11): the node under a command flood or random valid commands
for ten minutes.

Why: the rostests run the node for seconds; a slow leak, a rate that sags, a NaN that slips through validation
or a loop that stops answering shows only over minutes of abuse. The node is launched with launch/top_sim.launch
(no rviz, default scene, default publish rate) against a private rosmaster, and for --duration seconds:

  flood   TopCommand on ~command at --flood-rate (default 1 kHz), mostly valid (inclination, spin, paper law),
          --invalid-fraction of them invalid (NaN, Inf, |alpha| >= pi/2, negative mu_c, unknown law, ...);
  random  random valid TopCommands at a few Hz: inclination below the critical angle atan(max mu) of the law in
          force at times and above it at others, spin of either sign, friction law changes (paper, coulomb,
          linearized, table), static friction, restitution, and a ~reset about once a minute.

In both modes a ~reset follows any CONTACT_FAULT seen in TopState (counted), so that one fault does not end
the soak. Every TopState is recorded: receive rate per --window (median, min), holes in header.seq, non-finite
numbers in any field (count), the energy-balance residual (TopState.energy_balance_residual is relative to the
last command or reset; /diagnostics also gives the max since the last reset), and the achieved real-time factor.
Every --sample-period: the node's VmRSS (/proc/<pid>/status), its CPU time (/proc/<pid>/stat) and the 1-minute
load average (the machine is shared). Every --alive-period: a ~pause call with data=false (a no-op on a running
node, answered by the node's own loop, unlike ~get_loggers which roscpp answers from an internal thread).

  bench/node_soak.py --mode flood|random [--duration 600] [--json FILE] [--seed 1]

Writes a JSON result (--json) and prints a one-line summary. Exit status 0 whatever the figures (a benchmark
reports, it does not assert), non-zero only if the harness itself failed (no build, the node never came up).
Needs a built workspace (scripts/build.sh).
"""
import argparse
import json
import math
import os
import random
import re
import statistics
import sys
import threading
import time
import warnings

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, 'scripts'))
from node_harness import (CLK_TCK, cpu_ticks, launch_node, loadavg_1min, percentile, ros_environment,  # noqa: E402
                          rss_kib, start_master, stop_group)

CONTACT_FAULT = 4   # TopState.CONTACT_FAULT
SCENE_LAW = {'law': 'paper', 'mu_c': 0.25, 's_c': 0.6}   # config/planes/pmma.yaml, the default scene's plane


# ---- commands ----------------------------------------------------------------------------------------------------

def law_mu0(law):
    """mu(0) of a friction law dict: the lower bound the core demands of static_friction."""
    return {'paper': lambda: 0.0, 'coulomb': lambda: law['mu'],
            'linearized': lambda: law['mu0'] - law['k'] * law['s0'],
            'table': lambda: law['table_mu'][0]}[law['law']]()


def law_max_mu(law):
    """The largest mu of a law: its critical inclination is atan of it (no sleeping state above)."""
    return {'paper': lambda: law['mu_c'], 'coulomb': lambda: law['mu'],
            'linearized': lambda: law['mu0'] + law['k'] * (1.0 - law['s0']),
            'table': lambda: max(law['table_mu'])}[law['law']]()


def random_law(rng):
    """A valid friction law with mu >= 0 on all of [0, 1] (no clamp, nothing that propels)."""
    kind = rng.choice(['paper', 'coulomb', 'linearized', 'table'])
    if kind == 'paper':
        return {'law': kind, 'mu_c': rng.uniform(0.15, 0.4), 's_c': rng.uniform(0.5, 1.0)}
    if kind == 'coulomb':
        return {'law': kind, 'mu': rng.uniform(0.1, 0.4)}
    if kind == 'linearized':
        k, s0 = rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0)
        return {'law': kind, 'k': k, 's0': s0, 'mu0': k * s0 + rng.uniform(0.02, 0.3)}
    return {'law': kind, 'table_s': [0.0, rng.uniform(0.1, 0.5), 1.0],
            'table_mu': [rng.uniform(0.0, 0.1), rng.uniform(0.15, 0.4), rng.uniform(0.1, 0.3)]}


def set_law(msg, law):
    """Copies a friction law dict into a TopCommand."""
    msg.set_friction = True
    msg.friction_law = law['law']
    for key, value in law.items():
        if key != 'law':
            setattr(msg, key, value)


class RandomCommands:
    """Random valid commands; remembers the law and static friction in force, which bound what is valid next."""

    def __init__(self, rng, TopCommand):
        self.rng, self.TopCommand = rng, TopCommand
        self.reset()

    def reset(self):
        """After ~reset the node is back at the scene: its law, static friction unset."""
        self.law, self.static_set = dict(SCENE_LAW), False

    def inclination(self):
        """Below the critical angle 70 % of the time, above it (up to 1.5 times, < pi/2) otherwise; 10 % negative."""
        alpha_c = math.atan(law_max_mu(self.law))
        scale = self.rng.uniform(0.0, 0.9) if self.rng.random() < 0.7 else self.rng.uniform(1.05, 1.5)
        sign = -1.0 if self.rng.random() < 0.1 else 1.0
        return sign * min(scale * alpha_c, 1.5), scale > 1.0

    def static(self, law):
        return law_mu0(law) + self.rng.uniform(0.0, 0.1)

    def next(self):
        """(TopCommand, kind, above_critical)."""
        m, kind, above = self.TopCommand(), self.rng.choice(['inclination', 'spin', 'friction', 'static',
                                                             'restitution', 'combined']), False
        if kind in ('inclination', 'combined'):
            m.set_inclination = True
            m.inclination, above = self.inclination()
        if kind in ('spin', 'combined'):
            m.set_spin = True
            m.spin = self.rng.uniform(50.0, 600.0) * (-1.0 if self.rng.random() < 0.2 else 1.0)
        if kind in ('friction', 'combined'):
            self.law = random_law(self.rng)
            set_law(m, self.law)
        if kind == 'static' or (m.set_friction and self.static_set):
            m.set_static_friction, m.static_friction, self.static_set = True, self.static(self.law), True
        if kind == 'restitution':
            m.set_restitution, m.restitution = True, self.rng.uniform(0.0, 1.0)
        return m, kind, above


def valid_flood_command(rng, TopCommand):
    """A valid command near the default scene: inclination below alpha_c, spin, or the paper law."""
    m, kind = TopCommand(), rng.random()
    if kind < 0.45:
        m.set_inclination, m.inclination = True, rng.uniform(0.05, 0.2)
    elif kind < 0.9:
        m.set_spin, m.spin = True, rng.uniform(150.0, 250.0)
    else:
        set_law(m, {'law': 'paper', 'mu_c': rng.uniform(0.2, 0.3), 's_c': rng.uniform(0.5, 0.8)})
    return m


def invalid_flood_command(rng, TopCommand):
    """A command the node must reject as a whole: a non-finite or out-of-range value, or a malformed law."""
    m, nan, inf = TopCommand(), float('nan'), float('inf')
    case = rng.randrange(8)
    if case < 3:
        m.set_inclination, m.inclination = True, [nan, inf, 1.6][case]
    elif case < 5:
        m.set_spin, m.spin = True, [nan, -inf][case - 3]
    elif case == 5:
        set_law(m, {'law': 'paper', 'mu_c': -0.1, 's_c': 0.6})
    elif case == 6:
        set_law(m, {'law': 'no_such_law'})
    else:
        set_law(m, {'law': 'table', 'table_s': [0.0, 0.5], 'table_mu': [0.1]})
    return m


# ---- recording ---------------------------------------------------------------------------------------------------

def non_finite(msg, prefix=''):
    """Names of the float fields of a message (recursively) that are NaN or infinite."""
    bad = []
    for name in getattr(msg, '__slots__', ()):
        value = getattr(msg, name)
        if isinstance(value, float):
            if not math.isfinite(value):
                bad.append(prefix + name)
        elif isinstance(value, (list, tuple)):
            bad += [f'{prefix}{name}[{i}]' for i, v in enumerate(value) if isinstance(v, float) and not math.isfinite(v)]
        elif hasattr(value, '__slots__'):
            bad += non_finite(value, prefix + name + '.')
    return bad


def fault_kind(text):
    """The kind named in a fault description ('t = 50.3 s: fallen: the figure axis ...' -> 'fallen')."""
    m = re.search(r's: (\w+): ', text)
    return m.group(1) if m else text


class StateRecorder:
    """Every TopState: receive time, seq, residual, achieved factor; non-finite fields; faults."""

    def __init__(self):
        self.lock = threading.Lock()
        self.recv, self.seq, self.residual, self.rtf = [], [], [], []
        self.non_finite_messages, self.non_finite_examples = 0, []
        self.fault_pending, self.faults, self.fault_examples, self.ignore_faults_until = False, {}, [], 0.0
        self.last = None

    def callback(self, msg):
        now = time.monotonic()
        bad = non_finite(msg)
        with self.lock:
            self.recv.append(now)
            self.seq.append(msg.header.seq)
            self.residual.append(msg.energy_balance_residual)
            self.rtf.append(msg.real_time_factor)
            self.last = msg
            if bad:
                self.non_finite_messages += 1
                if len(self.non_finite_examples) < 10:
                    self.non_finite_examples.append({'sim_time': msg.sim_time, 'fields': bad})
            if msg.regime == CONTACT_FAULT and not self.fault_pending and now >= self.ignore_faults_until:
                self.fault_pending = True
                kind = fault_kind(msg.fault)
                self.faults[kind] = self.faults.get(kind, 0) + 1
                if len(self.fault_examples) < 5:
                    self.fault_examples.append(msg.fault)


class DiagnosticsRecorder:
    """The node's /diagnostics status: the last values and the largest max-residual since a reset."""

    def __init__(self, node):
        self.name = node.strip('/') + ': simulation'
        self.lock = threading.Lock()
        self.last, self.max_residual = {}, 0.0

    def callback(self, msg):
        for status in msg.status:
            if status.name.endswith(self.name):
                values = {kv.key: kv.value for kv in status.values}
                with self.lock:
                    self.last = dict(values, level=int.from_bytes(status.level, 'little')
                                     if isinstance(status.level, bytes) else status.level, message=status.message)
                    r = float(values.get('max energy balance residual', 'nan'))
                    if math.isfinite(r):
                        self.max_residual = max(self.max_residual, r)


# ---- the soak ----------------------------------------------------------------------------------------------------

def call_with_timeout(fn, timeout):
    """(ok, seconds, error text) of fn() run in a thread: a node that stopped answering cannot hang the soak."""
    box = {}

    def target():
        try:
            fn()
            box['ok'] = True
        except Exception as e:   # a failed call is a finding, recorded with its text
            box['error'] = f'{type(e).__name__}: {e}'
    t0 = time.monotonic()
    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(timeout)
    return box.get('ok', False), time.monotonic() - t0, box.get('error', 'no answer within the timeout')


class Soak:
    """One soak run: the node, its publisher and service proxies, the recorders and the samples taken."""

    def __init__(self, args, rospy, msgs, pid, launch):
        self.args, self.rospy, self.msgs, self.pid, self.launch = args, rospy, msgs, pid, launch
        self.rng = random.Random(args.seed)
        self.randoms = RandomCommands(self.rng, msgs['TopCommand'])
        self.states, self.diag = StateRecorder(), DiagnosticsRecorder(args.node)
        rospy.Subscriber(f'{args.node}/top_state', msgs['TopState'], self.states.callback, queue_size=100000)
        rospy.Subscriber('/diagnostics', msgs['DiagnosticArray'], self.diag.callback, queue_size=100)
        with warnings.catch_warnings():   # queue_size=None: publish() writes the socket in this thread
            warnings.simplefilter('ignore', SyntaxWarning)
            self.pub = rospy.Publisher(f'{args.node}/command', msgs['TopCommand'], queue_size=None, tcp_nodelay=True)
        self.pause = rospy.ServiceProxy(f'{args.node}/pause', msgs['SetBool'])
        self.reset_srv = rospy.ServiceProxy(f'{args.node}/reset', msgs['Trigger'])
        self.sent, self.sent_invalid, self.kinds, self.above_critical = [], 0, {}, 0
        self.samples, self.alive, self.resets = [], [], {'fault': 0, 'random': 0, 'failed': 0}
        self.node_exited_at = None

    def send(self):
        """One command of the mode; returns the delay to the next."""
        a = self.args
        if a.mode == 'flood':
            invalid = self.rng.random() < a.invalid_fraction
            make = invalid_flood_command if invalid else valid_flood_command
            self.pub.publish(make(self.rng, self.msgs['TopCommand']))
            self.sent_invalid += invalid
            self.sent.append(time.monotonic())
            return 1.0 / a.flood_rate
        msg, kind, above = self.randoms.next()
        self.pub.publish(msg)
        self.sent.append(time.monotonic())
        self.kinds[kind] = self.kinds.get(kind, 0) + 1
        self.above_critical += above
        return self.rng.uniform(0.5, 1.5) / a.random_rate

    def sample(self, t0):
        """VmRSS, CPU ticks and load now."""
        self.samples.append({'t': time.monotonic() - t0, 'rss_kib': rss_kib(self.pid),
                             'cpu_ticks': cpu_ticks(self.pid), 'loadavg_1min': loadavg_1min()})

    def check_alive(self, t0):
        """~pause false: a no-op on a running node, answered by its main loop."""
        ok, seconds, error = call_with_timeout(lambda: self.pause(False), self.args.call_timeout)
        self.alive.append({'t': time.monotonic() - t0, 'ok': ok, 'seconds': seconds, **({} if ok else {'error': error})})

    def reset(self, why):
        """~reset; the random generator follows the node back to the scene's law."""
        ok, _, _ = call_with_timeout(lambda: self.reset_srv(), self.args.call_timeout)
        self.resets[why] += 1
        self.resets['failed'] += not ok
        self.randoms.reset()
        with self.states.lock:   # TopStates still in flight show the old fault: do not count it twice
            self.states.fault_pending = False
            self.states.ignore_faults_until = time.monotonic() + 0.5

    def start(self):
        """Forget what was received during the warm-up; the soak window starts now."""
        with self.states.lock:
            s = self.states
            s.recv, s.seq, s.residual, s.rtf = [], [], [], []
            s.non_finite_messages, s.non_finite_examples, s.faults, s.fault_examples = 0, [], {}, []
        self.ticks0 = cpu_ticks(self.pid)
        return time.monotonic()

    def run(self):
        """The soak window: commands, samples, liveness checks and fault resets until --duration is over."""
        a, t0 = self.args, self.start()
        end = t0 + a.duration
        next_cmd, next_sample, next_alive = t0, t0, t0 + a.alive_period
        next_reset = t0 + self.rng.uniform(0.5, 1.5) * a.reset_period
        while time.monotonic() < end:
            if self.launch.poll() is not None:
                self.node_exited_at = time.monotonic() - t0
                break
            now = time.monotonic()
            if now >= next_cmd:
                next_cmd = max(next_cmd + self.send(), now - 0.1)   # late: no burst of more than 100 ms
            if now >= next_sample:
                self.sample(t0)
                next_sample += a.sample_period
            if now >= next_alive:
                self.check_alive(t0)
                next_alive += a.alive_period
            if self.states.fault_pending:
                self.reset('fault')
            elif a.mode == 'random' and now >= next_reset:
                self.reset('random')
                next_reset = now + self.rng.uniform(0.5, 1.5) * a.reset_period
            time.sleep(max(0.0, min(next_cmd, next_sample, next_alive, end) - time.monotonic()))
        self.wall = time.monotonic() - t0
        self.ticks1 = cpu_ticks(self.pid) if self.node_exited_at is None else None
        if self.node_exited_at is None:
            self.sample(t0)
        self.t0 = t0


# ---- figures -----------------------------------------------------------------------------------------------------

def window_rates(times, t0, wall, window):
    """Events per second in each whole window of `window` seconds from t0."""
    counts = [0] * int(wall // window)
    for t in times:
        k = int((t - t0) // window)
        if 0 <= k < len(counts):
            counts[k] += 1
    return [c / window for c in counts]


def slope_per_minute(samples, key, after):
    """Least-squares slope of samples[key] against time [unit per minute], over samples at t >= after."""
    pts = [(s['t'] / 60.0, s[key]) for s in samples if s['t'] >= after]
    if len(pts) < 3:
        return None
    mt, my = statistics.fmean(p[0] for p in pts), statistics.fmean(p[1] for p in pts)
    sxx = sum((t - mt) ** 2 for t, _ in pts)
    return sum((t - mt) * (y - my) for t, y in pts) / sxx


def rate_figures(soak, rate):
    """Receive rate per window against the requested publish rate; seq holes."""
    s, a = soak.states, soak.args
    rates = window_rates(s.recv, soak.t0, soak.wall, a.window)
    lost = (s.seq[-1] - s.seq[0] + 1) - len(s.seq) if s.seq else None
    sends = window_rates(soak.sent, soak.t0, soak.wall, a.window)
    return {'publish_rate_hz': rate, 'received': len(s.recv), 'lost_seq_holes': lost,
            'rate_window_s': a.window, 'rate_median_hz': statistics.median(rates) if rates else None,
            'rate_min_hz': min(rates) if rates else None, 'rate_windows_hz': rates,
            'commands_sent': len(soak.sent), 'commands_invalid_sent': soak.sent_invalid,
            'send_rate_median_hz': statistics.median(sends) if sends else None,
            'send_rate_min_hz': min(sends) if sends else None}


def memory_cpu_figures(soak):
    """RSS first/last/max and its slope after the warm-up; CPU share; load average."""
    a, smp = soak.args, soak.samples
    rss = [x['rss_kib'] for x in smp]
    cpu = None if soak.ticks1 is None else 100.0 * (soak.ticks1 - soak.ticks0) / CLK_TCK / soak.wall
    loads = [x['loadavg_1min'] for x in smp]
    per_sample = [100.0 * (b['cpu_ticks'] - p['cpu_ticks']) / CLK_TCK / (b['t'] - p['t'])
                  for p, b in zip(smp, smp[1:]) if b['t'] > p['t']]
    return {'rss_first_kib': rss[0], 'rss_last_kib': rss[-1], 'rss_max_kib': max(rss),
            'rss_slope_kib_per_min': slope_per_minute(smp, 'rss_kib', a.rss_warmup), 'rss_warmup_s': a.rss_warmup,
            'cpu_percent': cpu, 'cpu_percent_max_sample': max(per_sample) if per_sample else None,
            'loadavg_1min_first': loads[0], 'loadavg_1min_mean': statistics.fmean(loads),
            'loadavg_1min_max': max(loads), 'samples': smp}


def health_figures(soak):
    """Non-finite fields, residual, achieved factor, faults, liveness and the node's last diagnostics."""
    s, d = soak.states, soak.diag
    ok = [c for c in soak.alive if c['ok']]
    return {'non_finite_messages': s.non_finite_messages, 'non_finite_examples': s.non_finite_examples,
            'residual_max': max(s.residual) if s.residual else None,
            'residual_p99': percentile(s.residual, 99) if s.residual else None,
            'diagnostics_max_residual_max': d.max_residual,
            'achieved_rtf_median': statistics.median(s.rtf) if s.rtf else None,
            'achieved_rtf_min': min(s.rtf) if s.rtf else None,
            'faults': s.faults, 'fault_examples': s.fault_examples, 'resets': soak.resets, 'command_kinds': soak.kinds,
            'inclinations_above_critical': soak.above_critical,
            'alive_checks': len(soak.alive), 'alive_ok': len(ok),
            'alive_max_s': max((c['seconds'] for c in ok), default=None),
            'alive_failures': [c for c in soak.alive if not c['ok']],
            'diagnostics_last': d.last, 'node_exited_at_s': soak.node_exited_at}


def one_line(r):
    """The result as one line of text."""
    f = lambda v, d=4: 'n/a' if v is None else f'{v:.{d}g}'   # noqa: E731
    return (f"node_soak {r['mode']} {f(r['wall_s'])} s: rate median {f(r['rate_median_hz'])} min "
            f"{f(r['rate_min_hz'])} Hz (lost {r['lost_seq_holes']}), sent {r['commands_sent']} "
            f"({r['commands_invalid_sent']} invalid, rejected {r['diagnostics_last'].get('rejected commands')}), "
            f"non-finite {r['non_finite_messages']}, RSS {r['rss_first_kib']}->{r['rss_last_kib']} KiB "
            f"(max {r['rss_max_kib']}, slope {f(r['rss_slope_kib_per_min'])} KiB/min), CPU {f(r['cpu_percent'], 3)} %, "
            f"residual max {f(r['residual_max'], 3)}, alive {r['alive_ok']}/{r['alive_checks']}, "
            f"faults {sum(r['faults'].values())}, load mean {f(r['loadavg_1min_mean'], 3)}")


# ---- main --------------------------------------------------------------------------------------------------------

def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--mode', choices=['flood', 'random'], required=True)
    ap.add_argument('--duration', type=float, default=600.0, help='soak window [s]')
    ap.add_argument('--warmup', type=float, default=3.0, help='wait after the node is up, before the window [s]')
    ap.add_argument('--flood-rate', type=float, default=1000.0, help='flood: commands per second')
    ap.add_argument('--invalid-fraction', type=float, default=0.1, help='flood: share of invalid commands')
    ap.add_argument('--random-rate', type=float, default=3.0, help='random: mean commands per second')
    ap.add_argument('--reset-period', type=float, default=60.0, help='random: mean seconds between ~reset calls')
    ap.add_argument('--window', type=float, default=10.0, help='receive-rate window [s]')
    ap.add_argument('--sample-period', type=float, default=5.0, help='RSS / CPU / load sampling [s]')
    ap.add_argument('--rss-warmup', type=float, default=60.0, help='RSS slope fitted from this time on [s]')
    ap.add_argument('--alive-period', type=float, default=30.0, help='liveness service call [s]')
    ap.add_argument('--call-timeout', type=float, default=5.0, help='a service call slower than this failed [s]')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--node', default='/top_sim', help='node name as launched by top_sim.launch')
    ap.add_argument('--port', type=int, help='private rosmaster port (default: a free one)')
    ap.add_argument('--json', help='write the result here')
    ap.add_argument('--log-dir')
    args = ap.parse_args()
    if args.duration < 2 * args.window or not 0.0 <= args.invalid_fraction <= 1.0:
        ap.error('--duration must cover two windows; --invalid-fraction must be in [0, 1]')
    return args


def ros_messages():
    """The message and service classes the soak uses (importable once the devel space is on sys.path)."""
    from diagnostic_msgs.msg import DiagnosticArray
    from std_srvs.srv import SetBool, Trigger
    from top_sim.msg import TopCommand, TopState
    return {'DiagnosticArray': DiagnosticArray, 'SetBool': SetBool, 'Trigger': Trigger,
            'TopCommand': TopCommand, 'TopState': TopState}


def soak_node(args, env):
    """Launches the node, runs the soak and stops the node; returns the Soak with its records."""
    import rospy
    rospy.init_node('top_sim_soak', disable_signals=True)
    log_path = os.path.join(args.log_dir, f'{args.mode}_roslaunch.log')
    launch, pid = launch_node(env, [], args.node, log_path)
    try:
        soak = Soak(args, rospy, ros_messages(), pid, launch)
        soak.publish_rate = float(rospy.get_param(f'{args.node}/publish_rate'))
        time.sleep(args.warmup)   # connections, the first second of achieved-factor averaging
        soak.run()
        time.sleep(2.0)   # no more commands: the next /diagnostics (1 Hz) counts every rejected one
    finally:
        stop_group(launch)
    soak.log_path, soak.log_bytes = log_path, os.path.getsize(log_path)
    with open(log_path, errors='replace') as f:
        text = f.read()
    soak.log_counts = {'warn_lines': text.count('[ WARN]'), 'falling_behind': text.count('top_sim_node: falling behind'),
                       'caught_up': text.count('caught up'), 'error_lines': text.count('[ERROR]')}
    return soak


def main():
    args = parse_args()
    args.log_dir = args.log_dir or f'/tmp/top_sim_node_soak.{os.getpid()}'
    os.makedirs(args.log_dir, exist_ok=True)
    env = ros_environment('node_soak')
    master = start_master(env, 'node_soak', args.port)
    try:
        soak = soak_node(args, env)
    finally:
        stop_group(master)
    result = {'mode': args.mode, 'command': 'bench/node_soak.py ' + ' '.join(sys.argv[1:]),
              'date': time.strftime('%Y-%m-%d %H:%M:%S'), 'wall_s': soak.wall, 'seed': args.seed,
              'roslaunch_log': soak.log_path, 'roslaunch_log_bytes': soak.log_bytes, 'log_counts': soak.log_counts}
    result.update(rate_figures(soak, soak.publish_rate))
    result.update(memory_cpu_figures(soak))
    result.update(health_figures(soak))
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(result, f, indent=1)
    print(one_line(result), flush=True)


if __name__ == '__main__':
    main()
