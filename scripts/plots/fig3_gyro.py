#!/usr/bin/python3
"""Fig. 3 analogue: the gyroscope-loaded top (config/scenes/gyro_reversal.yaml) whose shell spin the rotor
drags through zero: the path flips from pi - phi* to phi* while the top keeps going downhill.

usage: fig3_gyro.py DATA_DIR OUT.png
Reads DATA_DIR/fig3_gyro_reversal.csv (top_sim_run, 50 samples per second).
"""
import math

import numpy as np

from plotlib import command_line, load, paper_phi_star, plt, save

ALPHA, MU_C, S_C = 0.07, 0.25, 0.6  # config/scenes/gyro_reversal.yaml (PMMA)


def main(data_dir, out):
    d = load(f"{data_dir}/fig3_gyro_reversal.csv")
    phi_star = paper_phi_star(ALPHA, MU_C, S_C)
    t, x, y, spin = d["t"], d["contact_x"], d["contact_y"], d["spin"]
    flip = int(np.argmax(spin >= 0.0))
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(14, 4.6), gridspec_kw={"width_ratios": [1.3, 1, 1]})

    neg, pos = spin < 0.0, spin >= 0.0
    a.plot(1e3 * x[neg], 1e3 * y[neg], color="tab:blue", lw=1.5, label="shell spin < 0")
    a.plot(1e3 * x[pos], 1e3 * y[pos], color="tab:red", lw=1.5, label="shell spin > 0")
    a.plot(1e3 * x[flip], 1e3 * y[flip], "ko", ms=5, label=f"shell spin = 0 at t = {t[flip]:.2f} s")
    L = 1e3 * 0.025
    a.plot([1e3 * x[flip], 1e3 * x[flip] - L * math.cos(math.pi - phi_star)],
           [1e3 * y[flip], 1e3 * y[flip] + L * math.sin(math.pi - phi_star)], "k--", lw=0.7,
           label=r"analytic $\pi - \varphi^*$ (before) and $\varphi^*$ (after)")
    a.plot([1e3 * x[flip], 1e3 * x[flip] + 3 * L * math.cos(phi_star)],
           [1e3 * y[flip], 1e3 * y[flip] - 3 * L * math.sin(phi_star)], "k--", lw=0.7)
    a.set_xlabel("x (horizontal) [mm]")
    a.set_ylabel("y (uphill) [mm]")
    a.set_title("a) contact-point path, 60 s from the origin (y stretched x3)")
    a.set_aspect(3.0, adjustable="datalim")
    a.legend(fontsize=7, loc="upper right")

    b.plot(t, spin, color="tab:purple", lw=1.2, label=r"shell spin $\omega\cdot\hat f$")
    b.axhline(0.0, color="k", lw=0.6)
    b.set_xlabel("t [s]")
    b.set_ylabel("shell spin [rad/s]")
    b2 = b.twinx()
    b2.plot(t, d["rotor_spin"], color="tab:gray", lw=1.0, ls="--", label=r"rotor spin $\Omega$")
    b2.set_ylabel("rotor spin [rad/s]")
    b2.grid(False)
    b.legend(handles=b.get_lines()[:1] + b2.get_lines(), fontsize=7, loc="center right")
    b.set_title("b) the bearing drags the shell spin through zero")

    c.plot(t, d["phi"], color="tab:blue", lw=1.0, label=r"$\varphi(t)$ (direction of travel)")
    c.axhline(math.pi - phi_star, color="k", ls="--", lw=0.7, label=rf"$\pi - \varphi^*$ = {math.pi - phi_star:.4f}")
    c.axhline(phi_star, color="k", ls=":", lw=0.9, label=rf"$\varphi^*$ = {phi_star:.4f}")
    c.axhline(math.pi / 2, color="tab:gray", lw=0.5)
    c.set_xlabel("t [s]")
    c.set_ylabel(r"$\varphi$ [rad]")
    c.set_title(r"c) direction of travel: $\pi - \varphi^*$ flips to $\varphi^*$")
    c.legend(fontsize=7, loc="center right")
    c.text(0.04, 0.3, f"downhill velocity never reverses:\nmax u_y over the run = {d['u_y'].max():.1e} m/s < 0",
           transform=c.transAxes, fontsize=7, va="center")
    fig.suptitle("Fig. 3 analogue: gyroscope-loaded aluminium top on PMMA, alpha = 0.07 rad; rotor J = 2e-6 kg m$^2$, "
                 "c = 1.5e-9 N m s, shell -20 rad/s, rotor +2000 rad/s, started asleep", fontsize=10)
    save(fig, out, "fig3")


if __name__ == "__main__":
    command_line(main, __doc__)
