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
# fuzz_targets.cpp, kSceneFiles and base_nodes(): every config scene and the variants, by index.
SCENES = {name: i for i, name in enumerate([
    "default", "gyro_reversal", "coulomb", "hopping", "ball", "adiabatic", "static", "euler_disk", "fig2_spin100",
    "fig2_spin200", "fig2_spin400", "fig5_linearized", "frictionless", "phase_reversed200", "phase_spin100",
    "phase_spin200", "phase_spin400", "reversed_spin", "spin_down", "supercritical", "tippe_top",
    "tippe_top_contensou", "tippe_top_rolling", "tippe_top_stem", "tippe_top_tumbling", "top_life", "upright",
    "auto", "spin_down_auto", "top_life_both", "tippe_top_stem_both"])}
METHODS = ["euler", "semi_implicit_euler", "rk4", "dopri5", "rosenbrock4", "switching", "implicit_midpoint",
           "fitted_midpoint"]


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
MORE_FIELDS = ["patch_radius", "rolling_resistance", "spin_drag", "drag"]   # after the second flag byte


def command(**fields):
    """One Command: the set_ flag byte, then each set field in FIELDS order (friction: bytes from friction());
    any of MORE_FIELDS sets flag 0x80 and adds a second flag byte and those fields."""
    flags, body = 0, b""
    for bit, name in enumerate(FIELDS):
        if name in fields:
            flags |= 1 << bit
            body += fields[name] if name == "friction" else num(fields[name])
    more, tail = 0, b""
    for bit, name in enumerate(MORE_FIELDS):
        if name in fields:
            more |= 1 << bit
            tail += num(fields[name])
    if more:
        return bytes([flags | 0x80]) + body + bytes([more]) + tail
    return bytes([flags]) + body


def command_input(scene, commands, warmup=0, queued=False):
    plan = (len(commands) - 1) | (0x80 if queued else 0)
    return bytes([SCENES[scene], warmup, plan]) + b"".join(commands)


STATE_KEYS = ["start", "tilt", "tilt_azimuth", "spin", "angular_velocity_transverse", "position", "velocity", "gap",
              "gap_rate", "rotor_spin", "method", "dt", "rtol", "atol", "max_dt"]


# The keys of write_contact (flag bit i of the third and fourth bytes), after STATE_KEYS; bit 0x8000 of the first
# two bytes announces them.
CONTACT_KEYS = ["shapes", "shape_offset", "shape_radius", "patch_radius", "patch_pressure", "drilling_law",
                "rolling_resistance", "spin_drag", "drag", "kind", "auto_tolerance", "material", "restitution",
                "inertia", "horizon", "static"]
WORDS = {"start": ["tilted", "stationary"], "method": METHODS, "patch_pressure": ["hertz", "uniform"],
         "drilling_law": ["exact", "elliptic"], "kind": ["full", "adiabatic", "auto"]}
HORIZONS = ["1e-3", "1e-2", "1e-1", "1", "10"]


def key_bytes(name, v):
    """One key's value: a word's index, a (pick, number) shape key, shapes, a patch radius, a horizon, numbers."""
    if name in WORDS:
        return bytes([WORDS[name].index(v)])
    if name == "shapes":  # [(kind, offset, radius), ...]
        return bytes([len(v) - 1]) + b"".join(bytes([k == "rim"]) + num(o) + num(r) for k, o, r in v)
    if name in ("shape_offset", "shape_radius"):  # (shape index, value)
        return bytes([v[0]]) + num(v[1])
    if name == "patch_radius":
        return bytes([0]) if v == "hertz" else bytes([1]) + num(v)
    if name == "horizon":
        return bytes([HORIZONS.index(v)])
    if isinstance(v, tuple):
        return num(v[0]) + num(v[1])
    return num(v)


