#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets (test/fuzz/corpus/<target>/), run by hand after changing it:

    python3 test/fuzz/make_seeds.py

scene_loader: the scenes of config/scenes and test/scenes, and the hand-written scenes of SCENES_BY_HAND.
command, step: inputs in the byte encoding of fuzz_targets.cpp (class Bytes), written here from readable lists.
Files of past findings (named finding-*) are kept; every other file of a corpus directory is rewritten.
"""
import pathlib
import shutil
import struct
import sys
from decimal import Decimal

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORPUS = ROOT / "test" / "fuzz" / "corpus"

# fuzz_targets.cpp, kSpecial: the values a number can name in two bytes.
SPECIAL = ["0", "-0", "1", "-1", "nan", "inf", "-inf", "max", "-max", "min", "denorm", "-denorm", "1e-300",
           "1e300", "pi/2", "pi/2-", "pi", "1e-12", "1e-9", "0.5", "2", "1e-6"]
LAWS = {"paper": 0, "linearized": 1, "coulomb": 2, "table": 3}      # kFrictionLawNames order
SCENES = {"default": 0, "gyro_reversal": 1, "coulomb": 2, "hopping": 3, "ball": 4, "adiabatic": 5, "static": 6}
METHODS = ["euler", "semi_implicit_euler", "rk4", "dopri5", "rosenbrock4", "switching"]


def num(v):
    """One number: a name of SPECIAL, a decimal string (m 10^e, |m| < 32768, e in [-24, 23]) or a float (raw)."""
    if isinstance(v, str) and v in SPECIAL:
        return bytes([1, SPECIAL.index(v)])
    if isinstance(v, str):
        sign, digits, exp = Decimal(v).normalize().as_tuple()
        m = int("".join(map(str, digits))) * (-1 if sign else 1)
        while exp > 23:
            m, exp = m * 10, exp - 1
        if abs(m) < 32768 and -24 <= exp <= 23:
            return bytes([2]) + struct.pack("<h", m) + bytes([exp + 24])
        v = float(v)
    return bytes([0]) + struct.pack("<d", v)


def friction(law, mu_c="0.25", s_c="0.6", mu0="0.1", k="1", s0="0.3", mu="0.3", points=(), name=None):
    """A friction law as a TopCommand carries it: every scalar parameter, then the table's points."""
    out = bytes([LAWS[law]]) if name is None else bytes([0xE0, len(name)]) + name.encode()
    out += b"".join(num(x) for x in (mu_c, s_c, mu0, k, s0, mu))
    if law == "table":
        out += bytes([len(points)]) + b"".join(num(s) + num(m) for s, m in points)
    return out


FIELDS = ["inclination", "spin", "rotor_spin", "rotor_coupling", "friction", "static_friction", "restitution"]


def command(**fields):
    """One Command: the set_ flag byte, then each set field in FIELDS order (friction: bytes from friction())."""
    flags, body = 0, b""
    for bit, name in enumerate(FIELDS):
        if name in fields:
            flags |= 1 << bit
            body += fields[name] if name == "friction" else num(fields[name])
    return bytes([flags]) + body


def command_input(scene, commands, warmup=0, queued=False):
    plan = (len(commands) - 1) | (0x80 if queued else 0)
    return bytes([SCENES[scene], warmup, plan]) + b"".join(commands)


STATE_KEYS = ["start", "tilt", "tilt_azimuth", "spin", "angular_velocity_transverse", "position", "velocity", "gap",
              "gap_rate", "rotor_spin", "method", "dt", "rtol", "atol", "max_dt"]


def step_input(scene, **keys):
    """An initial state and integrator settings: two flag bytes, then each given key in STATE_KEYS order."""
    flags, body = 0, b""
    for bit, name in enumerate(STATE_KEYS):
        if name not in keys:
            continue
        flags |= 1 << bit
        v = keys[name]
        if name == "start":
            body += bytes([1 if v == "stationary" else 0])
        elif name == "method":
            body += bytes([METHODS.index(v)])
        elif isinstance(v, tuple):
            body += num(v[0]) + num(v[1])
        else:
            body += num(v)
    return bytes([SCENES[scene]]) + struct.pack("<H", flags) + body


