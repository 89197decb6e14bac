#!/usr/bin/python3
"""Timings of python3 -m top_sim.sweep (docs/studies.md): scaling over 1 and 2 workers against top_sim_sweep's
threads, the cluster's cost per task, the cost per point by kind, and paper Fig. 4's whole grid run through a
Dask scheduler with two workers on this machine (CSV files and a figure).

    PYTHONPATH=build/python python3 bench/sweep_dask.py --sweep-binary build/bin/top_sim_sweep \
        [--fig4-data docs/data/dask_fig4] [--fig4-png docs/img/fig4_dask.png] [--skip PART ...]

PART: scaling, overhead, fig4. Prints the numbers (wall seconds, CPU seconds summed over the points as each
point's thread CPU time, the load average of the machine) as markdown tables.
"""
import argparse
import csv
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The Fig. 4 grid of scripts/make_figures.sh: (top, plane, start, alpha grid).
FIG4 = [(t, p, "tilted", "0.01:0.30:30") for t, p in
        (("aluminium", "pmma"), ("steel", "pmma"), ("steel", "steel"), ("wood", "steel"))] + \
       [(t, p, "launched", "0.14:0.30:17") for t, p in (("aluminium", "pmma"), ("steel", "steel"))]


def load():
    return os.getloadavg()[0]


