#!/usr/bin/env python3
"""Plots of peer_mujoco --tippe-top and --euler-disk (their --csv files): docs/img/mujoco_tippe_top.png and
docs/img/mujoco_euler_disk.png.

usage: plot_mujoco_shapes.py TIPPE_CSV DISK_CSV OUT_DIR
"""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path, key):
    """Rows of a CSV grouped by the columns `key` (a tuple of names)."""
    groups = defaultdict(list)
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            groups[tuple(row[k] for k in key)].append(row)
    return groups


def tippe(path, out):
    fig, ax = plt.subplots(figsize=(7, 4), dpi=120)
    for (dt,), rows in sorted(read(path, ("dt",)).items(), key=lambda kv: -float(kv[0][0])):
        ax.plot([float(r["t"]) for r in rows], [float(r["tilt"]) for r in rows], label=f"dt {dt} s", lw=1)
    ax.axhline(math.pi / 2, color="grey", lw=0.5, ls="--")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("tilt of the figure axis from the vertical [rad]")
    ax.set_title("MuJoCo 2.2.2: the tutorial tippe top (RK4, solref 0.02 1)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out)


def disk(path, out):
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), dpi=120, sharex=True)
    for (friction, dt), rows in sorted(read(path, ("friction", "dt")).items()):
        t = [float(r["t"]) for r in rows]
        a1.plot(t, [float(r["beta"]) for r in rows], label=f"{friction}, dt {dt} s", lw=1)
        a2.plot(t, [abs(float(r["circling_rate"])) for r in rows], lw=1)
    a1.set_ylabel("beta, disc to plane [rad]")
    a1.set_title("MuJoCo 2.2.2: Euler's disk from steady rolling at beta 0.5 rad (condim 6)")
    a1.legend(fontsize=8)
    a2.set_ylabel("contact circling rate [rad/s]")
    a2.set_xlabel("t [s]")
    a2.set_xlim(0, 6)
    fig.tight_layout()
    fig.savefig(out)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    tippe(sys.argv[1], f"{sys.argv[3]}/mujoco_tippe_top.png")
    disk(sys.argv[2], f"{sys.argv[3]}/mujoco_euler_disk.png")


if __name__ == "__main__":
    main()
