#!/usr/bin/python3
"""top_sim_fit stationary --plot: the measured points on mu(s) and the fitted law.

usage: fit_stationary.py POINTS.csv CURVE.csv OUT.png [LABEL]
POINTS.csv: s, y (= tan alpha), sigma_s, sigma_y, mirrored (1: negative spin, phi mapped to pi - phi).
CURVE.csv: s, mu of the fitted law (before the clamp at 0).
"""

import numpy as np

from plotlib import command_line, load, plt, save


def main(points, curve, out, label="fit"):
    p, c = load(points), load(curve)
    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    mirrored = p["mirrored"] > 0.5
    for mask, name, marker in ((~mirrored, "measured (spin > 0)", "o"), (mirrored, "measured, mirrored (spin < 0)", "s")):
        if np.any(mask):
            ax.errorbar(p["s"][mask], p["y"][mask], xerr=p["sigma_s"][mask], yerr=p["sigma_y"][mask], fmt=marker,
                        ms=3.5, lw=0.8, capsize=1.5, label=name)
    keep = c["mu"] >= -0.02
    ax.plot(c["s"][keep], c["mu"][keep], "k-", lw=1.2, label=label)
    ax.set_xlabel("s = tan(phi*/2)")
    ax.set_ylabel("mu = tan(alpha)")
    ax.set_xlim(0.0, 1.0)
    ax.set_ylim(bottom=0.0)
    ax.legend(fontsize=7)
    save(fig, out)


if __name__ == "__main__":
    command_line(main, __doc__, (3, 4))
