#!/usr/bin/env python3
"""Scale of top_sim_node with many tops (docs/node_benchmark.md): for each configuration, one node with N default
tops (the launch-time top plus N-1 from ~tops) against a private rosmaster; measured over a window after a warm-up:

  - the rate at which top_states (the array of every top) and /tf arrive at a subscriber (raw bytes, not
    deserialized, so the Python subscriber is not the bottleneck),
  - the node's CPU (utime + stime from /proc) as a share of one core, per top per wall second and per top per tick
    (the share over tops x the asked rate: issue 21's figure of merit; and over tops x the top_states received, the
    cost of a tick the node did make when it misses ticks),
  - the latency of a command to the LAST spawned top (its NAME/inclination until its NAME/top_state shows it),
  - from /diagnostics: tops falling behind, the launch-time top's achieved real-time factor,
  - with --probe tops (issue 49): the latency of a command to the LAST top through ~tops/command, seen in
    top_states (the array's raw bytes searched for the inclination sent, so the Python subscriber keeps up with
    10,000 tops); ready_s, from starting the node to the first top_states showing such a command (sent every 0.2 s
    from the start: the node answers ~tops/command); rate_s, from the start to the first wall second in which
    top_states arrived at 95 % of the asked rate or more,
  - start-up: until ~list names every top (startup_s); until the tops' own topics are all advertised (topics_s:
    they may follow in the background, docs/ros.md "Many tops: start-up"); the time from which no top is behind
    up to the start of the window (caught_up_s). --settle S waits, before the warm-up, until no top has been
    behind for S seconds in a row; caught_up_s looks up to the window's start (the command probe of the window takes
    its top out of the reduced model on purpose). --topics-last measures the window first and waits for the topics
    after it, then takes the CPU share again (cpu_share_after_topics).

  bench/node_scale.py [--configs 1:200,10:200,100:200,1000:50,1000:50:notf] [--seconds 20] [--repeat N]
                      [--scene FILE] [--settle S] [--topics-last [--topics-timeout S]] [--probe own|tops]
                      [--per-top-topics true|false]
                      [--node LABEL=BIN ...] [--json FILE]

A configuration is TOPS:RATE[:notf][:cpuN] (cpuN: the node pinned to CPU N by its ~cpu_affinity, all threads;
labelled "NODE cpuN"; the harness and its subscribers then keep off CPU N). Figures are noisy on a shared 2-core
machine: the load average is recorded, and --repeat N runs the configurations N times in turn (round-robin, so
load drifts hit all alike) and the table gives each one's medians. --node LABEL=BIN runs another build's
top_sim_node (with the libraries next to it, e.g. a copy of an earlier devel/lib); given more than once (LABEL=
alone: the package's node), the builds take turns within each round, so before and after are measured under the
same load.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import threading
import time
import warnings

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'scripts'))
import node_harness as nh  # noqa: E402

NODE = '/top_sim_scale'


class Arrivals(object):
    """Wall arrival times of a topic's messages, counted without deserializing them."""

    def __init__(self, rospy, topic):
        self.times = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, rospy.AnyMsg, self.on_msg, queue_size=100, tcp_nodelay=True)

    def on_msg(self, _):
        with self.lock:
            self.times.append(time.perf_counter())

    def rate(self, t0, t1):
        with self.lock:
            n = sum(1 for t in self.times if t0 <= t < t1)
        return n / (t1 - t0)


class Latency(object):
    """Command -> state latency of one top: the time from publishing an inclination to the first TopState with it."""

    def __init__(self, rospy, top_sim_msg, prefix):
        self.lock = threading.Lock()
        self.pending = None
        self.samples = []
        self.sub = rospy.Subscriber(prefix + 'top_state', top_sim_msg.TopState, self.on_state, queue_size=100,
                                    tcp_nodelay=True)
        from std_msgs.msg import Float64
        self.Float64 = Float64
        with warnings.catch_warnings():  # queue_size=None on purpose: publish() writes in this thread (exact send time)
            warnings.simplefilter('ignore', SyntaxWarning)
            self.pub = rospy.Publisher(prefix + 'inclination', Float64, queue_size=None, tcp_nodelay=True)

    def on_state(self, m):
        with self.lock:
            if self.pending and abs(m.alpha - self.pending[0]) < 1e-12:
                self.samples.append(time.perf_counter() - self.pending[1])
                self.pending = None

    def send(self, alpha):
        with self.lock:
            self.pending = (alpha, time.perf_counter())
        self.pub.publish(self.Float64(alpha))


