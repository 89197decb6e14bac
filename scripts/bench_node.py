#!/usr/bin/env python3
"""Benchmarks top_sim_node streaming at a high publish rate (default 1 kHz, real-time factor 1).

Per run it launches launch/top_sim.launch (no rviz) against a private master, lets it settle, then over the
measurement window records every TopState it receives and reports:
  - cpu_percent: the node process's user+system CPU time (/proc/<pid>/stat) over the window, % of one core;
  - inter-arrival p50/p99 of receive times, and the arrival jitter: receive time minus the ideal schedule
    given by the header stamps (a straight line fitted through (stamp, receive time)), |residual| p50/p99;
  - command-to-effect latency: an inclination is published about once a second (alternating two values);
    the latency is the wall time until the first TopState whose alpha equals the new value;
  - achieved real-time factor: simulated time advanced / wall time, from the first and last TopState;
  - received / expected message count.
Numbers are medians over the runs. Targets are reported, never asserted (exit status 0 whatever they are).

  scripts/bench_node.py [--runs 3] [--duration 30] [--rate 1000] [--rtf 1] [--markdown docs/node_benchmark.md]

Needs a built workspace (scripts/build.sh): sources $TOP_SIM_WS/devel/setup.bash if top_sim is not found.
"""
import argparse
import json
import os
import platform
import statistics
import sys
import threading
import time
import warnings

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))   # node_harness.py, also from catkin's relay
from node_harness import (REPO, CLK_TCK, cpu_ticks, launch_node, percentile, ros_environment,  # noqa: E402
                          start_master, stop_group)


def arrival_jitter(recv, stamp):
    """|receive time - schedule| per message; the schedule is the header stamps shifted by the median offset,
    with a drift taken from the medians of the first and last thirds (robust to delayed bursts)."""
    d = [r - s for r, s in zip(recv, stamp)]
    n = len(d) // 3
    s1, s3 = statistics.median(stamp[:n]), statistics.median(stamp[-n:])
    d1, d3 = statistics.median(d[:n]), statistics.median(d[-n:])
    slope = (d3 - d1) / (s3 - s1) if s3 > s1 else 0.0
    residual = [di - (d1 + slope * (si - s1)) for di, si in zip(d, stamp)]
    m = statistics.median(residual)
    return [abs(x - m) for x in residual]


class Recorder:
    """TopState subscriber: receive time, header stamp, simulated time, alpha and reported factor of each message."""

    def __init__(self, rospy, TopState, topic):
        self.lock = threading.Lock()
        self.rows = []
        self.recording = False
        self.pending = None       # (target alpha, send time) of the inclination command in flight
        self.latencies = []
        self.between = []         # TopStates received after the command was sent, before the one showing it
        self.seen = 0
        self.sub = rospy.Subscriber(topic, TopState, self.callback, queue_size=10000, tcp_nodelay=True)

    def callback(self, msg):
        now = time.perf_counter()
        with self.lock:
            if not self.recording:
                return
            self.rows.append((now, msg.header.stamp.to_sec(), msg.sim_time, msg.alpha, msg.real_time_factor,
                              msg.header.seq))
            if self.pending is not None:
                if abs(msg.alpha - self.pending[0]) < 1e-12:
                    self.latencies.append((now - self.pending[1], msg.header.stamp.to_sec() - self.pending[1]))
                    self.between.append(self.seen)
                    self.pending = None
                else:
                    self.seen += 1


