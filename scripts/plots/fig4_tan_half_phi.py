#!/usr/bin/python3
"""Fig. 4 analogue: tan(phi*/2) against tan(alpha) from top_sim_sweep's CSV files.

usage: fig4_tan_half_phi.py DATA_DIR OUT.png
Reads DATA_DIR/fig4_<top>_<plane>.csv (tilted start) and fig4_<top>_<plane>_launched.csv.
Lines: physics.md's paper-law branches for each plane's (mu_c, s_c) read from the CSV; stable solid,
unstable dashed. Points: measured tan(phi/2) at the end of each run (sleeping, or sliding above alpha_c).
"""
import glob
import os

import numpy as np

from plotlib import command_line, load, paper_branches, plt, save

PLANE_COLOURS = {"pmma": "tab:blue", "steel": "tab:orange"}
TOP_MARKERS = {"aluminium": "o", "steel": "s", "wood": "^"}
TOP_SIZES = {"aluminium": 7.0, "steel": 4.0, "wood": 3.0}  # nested sizes: coinciding points stay visible


def main(data_dir, out):
    files = sorted(glob.glob(os.path.join(data_dir, "fig4_*.csv")))
    if not files:
        raise SystemExit(f"fig4: no fig4_*.csv in {data_dir}")
    fig, ax = plt.subplots(figsize=(7.2, 5.4))
    drawn_planes = set()
    for path in files:
        d = load(path)
        launched = path.endswith("_launched.csv")
        top, plane = d["top"][0], d["plane"][0]
        mu_c, s_c = d["mu_c"][0], d["s_c"][0]
        colour = PLANE_COLOURS.get(plane, "tab:gray")
        if plane not in drawn_planes:
            drawn_planes.add(plane)
            ta = np.linspace(0.0, mu_c, 400)
            stable, unstable = paper_branches(ta, mu_c, s_c)
            ax.plot(ta, stable, "-", color=colour, lw=1.4,
                    label=f"{plane}: stable branch ($\\mu_c$={mu_c:g}, $s_c$={s_c:g})")
            keep = unstable <= 1.0
            ax.plot(ta[keep], unstable[keep], "--", color=colour, lw=1.2, label=f"{plane}: unstable branch")
            ax.plot([mu_c], [s_c], "*", color=colour, ms=9)
        sleeping = np.array([o == "sleeping" for o in d["outcome"]])
        sliding = np.array([o == "sliding" for o in d["outcome"]])
        marker = TOP_MARKERS.get(top, "D")
        face = "none" if launched else colour
        start = "launched" if launched else "at rest"
        size = 9.0 if launched else TOP_SIZES.get(top, 4.0)
        ax.plot(d["tan_alpha"][sleeping], d["tan_half_phi_measured"][sleeping], marker, ls="none", ms=size,
                mfc=face, mec=colour, label=f"{top} on {plane}, {start}: sleeping")
        if sliding.any():
            ax.plot(d["tan_alpha"][sliding], d["tan_half_phi_measured"][sliding], "x", ls="none", ms=5,
                    color=colour, alpha=0.8 if not launched else 0.4)
        other = ~(sleeping | sliding)
        if other.any():
            ax.plot(d["tan_alpha"][other], d["tan_half_phi_measured"][other], "?", ls="none", color="k")
    ax.axhline(1.0, color="k", ls=":", lw=1.0, label="supercritical asymptote tan($\\varphi$/2) = 1")
    ax.plot([], [], "x", color="k", ls="none", label="sliding (direction after 30 s)")
    ax.set_xlabel(r"tan $\alpha$")
    ax.set_ylabel(r"tan($\varphi^*$/2)")
    ax.set_xlim(0.0, 0.36)
    ax.set_ylim(0.0, 1.05)
    ax.set_title("Fig. 4 analogue: sleeping direction against inclination (200 rad/s)")
    ax.legend(fontsize=6.5, loc="lower right", ncol=1, framealpha=0.9)
    save(fig, out, "fig4")


if __name__ == "__main__":
    command_line(main, __doc__)
