"""Tests of python3 -m top_sim.sweep (docs/studies.md) against top_sim_sweep and the seeded samplers.

Run by ctest (plain build) with PYTHONPATH=<build>/python; TOP_SIM_SWEEP_BINARY names top_sim_sweep. The cluster
with a lost worker runs in two network namespaces (as test/ros/distributed_netns.sh) and is skipped without root.
Rows are compared in every column but cpu_seconds (a thread's CPU time differs from run to run).
"""
import csv
import io
import math
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import top_sim
from top_sim import sweep

SWEEP_BINARY = os.environ.get("TOP_SIM_SWEEP_BINARY", "")
# Cheap points: sleeping ones end at 4 m of path (unconverged), alpha 0.26 slides for 30 s.
QUICK = ["--alpha", "0.05,0.12,0.2,0.26", "--max-path", "4"]


def python_sweep(args, timeout=120, **kw):
    return subprocess.run([sys.executable, "-m", "top_sim.sweep", "--no-progress"] + args, capture_output=True,
                          text=True, timeout=timeout, **kw)


def reference_rows(args, tmp_path):
    """top_sim_sweep's CSV for `args`."""
    if not SWEEP_BINARY:
        pytest.skip("TOP_SIM_SWEEP_BINARY not set (ctest sets it)")
    out = tmp_path / "reference.csv"
    subprocess.run([SWEEP_BINARY, "--threads", "2", "--out", str(out)] + args, check=True, capture_output=True)
    return out.read_text().splitlines()


def without_cpu(lines, first=0):
    """The rows with the cpu_seconds column removed (`first` = columns before top_sim_sweep's)."""
    k = first + top_sim.SWEEP_HEADER.split(",").index("cpu_seconds")
    return [",".join(f for i, f in enumerate(line.split(",")) if i != k) for line in lines]


def rows_are_valid(text, header):
    """A header and complete rows only."""
    lines = text.split("\n")
    columns = header.count(",") + 1
    return lines[0] == header and lines[-1] == "" and all(line.count(",") + 1 == columns for line in lines[1:-1])


# ---- arguments --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("args", [
    ["--alpha", "2"], ["--alpha", "0.1:0.2:0"], ["--spin", "0"], ["--mu-c", "-1"], ["--tol", "x"], ["--bogus"],
    ["--threads", "0"], ["--start", "sideways"], ["--alpha"], ["--top", "a,,b"], ["--patch-radius", "-1e-3"],
    ["--patch-radius", "nan"], ["--patch-radius", "hertzz"], ["--patch-radius", "0,hertzz"],
    ["--patch-radius", "hertz,-1"]])
def test_bad_arguments_give_top_sim_sweeps_messages(args, capsys):
    if not SWEEP_BINARY:
        pytest.skip("TOP_SIM_SWEEP_BINARY not set (ctest sets it)")
    assert sweep.main(args) == 2  # in this process: the errors come before any cluster starts
    ours = capsys.readouterr().err
    theirs = subprocess.run([SWEEP_BINARY] + args, capture_output=True, text=True)
    assert theirs.returncode == 2
    first = theirs.stderr.splitlines()[0].replace("top_sim_sweep: ", "")
    assert ours.splitlines()[0] == "top_sim.sweep: " + first


def test_bad_grid_point_names_the_key(capsys):
    assert sweep.main(["--alpha", "0.1", "--plane", "no_such_plane"]) == 2
    err = capsys.readouterr().err
    assert "bad grid point" in err and "friction" in err and "no_such_plane" in err


def test_hertz_patch_needs_the_materials(tmp_path, capsys):
    top = tmp_path / "bare_top.yaml"  # the aluminium top without young_modulus and poisson_ratio
    top.write_text("".join(line for line in open(os.path.join(top_sim.config_dir(), "tops", "aluminium.yaml"))
                           if not line.startswith(("young_modulus", "poisson_ratio"))))
    args = ["--alpha", "0.1", "--top", str(top), "--patch-radius", "0,hertz"]
    assert sweep.main(args) == 2
    ours = capsys.readouterr().err
    assert "--patch-radius = 'hertz'" in ours and "young_modulus" in ours and ">= 0 [m]" in ours
    if SWEEP_BINARY:
        theirs = subprocess.run([SWEEP_BINARY] + args, capture_output=True, text=True)
        assert theirs.returncode == 2 and "--patch-radius = 'hertz'" in theirs.stderr