def one_run(args, env, rospy, Float64, recorder, index):
    log_path = os.path.join(args.log_dir, f'run{index}_roslaunch.log')
    node = args.node
    launch, pid = launch_node(env, [f'scene:={args.scene}', f'publish_rate:={args.rate}',
                                    f'real_time_factor:={args.rtf}'], node, log_path)
    try:
        time.sleep(args.warmup)   # connection set-up and the first second of achieved-factor averaging

        # queue_size=None: publish() writes the socket in this thread, so the send time stamped below is exact.
        with warnings.catch_warnings():
            warnings.simplefilter('ignore', SyntaxWarning)
            pub = rospy.Publisher(f'{node}/inclination', Float64, queue_size=None, tcp_nodelay=True)
        time.sleep(0.5)           # let the node connect to this publisher before the first command
        with recorder.lock:
            recorder.rows, recorder.latencies, recorder.between, recorder.pending = [], [], [], None
            recorder.recording = True
        ticks0, wall0 = cpu_ticks(pid), time.perf_counter()
        loadavg_before = open('/proc/loadavg').read().split()[0]

        alphas = (args.alpha, args.alpha + args.alpha_step)
        commands = 0
        next_command = wall0 + 1.0
        end = wall0 + args.duration
        while time.perf_counter() < end:
            now = time.perf_counter()
            if now >= next_command:
                target = alphas[(commands + 1) % 2]
                with recorder.lock:
                    recorder.pending, recorder.seen = (target, time.perf_counter()), 0
                pub.publish(Float64(target))
                commands += 1
                next_command = now + 1.0
            time.sleep(0.01)

        ticks1, wall1 = cpu_ticks(pid), time.perf_counter()
        with recorder.lock:
            recorder.recording = False
            rows, latencies, between = list(recorder.rows), list(recorder.latencies), list(recorder.between)
        pub.unregister()
    finally:
        stop_group(launch)

    if len(rows) < 10:
        raise RuntimeError(f'only {len(rows)} TopState messages received (see {log_path})')
    recv = [r[0] for r in rows]
    stamp = [r[1] for r in rows]
    sim = [r[2] for r in rows]
    period = 1.0 / args.rate
    gaps = [b - a for a, b in zip(recv, recv[1:])]
    stamp_steps = [b - a for a, b in zip(stamp, stamp[1:])]
    jitter = arrival_jitter(recv, stamp)
    # Scheduled latency: when the effect would have arrived with the run's median delivery offset, which
    # removes stalls of this (Python) subscriber from the figure.
    offset = statistics.median(r - st for r, st in zip(recv, stamp))
    sched = [stamp_minus_send + offset for _, stamp_minus_send in latencies]
    latencies = [received for received, _ in latencies]
    return {
        'run': index,
        'wall_s': wall1 - wall0,
        'cpu_percent': 100.0 * (ticks1 - ticks0) / CLK_TCK / (wall1 - wall0),
        'received': len(rows),
        'expected': round((wall1 - wall0) * args.rate),
        'interarrival_p50_ms': 1e3 * percentile(gaps, 50),
        'interarrival_p99_ms': 1e3 * percentile(gaps, 99),
        'interarrival_max_ms': 1e3 * max(gaps),
        'jitter_p50_ms': 1e3 * percentile(jitter, 50),
        'jitter_p99_ms': 1e3 * percentile(jitter, 99),
        'stamp_step_p50_ms': 1e3 * percentile(stamp_steps, 50),
        'stamp_step_p99_ms': 1e3 * percentile(stamp_steps, 99),
        'stamp_gaps': sum(1 for d in stamp_steps if d > 1.5 * period),
        # roscpp numbers each published message in header.seq: a hole is a message lost on the way.
        'lost': (rows[-1][5] - rows[0][5] + 1) - len(rows),
        'commands': commands,
        'latency_samples': len(latencies),
        'latency_p50_ms': 1e3 * percentile(latencies, 50) if latencies else None,
        'latency_max_ms': 1e3 * max(latencies) if latencies else None,
        'sched_latency_p50_ms': 1e3 * percentile(sched, 50) if sched else None,
        'sched_latency_max_ms': 1e3 * max(sched) if sched else None,
        'stale_states_p50': statistics.median(between) if between else None,
        'latency_within_period_percent': (100.0 * sum(l <= period for l in latencies) / len(latencies)
                                          if latencies else None),
        'achieved_rtf': (sim[-1] - sim[0]) / (recv[-1] - recv[0]),
        'reported_rtf_median': statistics.median(r[4] for r in rows),
        'loadavg_before': loadavg_before,
        'loadavg_after': open('/proc/loadavg').read().split()[0],
    }


SUMMARY_KEYS = ['cpu_percent', 'interarrival_p50_ms', 'interarrival_p99_ms', 'stamp_step_p50_ms',
                'stamp_step_p99_ms', 'stamp_gaps', 'lost', 'jitter_p50_ms', 'jitter_p99_ms',
                'latency_p50_ms', 'latency_max_ms', 'sched_latency_p50_ms', 'sched_latency_max_ms', 'stale_states_p50', 'latency_within_period_percent', 'achieved_rtf',
                'reported_rtf_median', 'received', 'expected']


def median_of(results, key):
    values = [r[key] for r in results if r[key] is not None]
    return statistics.median(values) if values else None


