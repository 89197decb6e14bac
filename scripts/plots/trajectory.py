#!/usr/bin/python3
"""top_sim_bag --plot: one trajectory in top_sim_run's CSV columns: the contact point's path on the plane, the
direction of travel phi(t) against phi*, and the energy-balance residual against t.

usage: trajectory.py DATA.csv OUT.png [--phi-star PHI] [--title TEXT]
DATA.csv: top_sim_run --csv or top_sim_bag --csv (columns t, contact_x, contact_y, phi, energy_residual).
"""
import argparse

import numpy as np

from plotlib import continuous_angle, levels_in, load, plt


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("data")
    p.add_argument("out")
    p.add_argument("--phi-star", type=float, default=None, help="analytic sleeping-state angle [rad]")
    p.add_argument("--title", default="")
    a = p.parse_args(argv)
    d = load(a.data)
    t = d["t"]
    fig, (path, phi, energy) = plt.subplots(1, 3, figsize=(13.0, 4.0))
    path.plot(1e3 * d["contact_x"], 1e3 * d["contact_y"], lw=0.8)
    path.plot(1e3 * d["contact_x"][:1], 1e3 * d["contact_y"][:1], "o", ms=4, label=f"t = {t[0]:.3f} s")
    path.plot(1e3 * d["contact_x"][-1:], 1e3 * d["contact_y"][-1:], "s", ms=4, label=f"t = {t[-1]:.3f} s")
    path.set_aspect("equal", adjustable="datalim")
    path.set_xlabel("contact x (horizontal) [mm]")
    path.set_ylabel("contact y (uphill) [mm]")
    path.set_title("contact point on the plane")
    path.legend(fontsize=7)
    # Unwrapped: a direction near +-pi (a negative-spin top) would otherwise jump the full height at each wrap.
    angle = continuous_angle(d["phi"])
    phi.plot(t, angle, lw=0.8, label="phi (direction of travel, unwrapped)")
    if a.phi_star is not None:
        for i, level in enumerate(levels_in(angle, a.phi_star)):
            phi.axhline(level, color="k", ls="--", lw=1.0, label=f"phi* = {a.phi_star:.6f}" if i == 0 else None)
    phi.set_xlabel("t [s]")
    phi.set_ylabel("phi [rad]")
    phi.set_title("phi(t) against phi*")
    phi.legend(fontsize=7)
    residual = np.abs(d["energy_residual"])
    positive = residual > 0  # log axis: exact zeros (at re-bases) are left out
    energy.semilogy(t[positive], residual[positive], lw=0.8)
    energy.set_xlabel("t [s]")
    energy.set_ylabel("|E + W_diss - (E + W_diss)_0| / E_scale")
    energy.set_title("energy-balance residual")
    if a.title:
        fig.suptitle(a.title, fontsize=9)
    fig.tight_layout()
    fig.savefig(a.out)


if __name__ == "__main__":
    main()