@pytest.mark.parametrize("args, words", [
    (["--samples", "3", "--alpha", "0.1"], ["--seed"]),
    (["--seed", "1", "--alpha", "0.1"], ["--seed = '1'", "--samples"]),
    (["--samples", "0", "--seed", "1", "--alpha", "0.1"], ["--samples = '0'", "[1, 1000000]"]),
    (["--samples", "3", "--seed", "-1", "--alpha", "0.1"], ["--seed = '-1'", "[0, 2^63)"]),
    (["--samples", "3", "--seed", "1.5", "--alpha", "0.1"], ["--seed = '1.5'", "integer"]),
    (["--samples", "3", "--seed", "1", "--alpha", "uniform:0.2:0.1"], ["'uniform:0.2:0.1'", "LO < HI"]),
    (["--samples", "3", "--seed", "1", "--alpha", "uniform:0.1:2"], ["HI = 2", "(0, pi/2)"]),
    (["--samples", "3", "--seed", "1", "--alpha", "normal:0.1:0"], ["'normal:0.1:0'", "> 0"]),
    (["--samples", "3", "--seed", "1", "--alpha", "0.1", "--mu-c", "lognormal:-0.3:0.1"], ["--mu-c", "MEDIAN"]),
    (["--samples", "3", "--seed", "1", "--alpha", "poisson:1:2"], ["'poisson:1:2'", "uniform:LO:HI"]),
    (["--samples", "3", "--seed", "1", "--alpha", "0.1,0.2"], ["'0.1,0.2'", "one value"]),
    (["--alpha", "normal:0.1:0.01"], ["--samples"]),
    (["--samples", "3", "--seed", "1", "--alpha", "0.1", "--top", "aluminium,steel"], ["one top"]),
    (["--samples", "3", "--seed", "1", "--alpha", "0.1", "--patch-radius", "0,hertz"], ["one patch radius"]),
    (["--scheduler", "tcp://127.0.0.1:1", "--threads", "2"], ["--threads"]),
    (["--resume"], ["--out FILE"]),
    (["--connect-timeout", "0"], ["--connect-timeout = '0'", "(0, 3600]"])])
def test_bad_monte_carlo_and_cluster_flags(args, words, capsys):
    assert sweep.main(args) == 2
    first = capsys.readouterr().err.splitlines()[0]
    for w in words:
        assert w in first


# ---- the samplers -----------------------------------------------------------------------------------------------

def test_samplers_draw_their_distributions_reproducibly():
    n = 20000
    base = {"top": "aluminium", "plane": "pmma", "alpha": 0.1, "spin": 200.0, "mu_c": None, "s_c": None}
    dists = {"--alpha": ("uniform", 0.05, 0.15), "--spin": ("normal", 200.0, 10.0),
             "--mu-c": ("lognormal", 0.25, 0.1)}
    points = sweep.monte_carlo_points(base, dists, n, seed=11)
    alpha = np.array([p["alpha"] for p in points])
    spin = np.array([p["spin"] for p in points])
    log_mu = np.log([p["mu_c"] for p in points])
    # Means within 5 standard errors; the spreads within 5 % (n = 20000: their standard error is 0.5 %).
    assert abs(alpha.mean() - 0.1) < 5 * 0.1 / math.sqrt(12 * n) and alpha.min() >= 0.05 and alpha.max() <= 0.15
    assert abs(alpha.std() - 0.1 / math.sqrt(12)) < 0.05 * 0.1 / math.sqrt(12)
    assert abs(spin.mean() - 200.0) < 5 * 10.0 / math.sqrt(n) and abs(spin.std() - 10.0) < 0.5
    assert abs(log_mu.mean() - math.log(0.25)) < 5 * 0.1 / math.sqrt(n) and abs(log_mu.std() - 0.1) < 0.005
    assert all(p["s_c"] is None and p["top"] == "aluminium" for p in points)
    assert sweep.monte_carlo_points(base, dists, 50, seed=11) == points[:50]
    assert sweep.monte_carlo_points(base, dists, 50, seed=12) != points[:50]


def test_a_draw_outside_the_range_is_drawn_again():
    base = {"top": "aluminium", "plane": "pmma", "alpha": 0.1, "spin": 200.0, "mu_c": None, "s_c": None}
    points = sweep.monte_carlo_points(base, {"--alpha": ("normal", 0.01, 0.05)}, 2000, seed=3)
    alpha = np.array([p["alpha"] for p in points])
    assert alpha.min() > 0.0 and alpha.max() < math.pi / 2
    # Truncated at 0: about half the normal's draws were redrawn, so the median is near 0.01 + 0.6745 * 0.05 / 1.5.
    assert 0.03 < np.median(alpha) < 0.05


# ---- runs on a local cluster ------------------------------------------------------------------------------------

def test_local_cluster_rows_equal_top_sim_sweeps(tmp_path):
    args = QUICK + ["--top", "aluminium,steel", "--spin", "200,-150"]
    out = tmp_path / "dask.csv"
    r = python_sweep(args + ["--threads", "2", "--out", str(out)])
    assert r.returncode == 0, r.stderr
    assert "16 points" in r.stderr and "on 2 workers" in r.stderr
    ours = out.read_text().splitlines()
    assert without_cpu(ours) == without_cpu(reference_rows(args, tmp_path))
    assert {line.split(",")[12] for line in ours[1:]} >= {"sliding", "unconverged"}


