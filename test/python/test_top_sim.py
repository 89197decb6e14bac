"""Tests of the Python module top_sim against physics.md's analytic results and the C++ tools' output.

Run by ctest (plain build) with PYTHONPATH=<build>/python; TOP_SIM_RUN_BINARY names top_sim_run.
"""
import csv
import math
import os
import subprocess
import threading

import numpy as np
import pytest

import top_sim

MU_C, S_C = 0.25, 0.6  # config/planes/pmma.yaml (the default scene's paper law)


def paper_phi_star(alpha):
    """physics.md section 5: mu(s*) = tan(alpha) on the rising branch, phi* = 2 atan(s*)."""
    s_star = S_C * (1.0 - math.sqrt(1.0 - math.tan(alpha) / MU_C))
    return s_star, 2.0 * math.atan(s_star)


def default_dict(**initial):
    """The default scene as a dict (the same keys as config/scenes/default.yaml)."""
    scene = {
        "top": "aluminium",
        "plane": {"inclination": 0.1, "gravity": 9.81},
        "friction": "pmma",
        "initial": {"start": "tilted", "tilt": 0.1, "spin": 200.0},
        "integrator": {"method": "dopri5", "rtol": 1e-8, "atol": 1e-10},
        "duration": 300.0,
    }
    scene["initial"].update(initial)
    return scene


def test_stationary_state_is_the_analytic_one():
    for alpha in (0.02, 0.1, 0.2):
        scene = default_dict()
        scene["plane"]["inclination"] = alpha
        st = top_sim.stationary_state(scene)
        s_star, phi_star = paper_phi_star(alpha)
        assert st["exists"]
        assert st["slip"] == pytest.approx(s_star, abs=1e-12)  # a root solve to machine precision
        assert st["phi"] == pytest.approx(phi_star, abs=1e-12)


def test_no_stationary_state_above_the_critical_inclination():
    scene = default_dict()
    scene["plane"]["inclination"] = math.atan(MU_C) + 0.01  # tan(alpha) > max mu = mu_c
    st = top_sim.stationary_state(scene)
    assert not st["exists"]
    assert st["reason"]


def test_default_scene_falls_asleep_at_phi_star():
    sim = top_sim.Simulator("default")
    snap = sim.run(300.0)
    assert snap["t"] == pytest.approx(300.0, abs=1e-9)
    assert snap["regime"] == "sleeping"
    assert snap["fault"] is None
    _, phi_star = paper_phi_star(0.1)
    assert snap["phi_star"] == pytest.approx(phi_star, abs=1e-12)
    # The contact point's direction of travel relaxes to phi*: within 1e-4 rad after 300 s (physics.md 5).
    assert snap["phi"] == pytest.approx(phi_star, abs=1e-4)
    assert abs(snap["energy_residual"]) < 1e-8  # E + W_diss conserved to the integrator's tolerance


def test_dict_file_and_name_give_the_same_run():
    by_name = top_sim.Simulator("default").run(2.0)
    path = os.path.join(top_sim.config_dir(), "scenes", "default.yaml")
    by_path = top_sim.Simulator(top_sim.load_scene(path)).run(2.0)
    by_dict = top_sim.Simulator(default_dict()).run(2.0)
    for other in (by_path, by_dict):
        np.testing.assert_array_equal(other["com"], by_name["com"])  # same scene, same arithmetic
        assert other["phi"] == by_name["phi"]


def test_trajectory_matches_top_sim_run_csv(tmp_path):
    binary = os.environ.get("TOP_SIM_RUN_BINARY")
    if not binary:
        pytest.skip("TOP_SIM_RUN_BINARY not set (ctest sets it)")
    path = os.path.join(top_sim.config_dir(), "scenes", "default.yaml")
    out = tmp_path / "default.csv"
    subprocess.run([binary, path, "--duration", "1", "--rate", "50", "--csv", str(out)], check=True,
                   capture_output=True)
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    traj = top_sim.Simulator("default").trajectory(1.0, 50.0)
    assert list(traj.keys()) == top_sim.COLUMNS
    assert list(rows[0].keys()) == top_sim.COLUMNS
    assert len(traj["t"]) == len(rows) == 51
    for name in top_sim.COLUMNS:
        if name in ("regime", "contact_mode"):
            names = top_sim.REGIMES if name == "regime" else top_sim.CONTACT_MODES
            assert [names[int(c)] for c in traj[name]] == [r[name] for r in rows]
        else:
            csv_values = np.array([float(r[name]) for r in rows])
            # The CSV prints each double's shortest round-trip text: the same samples, bit for bit.
            np.testing.assert_array_equal(traj[name], csv_values, err_msg=name)