class ArrayLatency(object):
    """Command -> state latency of one top through ~tops/command, seen in top_states: each inclination sent is a
    value no top has (0.11 or 0.12 rad plus k nanoradians), so its 8 bytes in a raw top_states message mean the
    command acted; the message is not deserialized (10,000 tops are 4 MB a message)."""

    def __init__(self, rospy, top_sim_msg, node, top):
        import struct
        self.pack = struct.Struct('<d').pack
        self.lock = threading.Lock()
        self.pending = None
        self.samples, self.hits = [], []
        self.top, self.k = top, 0
        self.sub = rospy.Subscriber(node + '/top_states', rospy.AnyMsg, self.on_states, queue_size=100,
                                    tcp_nodelay=True)
        self.TopCommand = top_sim_msg.TopCommand
        with warnings.catch_warnings():  # queue_size=None on purpose: publish() writes in this thread (exact send time)
            warnings.simplefilter('ignore', SyntaxWarning)
            self.pub = rospy.Publisher(node + '/tops/command', top_sim_msg.TopCommand, queue_size=None,
                                       tcp_nodelay=True)

    def on_states(self, m):
        now = time.perf_counter()
        with self.lock:
            if self.pending and self.pending[0] in m._buff:
                self.samples.append(now - self.pending[1])
                self.hits.append(now)
                self.pending = None

    def send(self):
        self.k += 1
        alpha = 0.1 + 0.01 * (self.k % 2 + 1) + 1e-9 * self.k
        with self.lock:
            self.pending = (self.pack(alpha), time.perf_counter())
        self.pub.publish(self.TopCommand(name=self.top, set_inclination=True, inclination=alpha))

    def first_hit(self):
        with self.lock:
            return self.hits[0] if self.hits else None


def first_full_second(times, t_start, rate):
    """The start of the first wall second (sliding, from each arrival) with at least 95 % of `rate` arrivals."""
    need = max(1, int(0.95 * rate))
    for i in range(len(times) - need + 1):
        if times[i + need - 1] - times[i] <= 1.0:
            return times[i] - t_start
    return None


def wait_ready(probe, timeout):
    """Sends a command every 0.2 s until top_states shows one; the wall time it did, or None."""
    deadline = time.perf_counter() + timeout
    while time.perf_counter() < deadline:
        probe.send()
        time.sleep(0.2)
        if probe.first_hit() is not None:
            return probe.first_hit()
    return None


class Diagnostics(object):
    """The node's last diagnostics, and the series (arrival time, tops behind, tops whose topics are pending)."""

    def __init__(self, rospy):
        from diagnostic_msgs.msg import DiagnosticArray
        self.values = {}
        self.series = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=10)

    def on_diag(self, m):
        for st in m.status:
            if 'simulation' in st.name:
                values = {kv.key: kv.value for kv in st.values}
                with self.lock:
                    self.values = values
                    # a build without background topics has no pending count: all its topics exist at start
                    self.series.append((time.perf_counter(), int(values.get('tops falling behind', 0)),
                                        int(values.get(PENDING, 0))))

    def wait(self, pred, timeout):
        """The arrival time of the first message (from now) whose (behind, pending) satisfies pred, or None."""
        start, deadline = len(self.series), time.perf_counter() + timeout
        while time.perf_counter() < deadline:
            with self.lock:
                for t, behind, pending in self.series[start:]:
                    if pred(behind, pending):
                        return t
            time.sleep(0.2)
        return None

    def settled(self, seconds, timeout):
        """Waits until no top has been behind for `seconds` (consecutive messages); False after `timeout`."""
        deadline = time.perf_counter() + timeout
        while time.perf_counter() < deadline:
            with self.lock:
                last_behind = max([t for t, b, _ in self.series if b > 0], default=None)
                recent = [t for t, b, _ in self.series if last_behind is None or t > last_behind]
            if recent and recent[-1] - recent[0] >= seconds:
                return True
            time.sleep(0.5)
        return False

    def caught_up(self, t_start, t_end):
        """The first message after the last one with a top behind, up to t_end (the time no top is behind from)."""
        with self.lock:
            seen = [(t, b) for t, b, _ in self.series if t <= t_end]
        last = max([t for t, b in seen if b > 0], default=None)
        after = [t for t, b in seen if last is None or t > last]
        return after[0] - t_start if after else None