def test_hertz_patch_rows_equal_top_sim_sweeps_and_move_phi(tmp_path):
    args = ["--alpha", "0.1", "--patch-radius", "0,hertz", "--start", "launched", "--max-path", "4"]
    out = tmp_path / "patch.csv"
    r = python_sweep(args + ["--threads", "2", "--out", str(out)])
    assert r.returncode == 0, r.stderr
    ours = out.read_text().splitlines()
    assert without_cpu(ours) == without_cpu(reference_rows(args, tmp_path))
    rows = list(csv.DictReader(io.StringIO("\n".join(ours))))
    assert [row["patch_radius"] for row in rows] == ["0", "hertz"]
    point, patch = (float(row["phi_measured"]) for row in rows)
    # The drilling torque turns the path: more than the sweep's phi tolerance (1e-6 rad) times a thousand.
    assert abs(patch - point) > 1e-3, (point, patch)


def test_interrupted_sweep_leaves_a_valid_file_and_resume_completes_it(tmp_path):
    args = ["--alpha", "0.03:0.07:5", "--max-path", "12"]  # 0.1 to 0.4 s of CPU per point
    out = tmp_path / "partial.csv"
    p = subprocess.Popen([sys.executable, "-m", "top_sim.sweep", "--threads", "2", "--out", str(out)] + args,
                         stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and (not out.exists() or out.read_text().count("\n") < 2):
        time.sleep(0.05)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=30)
    assert p.returncode == 130, err
    text = out.read_text()
    assert rows_are_valid(text, top_sim.SWEEP_HEADER)
    kept = text.count("\n") - 1
    assert 1 <= kept < 5 and "--resume" in err
    with open(out, "a") as f:
        f.write("aluminium,pmma,0.25,0.6,200,0.0")  # a row cut short, as by a kill during a write
    r = python_sweep(args + ["--threads", "2", "--out", str(out), "--resume"])
    assert r.returncode == 0, r.stderr
    assert "(%d of them from the resumed file)" % kept in r.stderr
    assert without_cpu(out.read_text().splitlines()) == without_cpu(reference_rows(args, tmp_path))


def test_resume_refuses_another_sweeps_file(tmp_path, capsys):
    out = tmp_path / "other.csv"
    out.write_text(top_sim.SWEEP_HEADER + "\n" + "steel,steel,0.2,0.7,200,0.1" + ",0" * 13 + "\n")
    assert sweep.main(QUICK + ["--out", str(out), "--resume"]) == 2
    assert "does not have" in capsys.readouterr().err


def test_monte_carlo_is_reproducible_with_a_seed(tmp_path):
    args = ["--samples", "6", "--seed", "42", "--alpha", "uniform:0.05:0.2", "--mu-c", "normal:0.25:0.01",
            "--max-path", "3"]
    out = tmp_path / "mc.csv"
    r = python_sweep(args + ["--threads", "2", "--out", str(out)])
    assert r.returncode == 0, r.stderr
    assert "Monte Carlo, 6 samples" in r.stderr and "phi* analytic (6 samples" in r.stderr
    lines = out.read_text().splitlines()
    assert lines[0] == "sample," + top_sim.SWEEP_HEADER
    # The seed alone makes the points again; run here, one by one, they give the cluster's rows.
    plan = sweep.parse_arguments(args)
    again = [lines[0]] + ["%d,%s" % (i, top_sim._core.run_sweep_point(p, plan.settings)["row"])
                          for i, p in enumerate(plan.points)]
    assert without_cpu(lines, first=1) == without_cpu(again, first=1)
    rows = list(csv.DictReader(io.StringIO("\n".join(lines))))
    assert all(0.05 <= float(row["alpha"]) <= 0.2 for row in rows)
    assert len({row["alpha"] for row in rows}) == 6 and len({row["mu_c"] for row in rows}) == 6
    other = sweep.parse_arguments(args[:3] + ["43"] + args[4:])
    assert [p["alpha"] for p in other.points] != [p["alpha"] for p in plan.points]


def test_unreachable_scheduler_fails_within_the_timeout(tmp_path):
    t0 = time.monotonic()
    r = python_sweep(QUICK + ["--scheduler", "tcp://127.0.0.1:9", "--connect-timeout", "2",
                              "--out", str(tmp_path / "x.csv")], timeout=60)
    assert r.returncode == 4
    assert "--scheduler = 'tcp://127.0.0.1:9': no Dask scheduler answered within 2 s" in r.stderr
    assert time.monotonic() - t0 < 20
