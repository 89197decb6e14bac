#!/usr/bin/env python3
"""A soak of mixed bodies in one node (issue 49, item 4): --tops tops drawn from every shipped scene
(config/scenes/*.yaml, in turn), then for --duration seconds, at random about --rate actions a second: spawn a top
on a random shipped scene (while fewer than --tops), kill a random spawned top, or command a random top through
~tops/command (an inclination in [0, 0.3] rad, a spin of 50 to 500 rad/s of either sign, pause, resume, or reset
it). Recorded: whether the node process stays up and ~list answers (every --alive-period), its VmRSS (every
--sample-period; the growth per 10 minutes after --rss-warmup, by a least-squares line), the rate of ~top_states,
per scene the share of top_states entries whose achieved real-time factor is below 0.95 (behind), and the ends:
a top whose TopState shows an end_state must keep it, at the same sim_time, in every later entry until it is
reset or killed ("latched"); each entry that breaks that is counted.

  bench/mixed_soak.py [--tops 100] [--duration 1800] [--rate 2] [--seed 1] [--json FILE]

Exit status 0 whatever the figures (a benchmark reports), non-zero only if the harness failed.
"""
import argparse
import glob
import json
import os
import random
import statistics
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import node_scale as ns  # noqa: E402

nh = ns.nh


class Watch(object):
    """top_states: arrival times; per top, its scene's behind count and the end it showed (to check latching)."""

    def __init__(self, rospy, msg):
        self.lock = threading.Lock()
        self.arrivals, self.scene_of, self.ends = [], {}, {}
        self.entries, self.behind = {}, {}
        self.latch_breaks, self.latch_examples, self.ends_seen = 0, [], 0
        self.grace = {}  # name -> monotonic time before which its entries may still be from before a reset
        self.sub = rospy.Subscriber(ns.NODE + '/top_states', msg, self.on_states, queue_size=5)

    def forget(self, name):
        """At a reset or a kill: the top may leave its end (entries of the next second may still show it)."""
        with self.lock:
            self.ends.pop(name, None)
            self.grace[name] = time.monotonic() + 1.0

    def on_states(self, m):
        with self.lock:
            self.arrivals.append(time.monotonic())
            for name, s in zip(m.names, m.states):
                scene = self.scene_of.get(name, 'default')
                self.entries[scene] = self.entries.get(scene, 0) + 1
                if s.real_time_factor < 0.95 and not s.paused and not s.end_state and s.regime != 4:
                    self.behind[scene] = self.behind.get(scene, 0) + 1
                self.check_end(name, s)

    def check_end(self, name, s):
        if time.monotonic() < self.grace.get(name, 0.0):
            return
        seen = self.ends.get(name)
        if seen is None:
            if s.end_state:
                self.ends[name] = (s.end_state, s.sim_time)
                self.ends_seen += 1
            return
        if (s.end_state, s.sim_time) != seen:
            self.latch_breaks += 1
            if len(self.latch_examples) < 5:
                self.latch_examples.append({'top': name, 'was': seen, 'now': (s.end_state, s.sim_time)})


def scenes():
    return sorted(glob.glob(os.path.join(nh.REPO, 'config', 'scenes', '*.yaml')))


def command(rng, TopCommand, name):
    m, kind = TopCommand(name=name), rng.choice(['inclination', 'spin', 'pause', 'resume', 'reset'])
    if kind == 'inclination':
        m.set_inclination, m.inclination = True, rng.uniform(0.0, 0.3)
    elif kind == 'spin':
        m.set_spin, m.spin = True, rng.uniform(50.0, 500.0) * rng.choice((-1.0, 1.0))
    elif kind in ('pause', 'resume'):
        m.set_paused, m.paused = True, kind == 'pause'
    else:
        m.reset = True
    return m, kind


class Soak(object):
    def __init__(self, args, rospy, pid, proc):
        from top_sim.msg import TopCommand, TopStateArray
        from top_sim.srv import Kill, ListTops, Spawn, SpawnRequest
        self.args, self.pid, self.proc, self.rng = args, pid, proc, random.Random(args.seed)
        self.TopCommand, self.SpawnRequest = TopCommand, SpawnRequest
        self.files = scenes()
        self.text = {f: open(f).read() for f in self.files}
        self.watch = Watch(rospy, TopStateArray)
        self.spawn = rospy.ServiceProxy(ns.NODE + '/spawn', Spawn)
        self.kill = rospy.ServiceProxy(ns.NODE + '/kill', Kill)
        self.list = rospy.ServiceProxy(ns.NODE + '/list', ListTops)
        self.pub = rospy.Publisher(ns.NODE + '/tops/command', TopCommand, queue_size=100)
        self.live, self.counter = [], 0
        self.actions, self.failures, self.samples, self.alive = {}, [], [], []

    def add(self, files):
        names = ['m%d' % (self.counter + i) for i in range(len(files))]
        self.counter += len(files)
        with self.watch.lock:
            for n, f in zip(names, files):
                self.watch.scene_of[n] = os.path.basename(f)[:-5]
        r = self.spawn(self.SpawnRequest(names=names, scenes=[self.text[f] for f in files]))
        if not r.success:
            self.failures.append('spawn: ' + r.message)
            return
        self.live += names

    def act(self):
        what = self.rng.choice(['spawn', 'kill', 'command', 'command', 'command'])
        if what == 'spawn' and len(self.live) + 1 < self.args.tops:
            self.add([self.rng.choice(self.files)])
        elif what == 'kill' and self.live:
            name = self.live.pop(self.rng.randrange(len(self.live)))
            r = self.kill(name=name)
            self.watch.forget(name)
            if not r.success:
                self.failures.append('kill: ' + r.message)
        elif self.live:
            name = self.rng.choice(self.live)
            m, what = command(self.rng, self.TopCommand, name)
            if m.reset:
                self.watch.forget(name)
            self.pub.publish(m)
        self.actions[what] = self.actions.get(what, 0) + 1

    def sample(self, t0):
        self.samples.append({'t': time.monotonic() - t0, 'rss_kib': nh.rss_kib(self.pid),
                             'cpu_ticks': nh.cpu_ticks(self.pid), 'load': nh.loadavg_1min(),
                             'tops': len(self.live) + 1})

    def check_alive(self, t0):
        t = time.monotonic()
        try:
            n = len(self.list().names)
            self.alive.append({'t': t - t0, 'ok': True, 'seconds': time.monotonic() - t, 'tops': n})
        except Exception as e:  # a node that stopped answering is a finding
            self.alive.append({'t': t - t0, 'ok': False, 'error': str(e)})

    def run(self):
        a = self.args
        self.add([self.files[i % len(self.files)] for i in range(a.tops - 1)])
        self.t0 = t0 = time.monotonic()
        # (when next, task returning the delay to its next run): actions at random, samples and checks in step
        tasks = [[t0, lambda: self.act() or self.rng.uniform(0.5, 1.5) / a.rate],
                 [t0, lambda: self.sample(t0) or a.sample_period],
                 [t0, lambda: self.check_alive(t0) or a.alive_period]]
        self.exited_at = None
        while time.monotonic() < t0 + a.duration and self.exited_at is None:
            for task in tasks:
                if time.monotonic() >= task[0]:
                    task[0] = time.monotonic() + task[1]()
            if self.proc.poll() is not None:
                self.exited_at = time.monotonic() - t0
            time.sleep(max(0.0, min([t[0] for t in tasks] + [t0 + a.duration]) - time.monotonic()))
        self.wall = time.monotonic() - t0


