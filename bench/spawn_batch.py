#!/usr/bin/env python3
"""How long ~spawn takes to make many tops (docs/node_benchmark.md, "Many tops through one topic"; issue 49): one
top_sim_node (the launch-time top alone, against a private rosmaster) per case and round, then

  batch        one ~spawn call with copies = N (names s0 ... s<N-1>) under the node's ~per_top_topics rule
               (beyond 100 tops in the node: no own topics),
  batch_own    the same call asking for every top's own five topics (per_top_topics = 1),
  single_own   N ~spawn calls of one top each, each with its own topics (what a node before issue 49 offered),

timed from the call to its answer (the wall clock of this script), with the node's CPU over the same span, and
checked: ~list names every new top afterwards.

  bench/spawn_batch.py [--tops 1000] [--cases batch,batch_own,single_own] [--repeat 3] [--scene FILE]
                       [--json FILE]
"""
import argparse
import json
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import node_scale as ns  # noqa: E402

nh = ns.nh


def one_case(args, env, case, run):
    import rospy
    from top_sim.srv import ListTops, Spawn, SpawnRequest
    ns.set_parameters(env, 1, 20.0, False, None, args.scene)
    log = os.path.join(args.log_dir, 'spawn_%s_%d.log' % (case, run))
    proc, pid = ns.start_node(env, log, timeout=120)
    try:
        rospy.wait_for_service(ns.NODE + '/spawn', timeout=60)
        spawn = rospy.ServiceProxy(ns.NODE + '/spawn', Spawn, persistent=True)
        listing = rospy.ServiceProxy(ns.NODE + '/list', ListTops)
        c0, t0 = nh.cpu_ticks(pid), time.perf_counter()
        if case == 'single_own':
            for i in range(args.tops):
                r = spawn(SpawnRequest(name='s%d' % i, per_top_topics=SpawnRequest.PER_TOP_TOPICS_ON))
                if not r.success:
                    raise RuntimeError(r.message)
        else:
            asked = SpawnRequest.PER_TOP_TOPICS_ON if case == 'batch_own' else SpawnRequest.PER_TOP_TOPICS_DEFAULT
            r = spawn(SpawnRequest(name='s', copies=args.tops, per_top_topics=asked))
            if not r.success:
                raise RuntimeError(r.message)
        t1, c1 = time.perf_counter(), nh.cpu_ticks(pid)
        names = set(listing().names)
        missing = [i for i in range(args.tops) if 's%d' % i not in names]
        if missing:
            raise RuntimeError('%d tops missing from ~list after %s' % (len(missing), case))
        return {'case': case, 'run': run, 'tops': args.tops, 'seconds': round(t1 - t0, 3),
                'ms_per_top': round(1e3 * (t1 - t0) / args.tops, 3),
                'node_cpu_s': round((c1 - c0) / nh.CLK_TCK, 2), 'load': round(nh.loadavg_1min(), 2)}
    finally:
        nh.stop_group(proc)


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    p.add_argument('--tops', type=int, default=1000)
    p.add_argument('--cases', default='batch,batch_own,single_own')
    p.add_argument('--repeat', type=int, default=3)
    p.add_argument('--scene', default='', help='the node\'s scene, which the copies run (default: default.yaml)')
    p.add_argument('--json', default='')
    p.add_argument('--log-dir', default='/tmp/top_sim_spawn')
    args = p.parse_args()
    env, master = ns.start_session('spawn_batch', args.log_dir)
    results = []
    try:
        for run in range(args.repeat):
            for case in args.cases.split(','):
                r = one_case(args, env, case, run)
                print(json.dumps(r), flush=True)
                results.append(r)
    finally:
        nh.stop_group(master)
    print('| case | tops | runs | seconds (median; runs) | ms per top | node CPU [s] | load |')
    print('|---|---|---|---|---|---|---|')
    for case in args.cases.split(','):
        rs = [r for r in results if r['case'] == case]
        secs = [r['seconds'] for r in rs]
        print('| %s | %d | %d | %.2f (%s) | %.2f | %.1f | %.1f-%.1f |' % (
            case, args.tops, len(rs), statistics.median(secs), ', '.join('%.2f' % x for x in secs),
            statistics.median(r['ms_per_top'] for r in rs), statistics.median(r['node_cpu_s'] for r in rs),
            min(r['load'] for r in rs), max(r['load'] for r in rs)))
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'commit': ns.git_commit(), 'results': results}, f, indent=1)


if __name__ == '__main__':
    main()
