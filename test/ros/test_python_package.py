"""The Python package top_sim in the catkin workspace (issue 35 item 5): the generated messages and services
(top_sim.msg, top_sim.srv) and the physics (top_sim._core, re-exported as top_sim.*) side by side, and
`python3 -m top_sim.sweep` on a local Dask cluster. Run by catkin's run_tests with the devel space sourced.
"""
import os
import subprocess
import sys

import top_sim
import top_sim.sweep


def test_messages_and_physics_are_one_package():
    from top_sim.msg import TopState, TopCommand
    from top_sim.srv import Spawn
    assert TopState._type == "top_sim/TopState" and TopCommand._type == "top_sim/TopCommand"
    assert Spawn._type == "top_sim/Spawn"
    snap = top_sim.Simulator("default").run(0.05)
    assert abs(snap["t"] - 0.05) < 1e-12 and snap["fault"] is None
    assert os.path.isdir(os.path.join(top_sim.config_dir(), "scenes"))
    # The compiled module sits in the devel space's top_sim directory, where catkin generates top_sim.msg.
    assert os.path.dirname(top_sim._core.__file__) == os.path.dirname(os.path.dirname(top_sim.msg.__file__))


def test_sweep_module_runs_from_the_workspace(tmp_path):
    out = tmp_path / "sweep.csv"
    args = ["--alpha", "0.1,0.27", "--max-path", "2"]
    r = subprocess.run([sys.executable, "-m", "top_sim.sweep", "--threads", "1", "--out", str(out)] + args,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    lines = out.read_text().splitlines()
    plan = top_sim.sweep.parse_arguments(args)
    cpu = top_sim.SWEEP_HEADER.split(",").index("cpu_seconds")
    assert lines[0] == top_sim.SWEEP_HEADER and len(lines) == 3
    for line, point in zip(lines[1:], plan.points):
        expected = top_sim._core.run_sweep_point(point, plan.settings)["row"].split(",")
        got = line.split(",")
        assert got[:cpu] + got[cpu + 1:] == expected[:cpu] + expected[cpu + 1:]
