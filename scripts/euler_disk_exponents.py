#!/usr/bin/env python3
"""Late-time exponents of a disc's run to its flat end (physics.md 13; Moffatt 2000: beta ~ tau^(1/3), Omega ~ tau^(-1/6)).

Reads top_sim_run's CSV (--csv) and the end time t0 (the summary's sim_seconds, ended lying_flat); fits
log beta and log Omega against log tau, tau = t0 - t, over the samples with beta in [BETA_LO, BETA_HI]. Omega is the
contact point's circling rate about the centre of mass (the unwrapped angle of contact - com, differenced). Also
prints the powers of the dissipations at a few instants: rolling resistance delta N |omega_r|, air k |omega|^2 + c |v|^2.
usage: euler_disk_exponents.py CSV T0 [--delta D] [--spin-drag K] [--drag C] [--beta-range LO HI]
"""
import argparse
import csv
import math

import numpy as np


def main():
    p = argparse.ArgumentParser()
    p.add_argument("csv")
    p.add_argument("t0", type=float)
    p.add_argument("--delta", type=float, default=0.0)
    p.add_argument("--spin-drag", type=float, default=0.0)
    p.add_argument("--drag", type=float, default=0.0)
    p.add_argument("--beta-range", type=float, nargs=2, default=[1e-3, 3e-2])
    a = p.parse_args()
    rows = list(csv.DictReader(open(a.csv)))
    t = np.array([float(r["t"]) for r in rows])
    beta = np.array([math.acos(min(1.0, float(r["f_z"]))) for r in rows])
    ang = np.unwrap([math.atan2(float(r["contact_y"]) - float(r["com_y"]), float(r["contact_x"]) - float(r["com_x"]))
                     for r in rows])
    omega = np.abs(np.gradient(ang, t))
    tau = a.t0 - t
    sel = (beta > a.beta_range[0]) & (beta < a.beta_range[1]) & (tau > 0)
    if sel.sum() < 10:
        raise SystemExit(f"only {sel.sum()} samples with beta in {a.beta_range}")
    kb, _ = np.polyfit(np.log(tau[sel]), np.log(beta[sel]), 1)
    ko, _ = np.polyfit(np.log(tau[sel]), np.log(omega[sel]), 1)
    print(f"samples {sel.sum()}, tau in [{tau[sel].min():.3g}, {tau[sel].max():.3g}] s")
    print(f"beta  ~ tau^{kb:.3f}   (Moffatt 1/3)")
    print(f"Omega ~ tau^{ko:.3f}   (Moffatt -1/6)")
    print("t [s], beta, Omega [rad/s], P_rolling [W], P_air [W]")
    for i in np.linspace(0, len(rows) - 2, 8).astype(int):
        r = rows[i]
        w = np.array([float(r[k]) for k in ("omega_x", "omega_y", "omega_z")])
        v = np.array([float(r[k]) for k in ("vcm_x", "vcm_y", "vcm_z")])
        p_roll = a.delta * float(r["N"]) * math.hypot(w[0], w[1])
        p_air = a.spin_drag * w.dot(w) + a.drag * v.dot(v)
        print(f"{t[i]:.2f}, {beta[i]:.4g}, {omega[i]:.4g}, {p_roll:.3g}, {p_air:.3g}")


if __name__ == "__main__":
    main()