def timed(cmd):
    """Wall seconds of `cmd` and its stderr; raises when it fails."""
    t0 = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - t0
    if r.returncode not in (0, 3):
        raise SystemExit("failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stderr))
    return wall, r.stderr


def cpu_of(csv_path):
    with open(csv_path) as f:
        return sum(float(row["cpu_seconds"]) for row in csv.DictReader(f))


def python_sweep(args):
    return [sys.executable, "-m", "top_sim.sweep", "--no-progress"] + args


def scaling(binary, tmp, repeats):
    """One grid (aluminium on PMMA, 30 inclinations, tilted) on 1 and 2 workers: top_sim_sweep's threads, a new
    local cluster (its start included) and a running scheduler with that many workers (start excluded). Runs
    interleaved, `repeats` times; the smallest and the median wall time."""
    grid = ["--alpha", "0.01:0.30:30"]
    out = os.path.join(tmp, "scaling.csv")
    walls, cpus, loads = {}, {}, []
    for r in range(repeats):
        for workers in (1, 2):
            address, procs = start_cluster(tmp, workers, port=8790 + workers)
            try:
                runs = (("top_sim_sweep --threads N", [binary, "--threads", str(workers)]),
                        ("top_sim.sweep, local cluster (start included)", python_sweep(["--threads", str(workers)])),
                        ("top_sim.sweep --scheduler, N workers running", python_sweep(["--scheduler", address])))
                for name, cmd in runs:
                    wall, _ = timed(cmd + grid + ["--out", out])
                    walls.setdefault((name, workers), []).append(wall)
                    cpus.setdefault((name, workers), []).append(cpu_of(out))
                    loads.append(load())
            finally:
                stop(procs)
    print("\n| tool | workers | wall [s]: smallest / median of %d | CPU of the points [s]: median |\n|---|---|---|---|"
          % repeats)
    for (name, workers), w in sorted(walls.items(), key=lambda kv: (kv[0][0], kv[0][1])):
        print("| %s | %d | %.2f / %.2f | %.2f |" % (name, workers, min(w), statistics.median(w),
                                                    statistics.median(cpus[(name, workers)])))
    print("load average during these runs: %.1f to %.1f" % (min(loads), max(loads)))


def stop(procs):
    for p in reversed(procs):
        p.send_signal(signal.SIGINT)
    for p in procs:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()


def overhead(tmp):
    """The cluster's cost per task: 1 and 200 points of a few milliseconds each on a new local cluster; the
    difference over 199 points is the cost of one more task (scheduling, pickling, the row written)."""
    out = os.path.join(tmp, "overhead.csv")
    print("\n| run (local cluster, 2 workers) | wall [s] | CPU of the points [s] | load |\n|---|---|---|---|")
    walls = []
    for n in (1, 200):
        wall, _ = timed(python_sweep(["--alpha", "0.01:0.30:%d" % n, "--max-duration", "0.05", "--threads", "2",
                                      "--out", out]))
        walls.append(wall)
        print("| start + %d point(s) of 0.05 simulated s | %.2f | %.3f | %.1f |" % (n, wall, cpu_of(out), load()))
    print("one more task: %.1f ms of wall time" % (1000 * (walls[1] - walls[0]) / 199))


def start_cluster(tmp, workers=2, port=8799):
    """A dask-scheduler and `workers` dask-workers on localhost; their processes."""
    address = "tcp://127.0.0.1:%d" % port
    procs = [subprocess.Popen(["dask-scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              stdout=subprocess.DEVNULL, stderr=open(os.path.join(tmp, "scheduler.log"), "w"))]
    for k in range(workers):
        procs.append(subprocess.Popen(["dask-worker", "--nthreads", "1", "--no-dashboard", address],
                                      stdout=subprocess.DEVNULL,
                                      stderr=open(os.path.join(tmp, "worker%d.log" % k), "w")))
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if open(os.path.join(tmp, "scheduler.log")).read().count("Register worker") >= workers:
            return address, procs
        time.sleep(0.2)
    raise SystemExit("the workers did not register within 60 s")


def fig4(tmp, binary, data_dir, png):
    """Paper Fig. 4's grid through one scheduler with two workers; each file compared with top_sim_sweep's (two
    threads) of the same grid, which is timed too."""
    address, procs = start_cluster(tmp)
    os.makedirs(data_dir, exist_ok=True)
    total, total_cxx, cpu, rows, same = 0.0, 0.0, 0.0, 0, 0
    try:
        print("\n| sweep | points | wall [s] | CPU of the points [s] | top_sim_sweep --threads 2: wall [s] | "
              "rows equal to top_sim_sweep's (but cpu_seconds) |\n|---|---|---|---|---|---|")
        for top, plane, start, alphas in FIG4:
            name = "fig4_%s_%s%s.csv" % (top, plane, "_launched" if start == "launched" else "")
            out, reference = os.path.join(data_dir, name), os.path.join(tmp, name)
            grid = ["--top", top, "--plane", plane, "--start", start, "--alpha", alphas]
            wall, _ = timed(python_sweep(["--scheduler", address, "--out", out] + grid))
            wall_cxx, _ = timed([binary, "--threads", "2", "--out", reference] + grid)
            n, eq = compare(out, reference)
            total, total_cxx, cpu = total + wall, total_cxx + wall_cxx, cpu + cpu_of(out)
            rows, same = rows + n, same + eq
            print("| %s/%s %s | %d | %.2f | %.2f | %.2f | %d of %d |" % (top, plane, start, n, wall, cpu_of(out),
                                                                        wall_cxx, eq, n))
        print("| **whole grid** | %d | **%.1f** | %.1f | %.1f | %d of %d |" % (rows, total, cpu, total_cxx, same, rows))
    finally:
        stop(procs)
    subprocess.run([sys.executable, os.path.join(REPO, "scripts", "plots", "fig4_tan_half_phi.py"), data_dir, png],
                   check=True)
    print("figure: %s (load average %.1f)" % (png, load()))


def cost_by_kind(data_dir):
    """CPU seconds per point by start and outcome, from the Fig. 4 files (each point's thread CPU time)."""
    kinds = {}
    for name in sorted(os.listdir(data_dir)):
        start = "launched" if name.endswith("_launched.csv") else "tilted"
        with open(os.path.join(data_dir, name)) as f:
            for r in csv.DictReader(f):
                kinds.setdefault((start, r["outcome"]), []).append((float(r["cpu_seconds"]), float(r["sim_seconds"]),
                                                                     float(r["alpha"])))
    print("\n| start | outcome | points | CPU per point: median / min / max [s] | simulated s: median |"
          "\n|---|---|---|---|---|")
    for (start, outcome), v in sorted(kinds.items()):
        c = [x[0] for x in v]
        print("| %s | %s | %d | %.3f / %.3f / %.3f | %.0f |" % (start, outcome, len(v), statistics.median(c), min(c),
                                                               max(c), statistics.median(x[1] for x in v)))
    low = [x for k, v in kinds.items() if k == ("tilted", "sleeping") for x in v]
    if low:
        print("tilted, sleeping: CPU per point against alpha: %s" % ", ".join(
            "%.2f: %.2f s" % (a, c) for c, _, a in sorted(low, key=lambda x: x[2])[::6]))


def compare(ours, theirs):
    """(rows, rows equal in every column but cpu_seconds) of two sweep CSV files."""
    def rows(path):
        with open(path) as f:
            return [{k: v for k, v in r.items() if k != "cpu_seconds"} for r in csv.DictReader(f)]
    a, b = rows(ours), rows(theirs)
    return len(a), sum(1 for x, y in zip(a, b) if x == y) if len(a) == len(b) else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sweep-binary", default=os.path.join(REPO, "build", "bin", "top_sim_sweep"))
    ap.add_argument("--fig4-data", default=os.path.join(REPO, "docs", "data", "dask_fig4"))
    ap.add_argument("--fig4-png", default=os.path.join(REPO, "docs", "img", "fig4_dask.png"))
    ap.add_argument("--repeats", type=int, default=3, help="runs of each scaling case (default 3)")
    ap.add_argument("--skip", nargs="*", default=[], choices=["scaling", "overhead", "fig4"])
    a = ap.parse_args()
    print("machine: %d cores, load average %.1f at the start" % (os.cpu_count(), load()))
    tmp = tempfile.mkdtemp(prefix="sweep_dask_bench.")
    try:
        if "scaling" not in a.skip:
            scaling(a.sweep_binary, tmp, a.repeats)
        if "overhead" not in a.skip:
            overhead(tmp)
        if "fig4" not in a.skip:
            fig4(tmp, a.sweep_binary, a.fig4_data, a.fig4_png)
        if os.path.isdir(a.fig4_data):
            cost_by_kind(a.fig4_data)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