TABLE = [("0", "0.1"), ("0.5", "0.3"), ("1", "0.2")]

COMMANDS = {
    "inclination": command_input("default", [command(inclination="0.2")]),
    "inclination_edge": command_input("default", [command(inclination="pi/2-")], warmup=128),
    "inclination_bad": command_input("default", [command(inclination="pi/2"), command(inclination="nan")]),
    "spin": command_input("default", [command(spin="400")], warmup=255),
    "spin_extremes": command_input("default", [command(spin="1e200"), command(spin="denorm"), command(spin="-inf")]),
    "coulomb_static": command_input("default", [command(friction=friction("coulomb", mu="0.3"),
                                                        static_friction="0.4")]),
    "table": command_input("default", [command(friction=friction("table", points=TABLE))]),
    "table_unsorted": command_input("default", [command(friction=friction("table", points=TABLE[::-1]))]),
    "linearized": command_input("default", [command(friction=friction("linearized", mu0="0.1", k="-0.5",
                                                                      s0="0.3"))]),
    "law_unknown": command_input("default", [command(friction=friction("paper", name="wood")),
                                             command(spin="100")]),
    "rotor": command_input("gyro_reversal", [command(rotor_spin="3000"), command(rotor_coupling="1e-8")]),
    "rotor_missing": command_input("default", [command(rotor_spin="3000", rotor_coupling="1e-8")]),
    "restitution": command_input("hopping", [command(restitution="1"), command(restitution="0")], warmup=64),
    "adiabatic": command_input("adiabatic", [command(inclination="0.3"), command(inclination="0.05")]),
    "static_normal_force": command_input("static", [command(static_friction="0.5"), command(restitution="0.5")]),
    "queued": command_input("coulomb", [command(friction=friction("coulomb", mu="0.1")),
                                        command(static_friction="0.2"), command(spin="-200")], queued=True),
    "everything_max": command_input("gyro_reversal", [command(**{f: ("max" if f != "friction" else
                                                                     friction("paper", mu_c="max", s_c="1"))
                                                                 for f in FIELDS})]),
    "ball": command_input("ball", [command(spin="50", static_friction="0.3")]),
}

STEPS = {
    "default": step_input("default"),
    "gyro_reversal": step_input("gyro_reversal"),
    "hopping": step_input("hopping"),
    "ball": step_input("ball"),
    "adiabatic": step_input("adiabatic"),
    "static": step_input("static"),
    "fast_tilted": step_input("default", tilt="0.3", spin="5000"),
    "stationary": step_input("default", start="stationary", spin="300"),
    "flight": step_input("default", gap="1e-3", gap_rate="0.1"),
    "near_max_tilt": step_input("default", tilt="1.05", spin="-50", tilt_azimuth="2"),
    "rolling_ball": step_input("ball", velocity=("5", "0"), spin="0", angular_velocity_transverse=("0", "-100")),
    "rk4_sliding": step_input("default", velocity=("1", "0"), method="rk4", dt="1e-3"),
    "euler_tiny_dt": step_input("default", method="euler", dt="1e-12"),
    "semi_implicit": step_input("coulomb", method="semi_implicit_euler", dt="1e-2"),
    "rosenbrock_tight": step_input("default", method="rosenbrock4", rtol="1e-12", atol="1e-15", max_dt="1e-5"),
    "upright": step_input("default", tilt="0", spin="0"),
    "rotor_reversed": step_input("gyro_reversal", rotor_spin="-5000", spin="20", method="switching"),
    "huge_spin": step_input("default", spin="1e150"),
    "huge_velocity": step_input("default", velocity=("max", "0")),
    "everything_odd": step_input("hopping", **{k: "-0" for k in STATE_KEYS if k not in ("start", "method", "dt")},
                                 start="stationary", method="dopri5", dt="1e-12"),
}


