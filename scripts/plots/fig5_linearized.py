#!/usr/bin/python3
"""Fig. 5 analogue: r_cm(t), v_cm(t) and f f_hat(t) of the aluminium top on PMMA at alpha 0.1 with the
linearized law (k = 1), coloured by the simulated second (red, green, red, ...), and the direction of
travel relaxing to phi* over the whole 600 s run.

usage: fig5_linearized.py DATA_DIR OUT.png
Reads DATA_DIR/fig5_linearized_60s.csv and fig5_linearized_600s.csv (from top_sim_run, thinned).
"""
import math

import numpy as np

from plotlib import by_second, command_line, load, plt, save

ALPHA, MU0, S0, K = 0.1, math.tan(0.1), 0.13576075974024854, 1.0  # config/scenes/fig5_linearized.yaml
COM_OFFSET = 0.010  # f of config/tops/aluminium.yaml [m]


def main(data_dir, out):
    d = load(f"{data_dir}/fig5_linearized_60s.csv")
    long = load(f"{data_dir}/fig5_linearized_600s.csv")
    phi_star = 2.0 * math.atan(S0)  # mu(s*) = tan(alpha) at s* = s0 (physics.md section 5)
    t = d["t"]
    fig, axes = plt.subplots(2, 2, figsize=(10, 8))
    (a, b), (c, e) = axes

    by_second(a, t, d["com_x"], d["com_y"], lw=0.8)
    span = np.hypot(d["com_x"][-1] - d["com_x"][0], d["com_y"][-1] - d["com_y"][0])
    a.plot([d["com_x"][0], d["com_x"][0] + span * math.cos(phi_star)],
           [d["com_y"][0], d["com_y"][0] - span * math.sin(phi_star)], "k--", lw=0.8,
           label=f"$\\varphi^*$ = 2 atan(s*) = {phi_star:.4f} rad")
    a.set_aspect("equal", adjustable="datalim")
    inset = a.inset_axes([0.08, 0.08, 0.42, 0.42])  # the first 5 s: nutation, then the precession loops
    first = t <= 5.0
    by_second(inset, t[first], d["com_x"][first], d["com_y"][first], lw=0.8)
    inset.set_aspect("equal", adjustable="datalim")
    inset.set_title("first 5 s", fontsize=7)
    inset.tick_params(labelsize=6)
    a.set_xlabel("x (horizontal) [m]")
    a.set_ylabel("y (uphill) [m]")
    a.set_title(r"a) centre of mass $\mathbf{r}_{cm}(t)$, plane frame, first 60 s")
    a.legend(fontsize=8, loc="upper right")

    by_second(b, t, d["vcm_x"], d["vcm_y"], lw=0.6)
    b.plot([0], [0], "k+")
    b.set_aspect("equal", adjustable="datalim")
    b.set_xlabel(r"$v_{cm,x}$ [m/s]")
    b.set_ylabel(r"$v_{cm,y}$ [m/s]")
    b.set_title(r"b) centre-of-mass velocity $\mathbf{v}_{cm}(t)$ (hodograph)")

    by_second(c, t, COM_OFFSET * d["f_x"], COM_OFFSET * d["f_y"], lw=0.6)
    c.plot([0], [0], "k+")
    c.set_aspect("equal", adjustable="datalim")
    c.set_xlabel(r"$f\,\hat f_x$ [m]")
    c.set_ylabel(r"$f\,\hat f_y$ [m]")
    c.set_title(r"c) figure axis $f\hat{\mathbf{f}}(t)$, in-plane components")

    # Envelope: the largest deviation in each 10 s block (2 Hz samples alias the ~5 s precession).
    dev = np.abs(long["phi"] - phi_star)
    block = np.floor(long["t"] / 10.0).astype(int)
    tb = np.array([long["t"][block == k].mean() for k in np.unique(block)])
    db = np.array([dev[block == k].max() for k in np.unique(block)])
    e.semilogy(tb, np.maximum(db, 1e-12), "o-", color="tab:blue", ms=2.5, lw=0.8)
    e.set_xlabel("t [s]")
    e.set_ylabel(r"max |$\varphi(t) - \varphi^*$| per 10 s [rad]")
    e.set_title(r"d) direction of travel relaxing to $\varphi^*$ (whole 600 s run)")
    fig.suptitle("Fig. 5 analogue: aluminium top on PMMA, alpha = 0.1 rad, 200 rad/s, tilted 0.1 rad at rest; "
                 f"linearized law mu(s) = {MU0:.4f} + {K:g} (s - {S0:.4f})\n"
                 "panels a-c: first 60 s, one colour per simulated second (red, green, red, ...)", fontsize=10)
    save(fig, out, "fig5")


if __name__ == "__main__":
    command_line(main, __doc__)