PENDING = 'tops whose topics are not yet advertised'


def set_parameters(env, tops, rate, tf, cpu=None, scene='', per_top_topics=None):
    import rospy
    scene = os.path.abspath(scene) if scene else os.path.join(nh.REPO, 'config', 'scenes', 'default.yaml')
    params = {
        'scene_file': scene, 'config_dir': os.path.join(nh.REPO, 'config'), 'publish_rate': float(rate),
        'publish_tf': tf, 'tops': {'t%04d' % i: '' for i in range(1, tops)},
        'cpu_affinity': -1 if cpu is None else cpu}
    if per_top_topics is not None:  # unset: the node's rule (builds before issue 49 do not know the key)
        params['per_top_topics'] = per_top_topics
    rospy.set_param(NODE, params)


def node_command(env, node):
    """The node's binary and environment: the package's, or `node` with the libraries of its directory first."""
    if not node:
        return subprocess.run(['bash', '-c', 'echo $(catkin_find top_sim top_sim_node | head -1)'], env=env,
                              capture_output=True, universal_newlines=True).stdout.strip(), env
    node = os.path.abspath(node)
    env = dict(env, LD_LIBRARY_PATH=os.path.dirname(node) + ':' + env.get('LD_LIBRARY_PATH', ''))
    return node, env


def start_node(env, log_path, timeout, node=''):
    node_bin, env = node_command(env, node)
    log = open(log_path, 'w')
    proc = subprocess.Popen([node_bin, '__name:=' + NODE.lstrip('/')], env=env, stdout=log, stderr=subprocess.STDOUT,
                            start_new_session=True)
    log.close()
    deadline = time.time() + timeout
    pid = None
    while pid is None and time.time() < deadline and proc.poll() is None:
        time.sleep(0.5)
        try:
            pid = nh.node_pid(env['ROS_MASTER_URI'], NODE)
        except OSError:
            pid = None
    if pid is None:
        nh.stop_group(proc)
        raise RuntimeError('%s did not come up (see %s)' % (NODE, log_path))
    return proc, pid


def wait_for_all_tops(rospy, tops, timeout):
    from top_sim.srv import ListTops
    rospy.wait_for_service(NODE + '/list', timeout=timeout)
    lst = rospy.ServiceProxy(NODE + '/list', ListTops)
    deadline = time.time() + timeout
    while len(lst().names) < tops:
        if time.time() > deadline:
            raise RuntimeError('only %d of %d tops after %g s' % (len(lst().names), tops, timeout))
        time.sleep(0.5)


ALL_CPUS = os.sched_getaffinity(0)


def keep_off_cpu(cpu):
    """Every thread of this harness (its subscribers) off `cpu`, or back on all CPUs with None: the node pinned
    there then has the CPU to itself, as a deployment that pins it would give it."""
    want = ALL_CPUS - {cpu} if cpu is not None and len(ALL_CPUS - {cpu}) > 0 else ALL_CPUS
    for tid in os.listdir('/proc/self/task'):
        try:
            os.sched_setaffinity(int(tid), want)
        except OSError:  # a thread that has just ended
            pass


