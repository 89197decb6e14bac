#!/usr/bin/python3
"""The sweeps of top_sim_stability (physics.md section 10): real parts of the classified eigenvalues against the
inclination (with alpha_c located and analytic) and against the shell spin (with the unstable windows); for a
tippe top the largest real part but the zero one of its spinning upright and inverted states against the spin, with
the located crossings and Magnus' critical spins.

usage: stability.py SWEEP.csv OUT.png [--alpha-c A] [--alpha-c-analytic A] [--nutation-windows LO:HI,...]
                    [--windows-upright LO:HI,...] [--windows-inverted LO:HI,...] [--magnus-upright W]
                    [--magnus-inverted W] [--critical-upright W] [--maxwell-klein W] [--title TEXT]
SWEEP.csv is written by top_sim_stability --plot (one row per analysed state; sweep = alpha, spin, upright or
inverted).
"""
import argparse
import math

import numpy as np

from plotlib import load, plt


def alpha_panel(ax, d, alpha_c, alpha_c_analytic, letter):
    a = d["alpha"]
    ok = np.ones(len(a), bool)  # rows without a sleeping state are NaN: the lines break there
    for key, label, style in (("prec_re", "precession", "o-"), ("nut_re", "nutation", "s-"),
                              ("fric_re_max", "slowest friction mode", "^-"), ("fric_re_min", "fastest friction mode", "v-")):
        ax.semilogy(a[ok], -d[key][ok], style, ms=3, lw=1, label=f"-Re {label}")
    if not math.isnan(alpha_c):
        ax.axvline(alpha_c, color="k", lw=1.2, label=f"alpha_c located (eigenvalue crossing) = {alpha_c:.10f}")
    if not math.isnan(alpha_c_analytic):
        ax.axvline(alpha_c_analytic, color="tab:red", ls="--", lw=0.9,
                   label=f"alpha_c analytic = atan(max mu) = {alpha_c_analytic:.10f}")
    ax.set_xlabel("inclination alpha [rad]")
    ax.set_ylabel("decay rate -Re(lambda) [1/s]")
    ax.set_title(f"{letter}decay rates of the sleeping state's modes against alpha")
    ax.legend(fontsize=7, loc="best")


def spin_panel(ax, d, windows, letter):
    w = d["spin"]
    ok = np.ones(len(w), bool)  # rows without a sleeping state (e.g. spin 0) are NaN: the lines break there
    ax.plot(w[ok], d["nut_re"][ok], "s-", ms=3, lw=1, color="tab:orange", label="Re nutation")
    ax.plot(w[ok], d["prec_re"][ok], "o-", ms=3, lw=1, color="tab:blue", label="Re precession")
    ax.axhline(0.0, color="k", lw=0.6)
    for k, (lo, hi) in enumerate(windows):
        ax.axvspan(lo, hi, color="tab:red", alpha=0.15, label="nutation unstable (Re > 0)" if k == 0 else None)
    top = np.nanmax(np.abs(d["nut_re"])) if np.isfinite(d["nut_re"]).any() else 1.0
    ax.set_ylim(-1.1 * top, 1.1 * top)
    ax.set_xlabel("shell spin omega* [rad/s]")
    ax.set_ylabel("Re(lambda) [1/s]")
    ax.set_title(f"{letter}nutation and precession against the shell spin")
    ax.legend(fontsize=7, loc="best")


STATE_COLOURS = {"upright": "tab:blue", "inverted": "tab:orange"}


def parse_windows(text):
    return [tuple(float(x) for x in w.split(":")) for w in text.split(",") if w]


def spinning_panel(ax, d, sweeps, windows, magnus, letter):
    """Max Re but the zero one against the spin for each spinning state; crossings located (edges of the unstable
    windows inside the sweep) and Magnus' omega_k (dashed)."""
    for state in ("upright", "inverted"):
        rows = sweeps == state
        if not rows.any():
            continue
        w, m = d["spin"][rows], d["max_real"][rows]
        colour = STATE_COLOURS[state]
        ax.plot(w, m, "-", lw=1.4, color=colour, label=f"{state}: max Re (all eigenvalues but the zero one)")
        inside = [e for lo, hi in windows[state] for e in (lo, hi) if w.min() < e < w.max()]
        for k, e in enumerate(inside):
            ax.plot([e], [0.0], "o", ms=7, mfc="none", mec=colour, mew=1.5,
                    label=f"{state}: crossing located {e:.8g} rad/s" if k == 0 else None)
        if not math.isnan(magnus[state]):
            ax.axvline(magnus[state], color=colour, ls="--", lw=0.9,
                       label=f"{state}: Magnus omega_k = {magnus[state]:.8g} rad/s")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_yscale("symlog", linthresh=1e-4)  # every value of a state away from its crossing is above 1e-4 in size
    ax.set_xlabel("spin about the figure axis [rad/s]")
    ax.set_ylabel("largest Re(lambda) [1/s] (symlog; > 0 unstable)")
    ax.set_title(f"{letter}the tippe top's spinning states against the spin")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)  # below: the curves fill the box


def main():
    p = argparse.ArgumentParser(usage=__doc__)
    p.add_argument("csv")
    p.add_argument("out")
    p.add_argument("--alpha-c", type=float, default=float("nan"))
    p.add_argument("--alpha-c-analytic", type=float, default=float("nan"))
    p.add_argument("--nutation-windows", default="")
    for state in ("upright", "inverted"):
        p.add_argument(f"--windows-{state}", default="")
        p.add_argument(f"--magnus-{state}", type=float, default=float("nan"))
    p.add_argument("--critical-upright", type=float, default=float("nan"))
    p.add_argument("--maxwell-klein", type=float, default=float("nan"))
    p.add_argument("--title", default="")
    args = p.parse_args()
    d = load(args.csv)
    sweeps = np.array(d["sweep"])
    kinds = [k for k in ("alpha", "spin") if (sweeps == k).any()]
    if ((sweeps == "upright") | (sweeps == "inverted")).any():
        kinds.append("spinning")
    height = 5.6 if "spinning" in kinds else 4.6  # room for the spinning panel's legend below it
    fig, axes = plt.subplots(1, len(kinds), figsize=(6.5 * len(kinds), height), squeeze=False)
    for k, (ax, kind) in enumerate(zip(axes[0], kinds)):
        rows = {key: (np.asarray(v)[sweeps == kind]) for key, v in d.items()}
        letter = f"{'ab'[k]}) " if len(kinds) > 1 else ""
        if kind == "spinning":
            windows = {"upright": parse_windows(args.windows_upright), "inverted": parse_windows(args.windows_inverted)}
            magnus = {"upright": args.magnus_upright, "inverted": args.magnus_inverted}
            spinning_panel(ax, d, sweeps, windows, magnus, letter)
            if not math.isnan(args.maxwell_klein):  # an ordinary top: the frictionless plane's limit, dotted
                ax.axvline(args.maxwell_klein, color="0.4", ls=":", lw=1.2,
                           label=f"frictionless Maxwell-Klein {args.maxwell_klein:.8g} rad/s")
                ax.set_title(f"{letter}an ordinary top's upright state against the spin "
                             f"(critical {args.critical_upright:.8g} rad/s)")
                ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
        elif kind == "alpha":
            alpha_panel(ax, rows, args.alpha_c, args.alpha_c_analytic, letter)
        else:
            spin_panel(ax, rows, parse_windows(args.nutation_windows), letter)
    if args.title:
        fig.suptitle(f"top_sim_stability: {args.title}", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out)
    print(f"stability.py: wrote {args.out}")


if __name__ == "__main__":
    main()