# Scenes that reach the loader's other branches: inline tops and laws, rotor, events, every section, bad keys.
SCENES_BY_HAND = {
    "inline_everything.yaml": """top: {mass: 0.05, tip_radius: 0.002, com_offset: 0.012, inertia_axial: 1.0e-5,
      inertia_transverse: 8.0e-6, max_tilt: 1.0, rotor: {inertia_axial: 2.0e-6, coupling: 1.0e-9, spin: 100.0}}
plane: {inclination: 0.05, gravity: 9.81}
friction: {law: table, points: [[0, 0.1], [0.4, 0.3], [1, 0.2]], static: 0.2, regularization_speed: 1.0e-8}
model: {normal_force: constrained, kind: full}
contact: {restitution: 0.3, stick_speed: 1.0e-6, settle_speed: 1.0e-5}
regime: {nutation_angle: 1.0e-3, nutation_rate: 2.0e-2, sleep_turn_rate: 1.0e-3, sleep_acceleration: 1.0e-7}
initial: {start: tilted, tilt: 0.2, tilt_azimuth: 1.0, spin: 150.0, angular_velocity_transverse: [1.0, -2.0],
          position: [0.1, 0.2], velocity: [0.01, 0.0], gap: 1.0e-4, gap_rate: 0.01}
integrator: {method: switching, dt: 1.0e-5, rtol: 1.0e-7, atol: 1.0e-9, max_dt: 1.0e-3}
duration: 0.5
events:
  - {t: 0.0001, spin: 300.0}
  - {t: 0.0002, inclination: 0.1, rotor_spin: 50.0, rotor_coupling: 0.0}
""",
    "linearized_static_model.yaml": """top: wood
friction: {law: linearized, mu0: 0.2, k: -0.3, s0: 0.5}
model: {normal_force: static}
initial: {start: stationary, spin: -100}
integrator: {method: rosenbrock4}
""",
    "adiabatic.yaml": "top: steel\nfriction: steel\nmodel: {kind: adiabatic}\nplane: {inclination: 0.05}\n",
    "flow_one_line.yaml": "{top: aluminium, friction: {law: coulomb, mu: 0.0}, integrator: {method: euler, dt: 1e-3}}",
    "bad_duplicate_key.yaml": "top: aluminium\ntop: steel\n",
    "bad_list_key.yaml": "top: {[]: 0}\n",
    "bad_subnormal.yaml": "top: {mass: 1e-310}\n",
    "bad_foreign_parameter.yaml": "top: aluminium\nfriction: {law: coulomb, mu_c: 0.3}\n",
    "bad_event_order.yaml": "top: aluminium\nevents: [{t: 0.2, spin: 1}, {t: 0.1, spin: 2}]\n",
    "bad_anchor_alias.yaml": "top: &a {mass: 0.02}\nplane: *a\nfriction: *a\n",
    "bad_not_a_mapping.yaml": "- top\n- aluminium\n",
    "bad_missing_file.yaml": "top: no_such_top\nfriction: ../scenes/default\n",
}


def write(directory, files):
    directory.mkdir(parents=True, exist_ok=True)
    for old in directory.iterdir():
        if not old.name.startswith("finding-"):
            old.unlink()
    for name, data in files.items():
        (directory / name).write_bytes(data)


def main():
    scenes = {name: text.encode() for name, text in SCENES_BY_HAND.items()}
    for folder in (ROOT / "config" / "scenes", ROOT / "test" / "scenes"):
        for f in sorted(folder.glob("*.yaml")):
            scenes[folder.parent.name + "_" + f.name] = f.read_bytes()
    write(CORPUS / "scene_loader", scenes)
    write(CORPUS / "command", COMMANDS)
    write(CORPUS / "step", STEPS)
    total = sum(f.stat().st_size for f in CORPUS.rglob("*") if f.is_file())
    print(f"{sum(1 for f in CORPUS.rglob('*') if f.is_file())} files, {total} bytes in {CORPUS}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
