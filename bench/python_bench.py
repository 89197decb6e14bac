#!/usr/bin/env python3
"""Cost of the Python module against the C++ core (docs/performance.md, "Python").

Runs the same operations as bench/core_bench.cpp's whole_run/dopri5_10s, whole_run/dopri5_300s and
short_advance_and_snapshot, and prints medians of repeated runs (seconds of wall time, single thread).
    PYTHONPATH=build/python python3 bench/python_bench.py [--repeats N]
"""
import argparse
import os
import statistics
import time
from concurrent.futures import ThreadPoolExecutor

import top_sim


def median_seconds(fn, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=11)
    args = ap.parse_args()
    scene = top_sim.load_scene("default")

    for duration in (10.0, 300.0):
        s = median_seconds(lambda: top_sim.Simulator(scene).run(duration), args.repeats)
        print("whole_run default %5.0f s (Simulator + run): %8.3f ms" % (duration, 1e3 * s))

    sim = top_sim.Simulator(scene)
    sim.run(10.0)
    calls = 2000
    per_call = median_seconds(lambda: [sim.run(1e-4) for _ in range(calls)], args.repeats) / calls
    print("sim.run(1e-4) on a running top (advance + snapshot dict): %8.2f us per call" % (1e6 * per_call))
    per_snap = median_seconds(lambda: [sim.snapshot() for _ in range(calls)], args.repeats) / calls
    print("sim.snapshot() alone: %8.2f us per call" % (1e6 * per_snap))
    traj = median_seconds(lambda: top_sim.Simulator(scene).trajectory(10.0, 100.0), args.repeats)
    print("trajectory(10 s, 100 Hz) from a new Simulator: %8.3f ms" % (1e3 * traj))

    # The GIL is released while simulating: N threads on N cores should approach N times the throughput.
    threads = os.cpu_count() or 1
    batch = lambda _: top_sim.Simulator(scene).run(300.0)
    seq = median_seconds(lambda: [batch(i) for i in range(4 * threads)], args.repeats)
    with ThreadPoolExecutor(threads) as pool:
        par = median_seconds(lambda: list(pool.map(batch, range(4 * threads))), args.repeats)
    print("%d x 300 s: sequential %.1f ms, %d threads %.1f ms, speed-up %.2f"
          % (4 * threads, 1e3 * seq, threads, 1e3 * par, seq / par))


if __name__ == "__main__":
    main()