def fmt(v, digits=3):
    if v is None:
        return 'n/a'
    if isinstance(v, float):
        return f'{v:.{digits}g}' if abs(v) < 1e4 else f'{v:.0f}'
    return str(v)


def markdown(args, results, summary, command):
    period_ms = 1e3 / args.rate
    cpu = open('/proc/cpuinfo').read()
    model = next((l.split(':', 1)[1].strip() for l in cpu.splitlines() if l.startswith('model name')), 'unknown')
    verdict = lambda ok: 'met' if ok else 'NOT met'
    rtf_err = abs(summary['achieved_rtf'] / args.rtf - 1.0)
    lat = summary['latency_p50_ms']
    loads = ', '.join(f'{r["loadavg_before"]}/{r["loadavg_after"]}' for r in results)
    lines = [
        '# top_sim_node benchmark',
        '',
        'Regenerate with (after `scripts/build.sh`):',
        '',
        f'    {command}',
        '',
        f'Scene `{os.path.relpath(args.scene, REPO)}`, publish_rate {args.rate:g} Hz, real_time_factor {args.rtf:g}, '
        f'{args.runs} runs of {args.duration:g} s each after {args.warmup:g} s of warm-up, no rviz, one inclination '
        'command per second. '
        f'Machine: {model}, {os.cpu_count()} cores, {platform.platform()}; 1-minute load average before/after '
        f'each run: {loads}. The subscriber is rospy on the same machine: its own scheduling is part of the '
        'measured receive jitter and latency.',
        '',
        'Medians over the runs. Targets are reported, not asserted.',
        '',
        '| quantity | median | target |',
        '|---|---|---|',
        f'| node CPU, % of one core | {fmt(summary["cpu_percent"])} | < 10 %: {verdict(summary["cpu_percent"] < 10)} |',
        f'| header-stamp step p50 / p99 [ms] (publish side) | {fmt(summary["stamp_step_p50_ms"])} / '
        f'{fmt(summary["stamp_step_p99_ms"])} | period {period_ms:g} ms |',
        f'| stamp steps longer than 1.5 periods (per run) | {fmt(summary["stamp_gaps"])} | |',
        f'| receive inter-arrival p50 / p99 [ms] | {fmt(summary["interarrival_p50_ms"])} / '
        f'{fmt(summary["interarrival_p99_ms"])} | period {period_ms:g} ms |',
        f'| receive jitter against the stamp schedule, p50 / p99 [ms] | {fmt(summary["jitter_p50_ms"])} / '
        f'{fmt(summary["jitter_p99_ms"])} | |',
        f'| inclination command-to-effect latency, p50 / max [ms] | {fmt(lat)} / {fmt(summary["latency_max_ms"])} '
        f'| <= {period_ms:g} ms (one period): {verdict(lat is not None and lat <= period_ms)} for the median; '
        f'{fmt(summary["latency_within_period_percent"])} % of commands within |',
        f'| same, effect time taken from its header stamp + median delivery offset, p50 / max [ms] | '
        f'{fmt(summary["sched_latency_p50_ms"])} / {fmt(summary["sched_latency_max_ms"])} | <= {period_ms:g} ms |',
        f'| TopStates received after the command still showing the old alpha (median) | '
        f'{fmt(summary["stale_states_p50"])} | 0 or 1 |',
        f'| achieved real-time factor (simulated / wall time) | {fmt(summary["achieved_rtf"], 6)} | within 1 % of '
        f'{args.rtf:g}: {verdict(rtf_err <= 0.01)} |',
        f'| real-time factor reported in TopState (median) | {fmt(summary["reported_rtf_median"], 6)} | |',
        f'| TopState received / expected (wall time x rate) | {fmt(summary["received"])} / '
        f'{fmt(summary["expected"])} | |',
        f'| TopState published but not received (holes in header.seq) | {fmt(summary["lost"])} | 0 |',
        '',
        'Definitions. CPU: utime + stime of the node process (all threads) from `/proc/<pid>/stat` over the '
        'window, divided by the wall time. Stamp step: difference of consecutive header stamps (the node stamps '
        'each publish with its simulated time, paced against the wall clock, so at factor 1 this is the spacing '
        'of its timer ticks). Inter-arrival: difference of consecutive receive times in the subscriber. Receive '
        'jitter: |receive time - header stamp - trend| where the trend is the median offset with the drift '
        'between the first and last thirds removed. Latency: wall time from publishing on `inclination` to the '
        'first received TopState carrying the new alpha; it includes both transports and the wait for the next '
        'timer tick. Achieved factor: simulated time advanced / receive-time span, first to last message.',
        '',
    ]
    busy = max(float(r['loadavg_before']) for r in results)
    if busy > os.cpu_count():
        lines += [f'Note: the machine was shared and busy during these runs (1-minute load average up to {busy:g} on '
                  f'{os.cpu_count()} cores), so timer ticks were delayed or skipped (stamp steps longer than 1.5 '
                  'periods above) and latency and jitter include waiting for a CPU; rerun on an idle machine for '
                  'the node\'s own figures.', '']
    lines += [
        '## Runs',
        '',
        '| run | CPU % | stamp step p50/p99 ms | inter-arrival p50/p99 ms | jitter p50/p99 ms | '
        'latency p50/max ms (n) | achieved RTF | received/expected (lost) |',
        '|---|---|---|---|---|---|---|---|',
    ]
    for r in results:
        lines.append(
            f'| {r["run"]} | {fmt(r["cpu_percent"])} | {fmt(r["stamp_step_p50_ms"])} / {fmt(r["stamp_step_p99_ms"])} '
            f'| {fmt(r["interarrival_p50_ms"])} / {fmt(r["interarrival_p99_ms"])} | {fmt(r["jitter_p50_ms"])} / '
            f'{fmt(r["jitter_p99_ms"])} | {fmt(r["latency_p50_ms"])} / {fmt(r["latency_max_ms"])} '
            f'({r["latency_samples"]}) | {fmt(r["achieved_rtf"], 6)} | {r["received"]}/{r["expected"]} ({r["lost"]}) |')
    return '\n'.join(lines) + '\n'


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--runs', type=int, default=3)
    ap.add_argument('--duration', type=float, default=30.0, help='measurement window per run [s]')
    ap.add_argument('--warmup', type=float, default=3.0, help='wait after the node is up [s]')
    ap.add_argument('--rate', type=float, default=1000.0, help='publish_rate [Hz]')
    ap.add_argument('--rtf', type=float, default=1.0, help='real_time_factor (> 0)')
    ap.add_argument('--scene', default=os.path.join(REPO, 'config', 'scenes', 'default.yaml'))
    ap.add_argument('--node', default='/top_sim', help='node name as launched by top_sim.launch')
    ap.add_argument('--alpha', type=float, default=0.10, help='the two inclinations commanded alternately [rad]')
    ap.add_argument('--alpha-step', type=float, default=0.01)
    ap.add_argument('--markdown', help='write the report here (e.g. docs/node_benchmark.md)')
    ap.add_argument('--json', help='write every run and the medians as JSON here')
    ap.add_argument('--log-dir', default=None)
    args = ap.parse_args()
    for name, value, ok, allowed in [('--runs', args.runs, args.runs >= 1, '>= 1'),
                                     ('--duration', args.duration, args.duration >= 3, '>= 3 s'),
                                     ('--rate', args.rate, args.rate > 0, '> 0 Hz'),
                                     ('--rtf', args.rtf, args.rtf > 0, '> 0 (0 = unpaced is not benchmarked)')]:
        if not ok:
            ap.error(f'{name} = {value}: must be {allowed}')
    args.scene = os.path.abspath(args.scene)
    args.log_dir = args.log_dir or f'/tmp/top_sim_bench_node.{os.getpid()}'
    os.makedirs(args.log_dir, exist_ok=True)

    env = ros_environment('bench_node')
    master = start_master(env, 'bench_node')
    results = []
    try:
        import rospy
        from std_msgs.msg import Float64
        from top_sim.msg import TopState
        rospy.init_node('top_sim_bench', disable_signals=True)
        recorder = Recorder(rospy, TopState, f'{args.node}/top_state')
        for i in range(1, args.runs + 1):
            r = one_run(args, env, rospy, Float64, recorder, i)
            print(json.dumps(r), flush=True)
            results.append(r)
    finally:
        stop_group(master)

    summary = {k: median_of(results, k) for k in SUMMARY_KEYS}
    print(json.dumps({'median': summary}, indent=1))
    command = 'scripts/bench_node.py ' + ' '.join(sys.argv[1:])
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'command': command, 'runs': results, 'median': summary}, f, indent=1)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(markdown(args, results, summary, command))
        print(f'bench_node: wrote {args.markdown}')


if __name__ == '__main__':
    main()
