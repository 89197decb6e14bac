#!/usr/bin/env python3
"""What a recording of top_sim_node costs (issue 31): `rosbag record -a` of a running node, per topic.

Why: a user records bags; every byte the node publishes goes to disk and to rviz. The node is launched with
launch/top_sim.launch (no rviz) against a private rosmaster, runs --age seconds (the trail grows), then
`rosbag record -a` records --seconds seconds. Reported: the bag's size per second of recording, and per topic the
message count, rate and bytes per second (messages' serialised sizes, read back from the bag).

  bench/bag_bandwidth.py [--age 60] [--seconds 20] [--tops N] [--topics T1,T2] [--json FILE] [-- LAUNCH_ARGS...]

--tops N: N tops in the node, the launch-time top and N - 1 copies of its scene spawned in one ~spawn call (issue
49); --topics: record only these topics (`rosbag record T1 T2`) instead of -a, e.g. /top_sim/top_states, what a
user of many tops records.

e.g. `bench/bag_bandwidth.py --age 600 -- trail_seconds:=600` for ten minutes of trail. Writes a JSON result
(--json) and prints a table. Exit status 0 whatever the figures (a benchmark reports, it does not assert), non-zero
only if the harness failed. Needs a built workspace (scripts/build.sh).
"""
import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, 'scripts'))
from node_harness import launch_node, ros_environment, start_master, stop_group  # noqa: E402


def per_topic(bag_path):
    """{topic: (messages, bytes, first stamp, last stamp)} of the bag, bytes as serialised."""
    import rosbag
    out = {}
    with rosbag.Bag(bag_path) as bag:
        for topic, raw, t in bag.read_messages(raw=True):
            n, b, first, _ = out.get(topic, (0, 0, t.to_sec(), 0.0))
            out[topic] = (n + 1, b + len(raw[1]), first, t.to_sec())
    return out


def spawn_copies(n):
    """n copies of the node's scene, c0 ... c<n-1>, in one ~spawn call."""
    import rospy
    from top_sim.srv import Spawn, SpawnRequest
    rospy.init_node('bag_bandwidth', anonymous=True, disable_signals=True)
    rospy.wait_for_service('/top_sim/spawn', timeout=60)
    r = rospy.ServiceProxy('/top_sim/spawn', Spawn)(SpawnRequest(name='c', copies=n))
    if not r.success:
        sys.exit('bag_bandwidth: spawn refused: ' + r.message)
    print(r.message)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--age', type=float, default=60.0, help='seconds the node runs before recording')
    ap.add_argument('--seconds', type=float, default=20.0, help='seconds recorded')
    ap.add_argument('--tops', type=int, default=1, help='tops in the node (N - 1 spawned as copies)')
    ap.add_argument('--topics', default='', help='comma-separated topics to record (default: -a)')
    ap.add_argument('--json', help='write the result here')
    ap.add_argument('launch_args', nargs='*', help='extra name:=value arguments for top_sim.launch')
    args = ap.parse_args()

    env = ros_environment('bag_bandwidth')
    master = start_master(env, 'bag_bandwidth')
    work = tempfile.mkdtemp(prefix='bag_bandwidth_')
    bag = os.path.join(work, 'all.bag')
    launch = None
    try:
        launch, _ = launch_node(env, args.launch_args, '/top_sim', os.path.join(work, 'node.log'))
        if args.tops > 1:
            spawn_copies(args.tops - 1)
        time.sleep(args.age)
        what = args.topics.split(',') if args.topics else ['-a']
        rec = subprocess.Popen(['rosbag', 'record'] + what + ['-O', bag, '--duration=%g' % args.seconds],
                               env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               start_new_session=True)
        try:
            rec.wait(timeout=args.seconds + 60)
        except subprocess.TimeoutExpired:
            os.killpg(rec.pid, signal.SIGINT)
            rec.wait()
    finally:
        if launch is not None:
            stop_group(launch)
        stop_group(master)
    if not os.path.exists(bag):
        sys.exit('bag_bandwidth: rosbag wrote no bag (%s)' % work)
    topics = per_topic(bag)
    size = os.path.getsize(bag)
    result = {'age_s': args.age, 'recorded_s': args.seconds, 'launch_args': args.launch_args, 'tops': args.tops,
              'recorded_topics': args.topics or '-a',
              'bag_bytes': size, 'bag_bytes_per_s': size / args.seconds, 'topics': {}}
    print('age %g s, recorded %g s: bag %.1f KB/s' % (args.age, args.seconds, size / args.seconds / 1e3))
    print('| topic | messages | rate [Hz] | KB/s | bytes per message |')
    print('|---|---|---|---|---|')
    for topic, (n, b, first, last) in sorted(topics.items(), key=lambda kv: -kv[1][1]):
        rate = (n - 1) / (last - first) if n > 1 and last > first else float('nan')
        result['topics'][topic] = {'messages': n, 'bytes': b, 'rate_hz': rate, 'bytes_per_s': b / args.seconds}
        print('| %s | %d | %.1f | %.1f | %.0f |' % (topic, n, rate, b / args.seconds / 1e3, b / n))
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(result, f, indent=1)
    os.remove(bag)


if __name__ == '__main__':
    main()