def measure(args, env, tops, rate, tf, index, node=('package', ''), pin_cpu=None):
    import rospy
    import top_sim.msg as top_sim_msg
    keep_off_cpu(pin_cpu)
    log_path = os.path.join(args.log_dir, 'scale_%s_%d_%g_%s.log' % (node[0].replace('/', '_'), tops, rate, 'tf' if tf else 'notf'))
    set_parameters(env, tops, rate, tf, pin_cpu, args.scene, args.per_top_topics)
    last_name = 't%04d' % (tops - 1) if tops > 1 else 'top'
    early = {}  # --probe tops: subscribed before the node starts, so its first messages are seen
    if args.probe == 'tops':
        early['states'] = Arrivals(rospy, NODE + '/top_states')
        early['probe'] = ArrayLatency(rospy, top_sim_msg, NODE, last_name)
    t_start = time.perf_counter()
    proc, pid = start_node(env, log_path, timeout=600, node=node[1])
    subs = [x.sub for x in early.values()] + ([early['probe'].pub] if early else [])
    ready = None
    try:
        if early:
            t_ready = wait_ready(early['probe'], timeout=600)
            ready = None if t_ready is None else t_ready - t_start
        wait_for_all_tops(rospy, tops, timeout=600)
        startup = time.perf_counter() - t_start
        diag = Diagnostics(rospy)
        # The tops' own topics may still be advertised in the background (docs/ros.md): the window waits for them
        # and for every top to keep real time (args.settle s in a row), then measures.
        topics = None
        if not args.topics_last:
            t_topics = diag.wait(lambda behind, pending: pending == 0, timeout=args.settle_timeout)
            topics = None if t_topics is None else t_topics - t_start
        settled = diag.settled(args.settle, timeout=args.settle_timeout)
        states = early.get('states') or Arrivals(rospy, NODE + '/top_states')
        tfs = Arrivals(rospy, '/tf')
        if early:
            latency = early['probe']
            subs += [tfs.sub, diag.sub]
        else:
            latency = Latency(rospy, top_sim_msg, NODE + '/' + ('t%04d/' % (tops - 1) if tops > 1 else ''))
            subs = [states.sub, tfs.sub, latency.sub, latency.pub, diag.sub]  # unregistered before the next node
        time.sleep(args.warmup)
        latency.samples = []  # the window's own
        t0, c0 = time.perf_counter(), nh.cpu_ticks(pid)
        load0 = nh.loadavg_1min()
        k = 0
        while time.perf_counter() < t0 + args.seconds:
            if early:
                latency.send()
            else:
                latency.send(0.1 + 0.01 * (k % 2 + 1))  # alternates 0.11 / 0.12 rad: each one a change
            k += 1
            time.sleep(0.5)
        t1, c1 = time.perf_counter(), nh.cpu_ticks(pid)
        caught_up = diag.caught_up(t_start, t0)
        cpu = (c1 - c0) / nh.CLK_TCK / (t1 - t0)
        lat = latency.samples
        states_hz = states.rate(t0, t1)
        d = diag.values
        after = {}
        if args.topics_last:  # the tops' own topics may still be on their way: wait, then the CPU share again
            after['topics_pending_in_window'] = number(d.get(PENDING))
            t_topics = diag.wait(lambda behind, pending: pending == 0, timeout=args.topics_timeout)
            topics = None if t_topics is None else t_topics - t_start
            if t_topics is not None:
                time.sleep(args.warmup)
                t2, c2 = time.perf_counter(), nh.cpu_ticks(pid)
                time.sleep(args.seconds)
                t3, c3 = time.perf_counter(), nh.cpu_ticks(pid)
                after['cpu_share_after_topics'] = round((c3 - c2) / nh.CLK_TCK / (t3 - t2), 4)
                after['top_states_hz_after_topics'] = round(states.rate(t2, t3), 2)
                after['tops_behind_after_topics'] = number(diag.values.get('tops falling behind'))
        return {
            'tops': tops, 'rate_hz': rate, 'tf': tf, 'node': node[0] + ('' if pin_cpu is None else ' cpu%d' % pin_cpu),
            'run': index,
            'startup_s': round(startup, 2),
            'probe': args.probe,
            'ready_s': None if ready is None else round(ready, 2),
            'rate_s': None if not early else rounded(first_full_second(list(states.times), t_start, rate)),
            'topics_s': None if topics is None else round(topics, 2),
            # up to the window: its command probe takes the last top out of the reduced model on purpose
            'caught_up_s': None if caught_up is None else round(caught_up, 2),
            'settled': settled,
            'top_states_hz': round(states.rate(t0, t1), 2), 'tf_msgs_hz': round(tfs.rate(t0, t1), 2),
            'cpu_share': round(cpu, 4), 'cpu_us_per_top_per_s': round(1e6 * cpu / tops, 1),
            'cpu_us_per_top_per_tick': round(1e6 * cpu / (tops * rate), 2),
            'cpu_us_per_top_per_tick_received': round(1e6 * cpu / (tops * states_hz), 2) if states_hz > 0 else None,
            'latency_samples': len(lat),
            'latency_p50_ms': round(1e3 * statistics.median(lat), 2) if lat else None,
            'latency_max_ms': round(1e3 * max(lat), 2) if lat else None,
            'tops_behind': d.get('tops falling behind'), 'achieved_rtf': d.get('achieved real-time factor'),
            'publish_rate_achieved': d.get('publish rate achieved [Hz]'),
            'load_before': round(load0, 2), 'load_after': round(nh.loadavg_1min(), 2),
            **after,
        }
    finally:
        for sub in subs:
            sub.unregister()
        nh.stop_group(proc)