def test_trajectory_sampling():
    sim = top_sim.Simulator("default")
    sim.run(0.5)
    traj = sim.trajectory(0.25, 40.0)
    assert len(traj["t"]) == 11  # both ends included
    np.testing.assert_allclose(traj["t"], 0.5 + np.arange(11) / 40.0, rtol=0, atol=1e-12)
    assert sim.time == pytest.approx(0.75, abs=1e-12)


def test_commands_take_effect_and_bad_ones_are_refused():
    sim = top_sim.Simulator("default")
    sim.run(0.1)
    sim.apply({"inclination": 0.05, "spin": 150.0})
    snap = sim.run(0.001)
    assert snap["alpha"] == 0.05
    before = sim.snapshot()
    with pytest.raises(ValueError, match="inclination"):
        sim.apply({"inclination": 2.0})
    with pytest.raises(KeyError, match="alpha"):
        sim.apply({"alpha": 0.1})
    with pytest.raises(ValueError, match="mu_c"):
        sim.apply({"friction": {"law": "paper", "mu_c": -1.0}})  # the core's range check: mu_c > 0
    with pytest.raises(KeyError, match="reads mu_c, s_c"):
        sim.apply({"friction": {"law": "paper", "mu": 0.3}})
    with pytest.raises(ValueError, match="must be finite and >= the current time"):
        sim.step_to(0.0)
    with pytest.raises(ValueError, match="duration"):
        sim.run(float("nan"))
    after = sim.snapshot()
    assert after["t"] == before["t"] and after["alpha"] == before["alpha"]  # refused input changes nothing
    np.testing.assert_array_equal(after["com"], before["com"])


def test_friction_parameters_not_given_keep_the_law_in_force():
    # One rule with TopCommand and dynamic_reconfigure: s_c not given stays the scene's 0.6 (pmma), mu_c changes.
    sim = top_sim.Simulator("default")
    sim.apply({"friction": {"law": "paper", "mu_c": 0.4}})
    sim.run(0.01)
    s_star = 0.6 * (1.0 - math.sqrt(1.0 - math.tan(0.1) / 0.4))
    assert sim.stationary_state()["phi"] == pytest.approx(2.0 * math.atan(s_star), abs=1e-12)


def test_friction_command_changes_phi_star():
    sim = top_sim.Simulator("default")
    sim.run(0.01)
    sim.apply({"friction": {"law": "paper", "mu_c": 0.4, "s_c": 0.6}})
    sim.run(0.01)
    s_star = 0.6 * (1.0 - math.sqrt(1.0 - math.tan(0.1) / 0.4))  # physics.md section 5 with the new law
    assert sim.stationary_state()["phi"] == pytest.approx(2.0 * math.atan(s_star), abs=1e-12)


def test_scene_errors_name_key_value_and_range():
    scene = default_dict()
    scene["plane"]["inclination"] = 2.0
    with pytest.raises(top_sim.SceneError, match=r"plane\.inclination: 2 is out of range; must be in \(-pi/2, pi/2\)"):
        top_sim.load_scene(scene)
    scene = default_dict()
    scene["initial"]["spinn"] = 1.0
    with pytest.raises(top_sim.SceneError, match="spinn"):
        top_sim.load_scene(scene)
    with pytest.raises(top_sim.SceneError, match="cannot open"):
        top_sim.load_scene("/nonexistent/scene.yaml")


