#!/usr/bin/env python3
"""Compares two top_sim_run builds' JSON summaries of every shipped scene, value by value.

    python3 scripts/compare_summaries.py BASE_BIN NEW_BIN [SCENE.yaml ...]

Runs `BIN SCENE --summary -` for each scene (default: config/scenes/*.yaml) with both binaries, parses both with
Python's json and requires the same keys in the same order, the same strings, nulls and booleans, and every number
the same double in every bit (so -0.0 differs from 0.0). The text may differ (e.g. 17 significant digits against
the shortest text that reads back as the same double); the values may not. cpu_seconds and real_time_factor are
wall-clock measurements, so only their presence is compared. Exit 0 when every scene matches, 1 otherwise.
"""

import glob
import json
import math
import os
import struct
import subprocess
import sys

TIMINGS = {"cpu_seconds", "real_time_factor"}  # measured, different on every run


def summary(binary, scene):
    """The parsed summary of `binary` on `scene`; the run's exit status may be 0 or 3 (a contact fault)."""
    run = subprocess.run([binary, scene, "--summary", "-", "--quiet"], capture_output=True, text=True, check=False)
    if run.returncode not in (0, 3):
        raise RuntimeError("%s %s: exit %d: %s" % (binary, scene, run.returncode, run.stderr.strip()))
    return json.loads(run.stdout, object_pairs_hook=list)


def same_double(a, b):
    return struct.pack("<d", float(a)) == struct.pack("<d", float(b)) or (math.isnan(a) and math.isnan(b))


def differences(a, b, where="$"):
    """Where `a` and `b` differ, as text lines (none when they are equal in value, key order and every bit)."""
    number = (int, float)
    if isinstance(a, number) and isinstance(b, number) and not isinstance(a, bool) and not isinstance(b, bool):
        return [] if same_double(a, b) else ["%s: %r != %r" % (where, a, b)]
    if type(a) is not type(b):
        return ["%s: %r != %r" % (where, a, b)]
    if not isinstance(a, list):
        return [] if a == b else ["%s: %r != %r" % (where, a, b)]
    is_object = all(isinstance(x, tuple) for x in a + b)
    if not is_object:
        if len(a) != len(b):
            return ["%s: %d items != %d" % (where, len(a), len(b))]
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, "%s[%d]" % (where, i))]
    keys_a, keys_b = [k for k, _ in a], [k for k, _ in b]
    if keys_a != keys_b:
        return ["%s: keys %s != %s" % (where, keys_a, keys_b)]
    out = []
    for (key, x), (_, y) in zip(a, b):
        if where == "$" and key in TIMINGS:
            continue
        out += differences(x, y, "%s.%s" % (where, key))
    return out


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    base, new = argv[1], argv[2]
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    scenes = argv[3:] or sorted(glob.glob(os.path.join(root, "config", "scenes", "*.yaml")))
    failed = 0
    for scene in scenes:
        found = differences(summary(base, scene), summary(new, scene))
        name = os.path.basename(scene)
        print("%-40s %s" % (name, "identical values" if not found else "DIFFERS"))
        for line in found[:20]:
            print("    " + line)
        failed += bool(found)
    print("%d of %d scenes with identical values" % (len(scenes) - failed, len(scenes)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