def step_input(scene, **keys):
    """An initial state and integrator settings: two flag bytes, then each given key in STATE_KEYS order; keys of
    CONTACT_KEYS add flag 0x8000, two more flag bytes and their values in CONTACT_KEYS order."""
    flags, body = 0, b""
    for bit, name in enumerate(STATE_KEYS):
        if name in keys:
            flags |= 1 << bit
            body += key_bytes(name, keys[name])
    more, tail = 0, b""
    for bit, name in enumerate(CONTACT_KEYS):
        if name in keys:
            more |= 1 << bit
            tail += key_bytes(name, keys[name])
    if more:
        return bytes([SCENES[scene]]) + struct.pack("<H", flags | 0x8000) + body + struct.pack("<H", more) + tail
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
    # bodies of shapes: friction changes on the tip and crown, the stem, the disc; patch and air fields
    "top_life_friction": command_input("top_life", [command(friction=friction("coulomb", mu="0.5")),
                                                    command(static_friction="0.6")], warmup=32),
    "top_life_table": command_input("top_life", [command(friction=friction("table", points=TABLE))]),
    "top_life_both_friction": command_input("top_life_both", [command(friction=friction("coulomb", mu="0.05"),
                                                                      static_friction="0.1"),
                                                              command(friction=friction("paper"))], warmup=64),
    "stem_friction": command_input("tippe_top_stem", [command(friction=friction("coulomb", mu="0"))]),
    "stem_both_friction": command_input("tippe_top_stem_both", [command(friction=friction("linearized", mu0="0.3",
                                                                                          k="-0.2", s0="0.5")),
                                                                command(spin="-180")], queued=True),
    "contensou_friction": command_input("tippe_top_contensou", [command(friction=friction("coulomb", mu="1"),
                                                                        patch_radius="1e-3")]),
    "euler_disk_friction": command_input("euler_disk", [command(friction=friction("coulomb", mu="0.2")),
                                                        command(rolling_resistance="1e-3", drag="0.1")]),
    "euler_disk_static_bad": command_input("euler_disk", [command(static_friction="0.1")]),
    "spin_down_patch": command_input("spin_down", [command(patch_radius="2e-4"), command(patch_radius="0")]),
    "air": command_input("default", [command(spin_drag="1e-6", drag="1e-3")], warmup=200),
    "air_bad": command_input("top_life", [command(spin_drag="-1", drag="nan")]),
    "auto_refuses_drag": command_input("auto", [command(drag="1e-3"), command(rolling_resistance="1e-6")]),
    "auto_patch": command_input("spin_down_auto", [command(inclination="0.05", spin_drag="1e-7"),
                                                   command(friction=friction("coulomb", mu="0.2"))]),
    "adiabatic_patch": command_input("adiabatic", [command(patch_radius="1e-4")]),
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
    # every other scene as it ships, and the variants
    **{"scene_" + name: step_input(name) for name in SCENES if name not in ("default", "gyro_reversal", "hopping", "ball",
                                                                 "adiabatic", "static")},
    "euler_disk_flat_end": step_input("euler_disk", tilt="2e-4", horizon="10"),
    "euler_disk_long": step_input("euler_disk", horizon="10", rtol="1e-3"),
    "top_life_long": step_input("top_life", horizon="10", rtol="1e-4"),
    "top_life_both_stuck": step_input("top_life_both", spin="0", static="0.5", horizon="1"),
    "top_life_both_spin": step_input("top_life_both", spin="200", horizon="1"),
    "top_life_drop": step_input("top_life", gap="1e-3", restitution="0.5", horizon="1e-1"),
    "stem_both": step_input("tippe_top_stem_both", horizon="1"),
    "stem_longer": step_input("tippe_top_stem", shape_offset=(1, "0.03"), shape_radius=(0, "0.02"), horizon="1"),
    "contensou_exact_hertz": step_input("tippe_top_contensou", drilling_law="exact", patch_pressure="hertz",
                                        patch_radius="1e-3", horizon="1"),
    "rim_only": step_input("default", shapes=[("rim", "0", "0.02")], tilt="0.5", inertia=("1e-6", "1e-6")),
    "sphere_rim": step_input("default", shapes=[("sphere", "-0.01", "1.5e-3"), ("rim", "0.004", "0.02")],
                             tilt="0.6", horizon="1e-1"),
    "three_shapes": step_input("default", shapes=[("sphere", "-0.01", "1e-3"), ("sphere", "0", "1e-3"),
                                                  ("rim", "0.01", "0.01")], inertia=("1e-7", "1e-7")),
    "patch_uniform_elliptic": step_input("default", patch_radius="5e-4", patch_pressure="uniform",
                                         drilling_law="elliptic", horizon="1"),
    "hertz_materials": step_input("default", patch_radius="hertz", material=("2e11", "0.3"), horizon="1e-1"),
    "hertz_bad_material": step_input("default", patch_radius="hertz", material=("2e11", "0.6")),
    "rolling_air": step_input("ball", rolling_resistance="1e-4", spin_drag="1e-6", drag="1e-2", horizon="1"),
    "auto_tolerance": step_input("spin_down_auto", auto_tolerance="1e-6", horizon="10", spin="300"),
    "auto_on_default": step_input("default", kind="auto", auto_tolerance="1e-3", horizon="10"),
    "auto_refuses_rolling": step_input("auto", rolling_resistance="1e-6"),
    "auto_tolerance_bad": step_input("default", auto_tolerance="1e-3"),
    "adiabatic_patch": step_input("adiabatic", patch_radius="1e-4", horizon="10"),
    "shapes_with_auto": step_input("tippe_top_stem", kind="auto"),
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
    # bodies of shapes, patch, air, auto (physics.md sections 12, 13), and this session's view and shape names
    "shapes_everything.yaml": """top:
  mass: 0.025
  inertia_axial: 5.0e-6
  inertia_transverse: 3.0e-6
  young_modulus: 6.9e10
  poisson_ratio: 0.33
  shapes:
    - sphere: {offset: -0.010, radius: 1.5e-3, name: tip}
    - rim: {offset: 0.004, radius: 0.020, name: crown}
friction: {law: coulomb, mu: 0.3, static: 0.4, young_modulus: 3.0e9, poisson_ratio: 0.37}
contact: {patch_radius: hertz, patch_pressure: uniform, drilling_law: elliptic, rolling_resistance: 1.0e-6,
          restitution: 0.2}
air: {spin_drag: 2.5e-7, drag: 1.0e-3}
view: {camera: follow, distance: 0.3, real_time_factor: 0.5}
initial: {tilt: 0.1, spin: 200.0}
events:
  - {t: 0.0001, patch_radius: 1.0e-4, rolling_resistance: 0.0, spin_drag: 0.0, drag: 0.0}
  - {t: 0.0002, friction: {mu: 0.2}, static_friction: 0.3}
""",
    "shapes_view.yaml": "top: {mass: 0.1, inertia_axial: 1e-5, inertia_transverse: 1e-5, "
                        "shapes: [{sphere: {offset: 0, radius: 0.02}}]}\nview: {camera: low, distance: 1}\n",
    "auto_patch.yaml": "top: aluminium\nfriction: pmma\nplane: {inclination: 0.0}\n"
                       "model: {kind: auto, auto_tolerance: 1.0e-5}\ncontact: {patch_radius: hertz}\n"
                       "air: {spin_drag: 1.0e-7}\ninitial: {tilt: 1.0e-4, spin: 100}\n",
    "bad_shape_kind.yaml": "top: {shapes: [{cone: {offset: 0, radius: 1}}]}\n",
    "bad_shape_missing_radius.yaml": "top: {shapes: [{rim: {offset: 0}}]}\n",
    "bad_shapes_and_tip_radius.yaml": "top: {tip_radius: 0.001, shapes: [{sphere: {offset: 0, radius: 1e-3}}]}\n",
    "bad_five_shapes.yaml": "top: {shapes: [" + ", ".join(["{sphere: {offset: 0, radius: 1e-3}}"] * 5) + "]}\n",
    "bad_rim_flat.yaml": "top: {mass: 0.4, inertia_axial: 3e-4, inertia_transverse: 2e-4, "
                         "shapes: [{rim: {offset: 0, radius: 0.04}}]}\ninitial: {tilt: 0}\n",
    "bad_hertz_no_material.yaml": "top: {mass: 0.02}\ncontact: {patch_radius: hertz}\n",
    "bad_auto_tolerance.yaml": "top: aluminium\nmodel: {kind: full, auto_tolerance: 1e-3}\n",
    "bad_auto_rolling.yaml": "top: aluminium\nmodel: {kind: auto}\ncontact: {rolling_resistance: 1e-6}\n",
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