def test_hopping_scene_keeps_the_energy_balance():
    sim = top_sim.Simulator("hopping")
    snap = sim.run(0.1)
    assert sim.mode_switch_count > 0  # it lifts off (physics.md section 9)
    assert sum(sim.mode_seconds.values()) == pytest.approx(0.1, abs=1e-12)
    assert abs(snap["energy_residual"]) < 1e-9  # every impact loss is booked in W_diss


def test_threads_run_simulators_in_parallel_with_the_same_results():
    alphas = [0.04, 0.08, 0.12, 0.16]
    sequential = [top_sim.Simulator(dict(default_dict(), plane={"inclination": a})).run(20.0)["phi"] for a in alphas]
    results = [None] * len(alphas)

    def work(i):
        results[i] = top_sim.Simulator(dict(default_dict(), plane={"inclination": alphas[i]})).run(20.0)["phi"]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(alphas))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == sequential  # each simulator is independent of the others


def test_gil_is_released_and_one_thread_owns_a_simulator():
    sim = top_sim.Simulator("default")
    done = threading.Event()

    def work():
        sim.run(3000.0)  # about 0.3 s of CPU
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    refused = False
    while not done.is_set():
        try:
            sim.time  # noqa: B018 - this Python code runs only if run() released the GIL
        except RuntimeError as e:
            assert "another thread" in str(e)
            refused = True
            break
    worker.join()
    assert refused, "the main thread never ran while run() was simulating: the GIL was held"
    assert sim.time == pytest.approx(3000.0)


def pivoting_dict(patch_radius):
    """An upright top on a level plane with Coulomb friction and a fixed patch (physics.md section 12)."""
    return {
        "top": {"mass": 0.025, "tip_radius": 1.5e-3, "com_offset": 0.01, "inertia_axial": 5.0e-6,
                "inertia_transverse": 3.0e-6},
        "plane": {"inclination": 0.0, "gravity": 9.81},
        "friction": {"law": "coulomb", "mu": 0.3},
        "contact": {"patch_radius": patch_radius},
        "initial": {"start": "tilted", "tilt": 0.0, "spin": 100.0},
    }


def pivoting_torque(scene, a):
    """n . M_n = -mu m g (3 pi a / 16): Coulomb drilling under a Hertzian pressure, spin positive."""
    return -scene["friction"]["mu"] * scene["top"]["mass"] * scene["plane"]["gravity"] * 3.0 * math.pi * a / 16.0


def test_finite_contact_quantities_in_snapshot_and_trajectory():
    a = 2.0e-4
    scene = pivoting_dict(a)
    sim = top_sim.Simulator(scene)
    snap = sim.run(0.1)
    expected = pivoting_torque(scene, a)
    assert snap["patch_radius"] == a
    assert snap["drilling_torque"] == pytest.approx(expected, rel=1e-6)
    traj = sim.trajectory(0.1, 20.0)
    np.testing.assert_array_equal(traj["patch_radius"], np.full(len(traj["t"]), a))
    np.testing.assert_allclose(traj["drilling_torque"], expected, rtol=1e-6)
    point = top_sim.Simulator("default").run(0.1)  # a point contact: both zero
    assert point["drilling_torque"] == 0.0 and point["patch_radius"] == 0.0


def test_finite_contact_commands_apply_and_bad_ones_are_refused():
    a = 2.0e-4
    scene = pivoting_dict(a)
    sim = top_sim.Simulator(scene)
    sim.run(0.05)
    before = sim.snapshot()
    with pytest.raises(ValueError, match="patch_radius"):
        sim.apply({"patch_radius": -1.0})
    for key in ("rolling_resistance", "spin_drag", "drag"):
        with pytest.raises(ValueError, match=key):
            sim.apply({key: float("nan")})
    after = sim.snapshot()
    assert after["t"] == before["t"] and after["patch_radius"] == a  # refused input changes nothing
    sim.apply({"patch_radius": 2.0 * a})
    snap = sim.run(0.01)
    assert snap["patch_radius"] == 2.0 * a
    assert snap["drilling_torque"] == pytest.approx(pivoting_torque(scene, 2.0 * a), rel=1e-6)
    sim.apply({"rolling_resistance": 1.0e-5, "spin_drag": 1.0e-9, "drag": 1.0e-6, "patch_radius": 0.0})
    snap = sim.run(0.01)
    assert snap["fault"] is None
    assert snap["patch_radius"] == 0.0 and snap["drilling_torque"] == 0.0  # back to a point contact


