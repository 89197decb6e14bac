#!/usr/bin/python3
"""The wake-up (docs/results.md "The wake-up"): config/scenes/spin_down.yaml, the aluminium top on a level PMMA
plane with a Hertz patch, spins down; its small tilt dies while the spin is above the upright state's critical spin
(top_sim_stability --state upright --sweep-spin) and grows below it, until the top falls (the `fallen` fault).

usage: spin_down.py RUN.csv CRITICAL_SPIN MAXWELL_KLEIN OUT.png [PASSAGE_ZERO]
RUN.csv: top_sim_run --csv (columns t, f_z, spin; the tilt is acos(f_z)). CRITICAL_SPIN, MAXWELL_KLEIN and
PASSAGE_ZERO (the zero of passage_growth_rate at the run's spin-down rate) in rad/s.
Panel a: spin against time, the critical spin and the frictionless Maxwell-Klein limit marked; panel b: the tilt
(log scale) with its window growth rate d ln(tilt)/dt (right axis), the crossing and the tilt 0.5 rad marked.
"""
import numpy as np

from plotlib import command_line, load, plt, save

WINDOW = 2.0      # [s] growth-rate window: many precession periods (about 0.2 s near the crossing) per window
FALL_TILT = 0.5   # [rad] the "visible fall"


def window_growth(t, tilt):
    """d ln(tilt)/dt between consecutive windows' largest tilts (the envelope: nutation and precession averaged)."""
    edges = np.arange(t[0], t[-1], WINDOW)
    mids, peaks = [], []
    for lo in edges:
        inside = (t >= lo) & (t < lo + WINDOW)
        if inside.sum() > 2:
            mids.append(lo + WINDOW / 2)
            peaks.append(tilt[inside].max())
    mids, peaks = np.array(mids), np.log(np.array(peaks))
    return 0.5 * (mids[1:] + mids[:-1]), np.diff(peaks) / np.diff(mids)


def main(csv, critical, maxwell_klein, out, passage_zero="nan"):
    critical, maxwell_klein = float(critical), float(maxwell_klein)
    d = load(csv)
    t, spin, tilt = d["t"], d["spin"], np.arccos(np.clip(d["f_z"], -1.0, 1.0))
    t_cross = t[np.argmax(spin < critical)]          # the spin passes the critical spin
    t_fall = t[np.argmax(tilt > FALL_TILT)]          # the visible fall
    tg, growth = window_growth(t, tilt)
    fig, (a, b) = plt.subplots(2, 1, figsize=(7.5, 7.0), sharex=True)
    a.plot(t, spin, color="tab:blue", lw=1.2, label="spin omega . f_hat (simulated)")
    a.axhline(critical, color="tab:red", ls="--", lw=1.0, label=f"critical spin (top_sim_stability) {critical:.4g} rad/s")
    a.axhline(maxwell_klein, color="0.4", ls=":", lw=1.0, label=f"frictionless Maxwell-Klein {maxwell_klein:.4g} rad/s")
    for ax in (a, b):
        ax.axvline(t_cross, color="tab:red", lw=0.8, alpha=0.6)
        ax.axvline(t_fall, color="k", lw=0.8, alpha=0.6)
    if not np.isnan(float(passage_zero)):
        a.axhline(float(passage_zero), color="tab:purple", ls=":", lw=1.0,
                  label=f"zero of the slow passage's rate {float(passage_zero):.4g} rad/s")
    a.set_ylabel("spin [rad/s]")
    a.set_title("a) spin-down on a Hertz patch (config/scenes/spin_down.yaml)")
    a.legend(fontsize=8)
    b.semilogy(t, tilt, color="tab:green", lw=0.8, label="tilt acos(f_z) [rad]")
    b.axhline(FALL_TILT, color="k", ls="--", lw=0.8)
    b.set_ylabel("tilt [rad] (log)")
    b.set_xlabel("t [s]")
    b.set_title(f"b) tilt; crossing at t = {t_cross:.1f} s (red), tilt {FALL_TILT} rad at t = {t_fall:.1f} s "
                f"(delay {t_fall - t_cross:.1f} s)")
    g = b.twinx()
    g.plot(tg, growth, ".", ms=2.5, color="tab:purple", label=f"d ln(tilt)/dt over {WINDOW:g} s windows [1/s]")
    g.axhline(0.0, color="tab:purple", lw=0.6)
    g.set_ylabel("growth rate [1/s]", color="tab:purple")
    g.set_yscale("symlog", linthresh=1e-3)  # the rates near the crossing are 1e-3 1/s, at the fall 0.3
    turn = np.flatnonzero(growth <= 0.0)
    if turn.size and turn[-1] + 1 < growth.size:  # the rate turns positive for good: the simulated crossing
        t_turn = tg[turn[-1]] + (tg[turn[-1] + 1] - tg[turn[-1]]) * -growth[turn[-1]] / (growth[turn[-1] + 1] - growth[turn[-1]])
        w_turn = np.interp(t_turn, t, spin)
        for ax in (a, b):
            ax.axvline(t_turn, color="tab:purple", ls="--", lw=0.8)
        a.plot([t_turn], [w_turn], "o", mfc="none", mec="tab:purple",
               label=f"tilt starts to grow (simulated) at {w_turn:.4g} rad/s")
        a.legend(fontsize=8)
    lines = b.get_legend_handles_labels(), g.get_legend_handles_labels()
    b.legend(lines[0][0] + lines[1][0], lines[0][1] + lines[1][1], fontsize=8, loc="upper left")
    fig.tight_layout()
    save(fig, out, "spin_down.py")


if __name__ == "__main__":
    command_line(main, __doc__, counts=(4, 5))