def figures(soak):
    a, w, smp = soak.args, soak.watch, soak.samples
    after = [s for s in smp if s['t'] >= a.rss_warmup]
    growth = None
    if len(after) >= 3:
        mt, my = statistics.fmean(s['t'] for s in after), statistics.fmean(s['rss_kib'] for s in after)
        slope = sum((s['t'] - mt) * (s['rss_kib'] - my) for s in after) / sum((s['t'] - mt) ** 2 for s in after)
        growth = 100.0 * slope * 600.0 / after[0]['rss_kib']  # % of the RSS at warm-up per 10 minutes
    window = [t for t in w.arrivals if t >= soak.t0]
    per_10s = [sum(1 for t in window if k * 10 <= t - soak.t0 < (k + 1) * 10) / 10.0 for k in range(int(soak.wall // 10))]
    cpu = [100.0 * (b['cpu_ticks'] - p['cpu_ticks']) / nh.CLK_TCK / (b['t'] - p['t']) for p, b in zip(smp, smp[1:])]
    behind = {scene: round(w.behind.get(scene, 0) / n, 4) for scene, n in sorted(w.entries.items())}
    return {'command': 'bench/mixed_soak.py ' + ' '.join(sys.argv[1:]), 'commit': ns.git_commit(),
            'wall_s': round(soak.wall, 1), 'node_exited_at_s': soak.exited_at,
            'alive_checks': len(soak.alive), 'alive_ok': sum(1 for c in soak.alive if c['ok']),
            'alive_failures': [c for c in soak.alive if not c['ok']],
            'rss_first_kib': smp[0]['rss_kib'], 'rss_last_kib': smp[-1]['rss_kib'], 'rss_max_kib': max(s['rss_kib'] for s in smp),
            'rss_growth_percent_per_10min_after_warmup': None if growth is None else round(growth, 3),
            'rss_warmup_s': a.rss_warmup, 'cpu_percent_median': statistics.median(cpu) if cpu else None,
            'top_states_hz_median': statistics.median(per_10s) if per_10s else None,
            'top_states_hz_min_10s': min(per_10s) if per_10s else None,
            'behind_share_by_scene': behind, 'ends_seen': w.ends_seen, 'latch_breaks': w.latch_breaks,
            'latch_examples': w.latch_examples, 'actions': soak.actions, 'failures': soak.failures[:20],
            'load_mean': statistics.fmean(s['load'] for s in smp), 'samples': smp}


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    p.add_argument('--tops', type=int, default=100)
    p.add_argument('--duration', type=float, default=1800.0)
    p.add_argument('--rate', type=float, default=2.0, help='actions per second (mean)')
    p.add_argument('--publish-rate', type=float, default=50.0)
    p.add_argument('--sample-period', type=float, default=10.0)
    p.add_argument('--alive-period', type=float, default=30.0)
    p.add_argument('--rss-warmup', type=float, default=300.0)
    p.add_argument('--seed', type=int, default=1)
    p.add_argument('--json', default='')
    p.add_argument('--log-dir', default='/tmp/top_sim_mixed_soak')
    args = p.parse_args()
    env, master = ns.start_session('mixed_soak', args.log_dir)
    try:
        import rospy
        ns.set_parameters(env, 1, args.publish_rate, True)
        proc, pid = ns.start_node(env, os.path.join(args.log_dir, 'node.log'), timeout=120)
        try:
            rospy.wait_for_service(ns.NODE + '/spawn', timeout=60)
            soak = Soak(args, rospy, pid, proc)
            soak.run()
        finally:
            nh.stop_group(proc)
    finally:
        nh.stop_group(master)
    result = figures(soak)
    if args.json:
        json.dump(result, open(args.json, 'w'), indent=1)
    print(json.dumps({k: v for k, v in result.items() if k != 'samples'}), flush=True)


if __name__ == '__main__':
    main()