def rounded(v, digits=2):
    return None if v is None else round(v, digits)


def parse_config(text):
    """TOPS:RATE[:notf][:cpuN] -> (tops, rate, tf, cpu or None)."""
    parts = text.split(':')
    tf, cpu = True, None
    for option in parts[2:]:
        if option == 'notf':
            tf = False
        elif option.startswith('cpu') and option[3:].isdigit():
            cpu = int(option[3:])
        else:
            sys.exit("node_scale.py: configuration '%s': option '%s' is not allowed (notf or cpuN, N a CPU)"
                     % (text, option))
    return int(parts[0]), float(parts[1]), tf, cpu


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    p.add_argument('--configs', default='1:200,10:200,100:200,1000:50,1000:50:notf')
    p.add_argument('--seconds', type=float, default=20.0)
    p.add_argument('--scene', default='', help='scene file of every top (default: config/scenes/default.yaml)')
    p.add_argument('--warmup', type=float, default=5.0)
    p.add_argument('--settle', type=float, default=0.0,
                   help='before the window, wait until no top has been behind for this many seconds (diagnostics)')
    p.add_argument('--settle-timeout', type=float, default=900.0)
    p.add_argument('--topics-last', action='store_true',
                   help='measure the window once no top is behind, then wait for the tops\' own topics '
                        '(--topics-timeout) and measure the CPU share again')
    p.add_argument('--topics-timeout', type=float, default=900.0)
    p.add_argument('--probe', choices=('own', 'tops'), default='own',
                   help="the command probe: the last top's own NAME/inclination and NAME/top_state (own), or "
                        "~tops/command and top_states (tops: also ready_s and rate_s; builds since issue 49)")
    p.add_argument('--per-top-topics', choices=('true', 'false'), default=None,
                   help="the node's ~per_top_topics (unset: the node's rule; builds since issue 49)")
    p.add_argument('--repeat', type=int, default=1)
    p.add_argument('--node', action='append', default=[],
                   help="LABEL=BIN: a top_sim_node build to run (BIN empty: the package's); repeatable")
    p.add_argument('--json', default='')
    p.add_argument('--log-dir', default='/tmp/top_sim_scale')
    return p.parse_args()


