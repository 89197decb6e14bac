#!/usr/bin/python3
"""The tippe top's tilt against time (docs/physics.md section 11): Cohen's sphere (config/scenes/tippe_top.yaml,
I_f = I_d) turns over towards pi; the prolate one (tippe_top_tumbling.yaml, I_f = 0.8 I_d) settles tumbling at the
tilt Jellett's integral fixes. Panel b: the contact's relative slip, which the final states drive to zero.

usage: tippe_top_tilt.py DATA_DIR OUT.png
Reads DATA_DIR/tippe_top.csv and DATA_DIR/tippe_top_tumbling.csv (top_sim_run --csv, columns t, f_z, omega_z,
spin, s, regime; the tilt is acos(f_z)).
"""
import math

import numpy as np

from plotlib import command_line, load, plt, save

# The two scenes' sphere (config/scenes/tippe_top*.yaml): m, g, R, f, I_d; I_f per scene.
M, G, R, F, I_D = 0.015, 9.81, 0.025, -0.005, 3.75e-6
SCENES = (("tippe_top", 3.75e-6, "tab:blue", r"tippe_top.yaml: $I_f = I_d$"),
          ("tippe_top_tumbling", 3.0e-6, "tab:red", r"tippe_top_tumbling.yaml: $I_f = 0.8\,I_d$"))
GLIDING_SLIP = 2e-3  # kTippeGlidingSlip (include/top_sim/regime.hpp)


def jellett(d, i_f):
    """lambda = L . (R n + f f_hat) at the first row (L about the centre of mass, n = e_z)."""
    fz, w3, wz = d["f_z"][0], d["spin"][0], d["omega_z"][0]
    # L . n = I_d omega_z + (I_f - I_d) omega3 f_z;  L . f_hat = I_f omega3
    return R * (I_D * wz + (i_f - I_D) * w3 * fz) + F * i_f * w3


def steady_lambda(c, i_f):
    """physics.md section 11: lambda of the gliding-free state at cos(theta) = c (nan where none exists)."""
    den = (i_f - I_D) * R * c + i_f * F
    omega2 = np.where(den * F > 0, M * G * F * R / np.where(den == 0, np.nan, den), np.nan)
    return np.sqrt(omega2) / R * (I_D * R * R * (1 - c * c) + i_f * (R * c + F) ** 2)


def tumbling_tilt(lam, i_f):
    """The tilt of the tumbling state with this lambda, or None (bisection-free: a fine grid, then linear)."""
    c = np.linspace(-1.0, 1.0, 200001)
    gap = steady_lambda(c, i_f) - lam
    idx = np.nonzero(np.isfinite(gap[:-1]) & np.isfinite(gap[1:]) & (np.sign(gap[:-1]) != np.sign(gap[1:])))[0]
    if len(idx) == 0:
        return None
    k = idx[0]
    return math.acos(c[k] - gap[k] * (c[k + 1] - c[k]) / (gap[k + 1] - gap[k]))


def main(data_dir, out):
    fig, (a, b) = plt.subplots(1, 2, figsize=(13, 4.6))
    for name, i_f, colour, label in SCENES:
        d = load(f"{data_dir}/{name}.csv")
        t, tilt = d["t"], np.arccos(np.clip(d["f_z"], -1.0, 1.0))
        a.plot(t, tilt, color=colour, lw=0.8, label=label)
        b.semilogy(t, np.maximum(d["s"], 1e-7), color=colour, lw=0.6, label=label)
        theta = tumbling_tilt(jellett(d, i_f), i_f)
        if theta is None:
            a.axhline(math.pi, color=colour, ls="--", lw=0.8, label=r"inverted: $\theta = \pi$ (no tumbling state)")
        else:
            a.axhline(theta, color=colour, ls="--", lw=0.8, label=rf"tumbling state from $\lambda$: {theta:.4f} rad")
        tumbling = [x for x, r in zip(t, d["regime"]) if r == "tumbling"]
        if tumbling:
            a.axvline(tumbling[0], color=colour, ls=":", lw=0.8, label=f"regime 'tumbling' from {tumbling[0]:.2f} s")
    a.axhline(math.pi / 2, color="k", lw=0.5)
    a.set_xlabel("t [s]")
    a.set_ylabel(r"tilt $\theta$ = angle of $\hat f$ from the vertical [rad]")
    a.set_ylim(0.0, 3.3)
    a.set_title("a) tilt against time (the width of the curves: nutation; red +-0.04 rad at 8.7 Hz)")
    a.legend(fontsize=7, loc="lower right")
    b.axhline(GLIDING_SLIP, color="k", ls="--", lw=0.7, label="s = 2e-3: regime tumbling below it (for 0.5 < tilt < pi - 0.5)")
    b.set_xlabel("t [s]")
    b.set_ylabel("relative slip s of the contact")
    b.set_title("b) slip (0 while the contact rolls, drawn at 1e-7)")
    b.legend(fontsize=7, loc="upper right")
    fig.suptitle("Tippe top: Cohen's sphere (R 2.5 cm, f = -0.5 cm, m 15 g, Coulomb 0.3 regularised at 1 cm/s, "
                 "100 rad/s from 0.1 rad) and its prolate variant", fontsize=10)
    save(fig, out, "tippe_top_tilt")


if __name__ == "__main__":
    command_line(main, __doc__)
