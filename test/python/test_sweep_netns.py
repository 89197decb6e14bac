"""python3 -m top_sim.sweep on a Dask cluster of two hosts, one of them lost mid-sweep: every point still arrives.

Two network namespaces joined by a veth pair (as test/ros/distributed_netns.sh does for the ROS graph): A runs the
dask scheduler, a worker and the sweep; B runs the second worker, which is killed (SIGKILL) once two rows are in.
Its tasks rerun on A's worker. Needs root and `ip` (iproute2); skipped otherwise.
"""
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

import top_sim

from test_sweep import reference_rows, without_cpu

PID = os.getpid()
NS_A, NS_B = "ts_dask_a_%d" % PID, "ts_dask_b_%d" % PID
VETH_A, VETH_B = "tda%d" % (PID % 100000), "tdb%d" % (PID % 100000)  # at most 15 characters
IP_A, IP_B = "10.214.0.1", "10.214.0.2"
SCHEDULER = "tcp://%s:8786" % IP_A
# 12 points of 0.1 to 0.6 s of CPU each: the sweep lasts seconds, long enough to lose a worker in the middle.
ARGS = ["--alpha", "0.03:0.2:12", "--max-path", "6"]


def skip_reason():
    if os.geteuid() != 0:
        return "network namespaces need root (uid %d)" % os.geteuid()
    if shutil.which("ip") is None:
        return "no 'ip' command (Debian package iproute2)"
    if shutil.which("dask-scheduler") is None or shutil.which("dask-worker") is None:
        return "no dask-scheduler / dask-worker (Debian package python3-distributed)"
    return ""


def ip(*args):
    subprocess.run(["ip"] + list(args), check=True, capture_output=True)


@pytest.fixture
def hosts():
    """Namespaces A and B with addresses IP_A and IP_B; removed afterwards with whatever runs in them."""
    reason = skip_reason()
    if reason:
        pytest.skip(reason)
    made = []
    try:
        for ns in (NS_A, NS_B):
            ip("netns", "add", ns)
            made.append(ns)
        ip("link", "add", VETH_A, "netns", NS_A, "type", "veth", "peer", "name", VETH_B, "netns", NS_B)
        for ns, veth, addr in ((NS_A, VETH_A, IP_A), (NS_B, VETH_B, IP_B)):
            ip("-n", ns, "addr", "add", addr + "/24", "dev", veth)
            ip("-n", ns, "link", "set", "lo", "up")
            ip("-n", ns, "link", "set", veth, "up")
    except subprocess.CalledProcessError as e:
        for ns in made:
            subprocess.run(["ip", "netns", "del", ns], capture_output=True)
        pytest.skip("network namespaces not permitted: %s" % e.stderr.decode().strip())
    yield
    for ns in made:
        pids = subprocess.run(["ip", "netns", "pids", ns], capture_output=True, text=True).stdout.split()
        for pid in pids:
            try:
                os.kill(int(pid), signal.SIGKILL)
            except ProcessLookupError:
                pass
        subprocess.run(["ip", "netns", "del", ns], capture_output=True)


def start(ns, args, log):
    """A process in namespace `ns` with this environment (PYTHONPATH finds top_sim), output to `log`."""
    return subprocess.Popen(["ip", "netns", "exec", ns] + args, stdout=log, stderr=subprocess.STDOUT)


def wait_for_rows(path, n, timeout):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if path.exists() and path.read_text().count("\n") >= n + 1:
            return True
        time.sleep(0.05)
    return False


def wait_for_workers(log_path, n, timeout):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if log_path.read_text().count("Register worker") >= n:
            return True
        time.sleep(0.1)
    return False


def test_a_worker_lost_mid_sweep_loses_no_point(hosts, tmp_path):
    expected = reference_rows(ARGS, tmp_path)
    logs = {name: open(tmp_path / (name + ".log"), "w") for name in ("scheduler", "worker_a", "worker_b")}
    worker = ["--nthreads", "1", "--no-nanny", "--no-dashboard", SCHEDULER]
    start(NS_A, ["dask-scheduler", "--host", IP_A, "--port", "8786", "--no-dashboard"], logs["scheduler"])
    start(NS_A, ["dask-worker", "--host", IP_A] + worker, logs["worker_a"])
    worker_b = start(NS_B, ["dask-worker", "--host", IP_B] + worker, logs["worker_b"])
    assert wait_for_workers(tmp_path / "scheduler.log", 2, 60), "the two workers did not register within 60 s"
    out = tmp_path / "netns.csv"
    sweep = subprocess.Popen(["ip", "netns", "exec", NS_A, sys.executable, "-m", "top_sim.sweep", "--no-progress",
                              "--scheduler", SCHEDULER, "--connect-timeout", "30", "--out", str(out)] + ARGS,
                             stderr=subprocess.PIPE, text=True)
    assert wait_for_rows(out, 2, 90), "no 2 rows within 90 s"
    rows_at_kill = out.read_text().count("\n") - 1
    worker_b.kill()  # SIGKILL: the host is gone, its task in flight with it
    _, err = sweep.communicate(timeout=120)
    for log in logs.values():
        log.close()
    scheduler_log = (tmp_path / "scheduler.log").read_text()
    assert sweep.returncode == 0, err + scheduler_log
    assert "on 2 workers" in err
    assert rows_at_kill < 12
    # The scheduler removed B with tasks of the sweep on it (processing > 0): they ran again on A.
    removed = [line for line in scheduler_log.splitlines() if "Remove worker" in line and IP_B in line]
    assert removed and "processing: 0>" not in removed[0], scheduler_log
    assert without_cpu(out.read_text().splitlines()) == without_cpu(expected)
    assert top_sim.SWEEP_HEADER == out.read_text().splitlines()[0]