def start_session(tool, log_dir):
    """The log directory, a private rosmaster and this process's rospy node: (environment, master process); stop
    the master with nh.stop_group."""
    os.makedirs(log_dir, exist_ok=True)
    env = nh.ros_environment(tool)
    master = nh.start_master(env, tool)
    try:
        import rospy
        rospy.init_node('top_sim_%s_bench' % tool, anonymous=True, disable_signals=True)
    except BaseException:
        nh.stop_group(master)
        raise
    return env, master


def main():
    args = parse_args()
    if args.per_top_topics is not None:
        args.per_top_topics = args.per_top_topics == 'true'
    env, master = start_session('node_scale', args.log_dir)
    results = []
    try:
        nodes = [tuple(n.split('=', 1)) if '=' in n else (n, n) for n in args.node] or [('package', '')]
        for run in range(args.repeat):
            for c in args.configs.split(','):
                tops, rate, tf, cpu = parse_config(c)
                for node in nodes:
                    r = measure(args, env, tops, rate, tf, run, node, cpu)
                    print(json.dumps(r), flush=True)
                    results.append(r)
    finally:
        nh.stop_group(master)
    table = medians(results)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'seconds': args.seconds, 'warmup': args.warmup, 'repeat': args.repeat,
                       'commit': git_commit(), 'medians': table, 'results': results}, f, indent=1)
    print(markdown(table))


def git_commit():
    r = subprocess.run(['git', '-C', nh.REPO, 'rev-parse', '--short', 'HEAD'], capture_output=True,
                       universal_newlines=True)
    return r.stdout.strip()


def number(v):
    """A figure as a float (diagnostics give strings); None when there is none."""
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


def medians(results):
    """Per configuration (in the order first run), the median of each figure over its runs; behind as min-max."""
    groups = {}
    for r in results:
        groups.setdefault((r.get('node', 'package'), r['tops'], r['rate_hz'], r['tf']), []).append(r)
    table = []
    for (node, tops, rate, tf), runs in groups.items():
        m = {'node': node, 'tops': tops, 'rate_hz': rate, 'tf': tf, 'runs': len(runs)}
        for key, value in runs[0].items():
            if key in m or key in ('node', 'run') or isinstance(value, bool):
                continue
            values = [number(r[key]) for r in runs if number(r[key]) is not None]
            m[key] = statistics.median(values) if values else None
        behind = [number(r['tops_behind']) for r in runs if number(r['tops_behind']) is not None]
        m['tops_behind_range'] = '%d-%d' % (min(behind), max(behind)) if behind else None
        table.append(m)
    return table


def markdown(results):
    """The table of docs/node_benchmark.md (medians over the runs; tops behind: the runs' range)."""
    rows = ['| node | tops | rate asked [Hz] | tf | top_states received [Hz] | node CPU [share of a core] | CPU per top '
            '[us per s] | CPU per top per tick [us] (per tick made) | command latency p50 / max [ms] | tops behind | start-up [s] | topics [s] | none behind from [s] | load '
            '| runs | ~tops/command answered from [s] | top_states at the rate from [s] |',
            '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|']
    for r in results:
        ms = ['-' if r[k] is None else '%.1f' % r[k] for k in ('latency_p50_ms', 'latency_max_ms')]
        opt = ['-' if r.get(k) is None else '%.1f' % r[k]
               for k in ('topics_s', 'caught_up_s', 'ready_s', 'rate_s')]
        rows.append('| %s | %d | %g | %s | %.1f | %.3f | %.0f | %.2f (%.2f) | %s / %s | %s | %.1f | %s | %s | %.1f-%.1f | %d | %s | %s |' % (
            r['node'], r['tops'], r['rate_hz'], 'on' if r['tf'] else 'off', r['top_states_hz'], r['cpu_share'],
            r['cpu_us_per_top_per_s'], r['cpu_us_per_top_per_tick'], r['cpu_us_per_top_per_tick_received'] or 0.0, ms[0], ms[1], r['tops_behind_range'], r['startup_s'], opt[0], opt[1], r['load_before'], r['load_after'], r['runs'],
            opt[2], opt[3]))
    return '\n'.join(rows)


if __name__ == '__main__':
    main()
