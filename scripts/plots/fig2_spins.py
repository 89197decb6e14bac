#!/usr/bin/python3
"""Fig. 2 analogue: the aluminium top on steel at alpha 0.09 started at 100, 200 and 400 rad/s.

usage: fig2_spins.py DATA_DIR OUT.png
Reads DATA_DIR/fig2_spin{100,200,400}.csv (top_sim_run on config/scenes/fig2_spin*.yaml, thinned).
a) the raw contact-point paths: all leave at the same phi*, but the relaxation wiggles grow with the spin;
b) the same paths with lengths scaled by (200/spin)^2: one curve;
c) the deviation of the direction of travel from phi* against time scaled by 200/spin: one curve.
"""

import numpy as np

from plotlib import command_line, load, paper_phi_star, plt, save

ALPHA, MU_C, S_C = 0.09, 0.20, 0.7  # config/scenes/fig2_spin*.yaml, config/planes/steel.yaml
SPINS = (100, 200, 400)
COLOURS = {100: "tab:blue", 200: "tab:orange", 400: "tab:green"}
STYLES = {100: "-", 200: "--", 400: ":"}


def main(data_dir, out):
    phi_star = paper_phi_star(ALPHA, MU_C, S_C)
    runs = {w: load(f"{data_dir}/fig2_spin{w}.csv") for w in SPINS}
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(14, 4.6))
    for w, d in runs.items():
        x, y = d["contact_x"], d["contact_y"]
        keep = x <= 3.0
        a.plot(x[keep], y[keep], STYLES[w], color=COLOURS[w], lw=1.0, label=f"{w} rad/s")
        k = (200.0 / w) ** 2
        keep = x * k <= 0.8
        b.plot(k * x[keep], k * y[keep], STYLES[w], color=COLOURS[w], lw=1.2, label=f"{w} rad/s, x (200/{w})$^2$")
        # Envelope of |phi - phi*| per block of 5 scaled seconds (the samples alias the precession).
        ts = d["t"] * 200.0 / w
        dev = np.abs(d["phi"] - phi_star)
        block = np.floor(ts / 5.0).astype(int)
        ids = np.unique(block)
        c.semilogy([ts[block == i].mean() for i in ids], [max(dev[block == i].max(), 1e-12) for i in ids],
                   STYLES[w], color=COLOURS[w], lw=1.2, label=f"{w} rad/s")
    for ax, span in ((a, 3.0), (b, 0.8)):
        ax.plot([0, span], [0, -span * np.tan(phi_star)], color="k", lw=0.6, alpha=0.6,
                label=f"direction $\\varphi^*$ = {phi_star:.4f} rad (analytic)")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x (horizontal) [m]")
        ax.set_ylabel("y (uphill) [m]")
        ax.legend(fontsize=7, loc="lower left")
    a.set_title("a) contact-point paths (first 3 m horizontally)")
    b.set_title(r"b) the same, lengths scaled by (200 / spin)$^2$ (first 0.8 m)")
    c.set_xlabel("t x 200 / spin [s]")
    c.set_ylabel(r"max |$\varphi - \varphi^*$| per 5 scaled s [rad]")
    c.set_title("c) relaxation against time scaled by the spin")
    c.legend(fontsize=7)
    fig.suptitle("Fig. 2 analogue: aluminium top on steel, alpha = 0.09 rad, started tilted 0.1 rad at rest: "
                 "phi* does not depend on the spin; relaxation time ~ spin, relaxation path ~ spin$^2$", fontsize=10)
    save(fig, out, "fig2")


if __name__ == "__main__":
    command_line(main, __doc__)