def disc_dict(transverse_rate=0.0, gap=None):
    """A thin disc (0.4 kg, rim radius 0.04 m; physics.md section 13) tilted 0.5 rad on a level plane."""
    initial = {"tilt": 0.5, "spin": 0.0, "angular_velocity_transverse": [transverse_rate, 0.0]}
    if gap is not None:
        initial["gap"] = gap
    return {
        "top": {"mass": 0.4, "inertia_axial": 3.2e-4, "inertia_transverse": 1.6e-4,
                "shapes": [{"rim": {"offset": 0.0, "radius": 0.04}}]},
        "plane": {"inclination": 0.0, "gravity": 9.81},
        "friction": {"law": "coulomb", "mu": 0.3, "static": 0.3},
        "initial": initial,
    }


def test_dropped_disc_touches_after_free_fall_and_ends_lying_flat():
    h, g, rate = 0.01, 9.81, 1000.0
    sim = top_sim.Simulator(disc_dict(gap=h))
    start = sim.snapshot()
    assert start["touching"] == 0 and start["contact_mode"] == "flight"
    assert start["end_state"] is None and start["end_state_message"] == "" and sim.end_state is None
    traj = sim.trajectory(5.0, rate)
    t, touching = traj["t"], traj["touching"]
    t_touch = math.sqrt(2.0 * h / g)  # free fall of h, no spin
    assert np.count_nonzero(t < t_touch) == math.floor(t_touch * rate) + 1
    np.testing.assert_array_equal(touching[t < t_touch], 0.0)
    first = t[np.argmax(touching == 1.0)]
    assert t_touch <= first <= t_touch + 1.0 / rate
    flight = top_sim.CONTACT_MODES.index("flight")
    np.testing.assert_array_equal(touching, np.where(traj["contact_mode"] == flight, 0.0, 1.0))
    assert t[-1] < 5.0  # stopped at the end state
    end = sim.snapshot()
    assert end["end_state"] == "lying_flat" and sim.end_state == "lying_flat"
    assert "lying_flat" in end["end_state_message"] and sim.end_message == end["end_state_message"]
    assert end["fault"] is None and sim.fault is None and sim.fault_message == ""  # a named end, no fault
    assert end["regime"] == "lying_flat"  # the end's word is the regime
    assert end["touching"] == 1 and isinstance(end["touching"], int)


def test_rolling_disc_touches_throughout():
    # Omega^2 a sin(beta) = 4 g with the centre at rest (physics.md section 13): the transverse rate -Omega tan(beta).
    beta, a, g = 0.5, 0.04, 9.81
    rate = -math.sqrt(4.0 * g / (a * math.sin(beta))) * math.tan(beta)
    sim = top_sim.Simulator(disc_dict(transverse_rate=rate))
    traj = sim.trajectory(1.0, 100.0)
    np.testing.assert_array_equal(traj["touching"], np.ones(len(traj["t"])))
    snap = sim.snapshot()
    assert snap["touching"] == 1 and snap["contact_mode"] == "rolling"
    assert snap["end_state"] is None and snap["end_state_message"] == ""
    assert top_sim.Simulator("default").snapshot()["touching"] == 1  # no shapes: the tip sphere, bit 0


def test_a_top_that_falls_ends_fallen_without_a_fault():
    # No spin: it falls over like an inverted pendulum (about 0.15 s); a fall is an end of its story (issue 46).
    sim = top_sim.Simulator({"top": "aluminium", "plane": {"inclination": 0.1}, "friction": "pmma",
                             "initial": {"tilt": 0.1, "spin": 0.0}})
    sim.run(2.0)
    snap = sim.snapshot()
    assert sim.end_state == "fallen" and snap["end_state"] == "fallen" and snap["regime"] == "fallen"
    assert sim.fault is None and sim.fault_message == "" and snap["fault"] is None
    assert "max_tilt" in sim.end_message and 0.1 < sim.time < 0.3
