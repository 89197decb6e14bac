#!/usr/bin/python3
"""phi against spin with a finite contact (issue 32 part 6): docs/data/phi_vs_spin_patch.json -> PNG.

usage: phi_vs_spin_patch.py DATA.json OUT.png
Top row: the drift angle phi (mean over the last half of each run) against the window's mean spin, per top, for the
point contact (adiabatic reference) and the Hertz patch with the exact and the elliptic drilling laws, at each
inclination (and, for the wooden top, with Stokes air drag and with that drag force x1000). Bottom row: the same points minus each series' mean, in microradians, so that a slope shows; the
legend gives the fitted d phi/d omega. Runs that ended in a contact fault (the top fell) are crosses at the top.
"""
import json

from plotlib import command_line, plt, save

COLOURS = {"point": "tab:blue", "hertz": "tab:orange", "elliptic": "tab:green", "air_stokes": "tab:purple",
           "air_drag_x1000": "tab:red"}
BIG = ("air_drag_x1000",)  # millirad effects: top row only, the bottom row is microrad
MARKERS = {0.09: "o", 0.15: "s"}


def main(data, out):
    d = json.load(open(data))
    pairs = []
    for r in d["runs"]:
        if (r["top"], r["plane"]) not in pairs:
            pairs.append((r["top"], r["plane"]))
    slopes = {(f["top"], f["alpha"], f["contact"]): f["dphi_domega"] for f in d["fits"]}
    fig, axes = plt.subplots(2, len(pairs), figsize=(5 * len(pairs), 8), squeeze=False)
    for col, (top, plane) in enumerate(pairs):
        a, b = axes[0][col], axes[1][col]
        runs = [r for r in d["runs"] if r["top"] == top and "phi" in r]
        for (alpha, contact) in sorted({(r["alpha"], r["contact"]) for r in runs}):
            series = [r for r in runs if r["alpha"] == alpha and r["contact"] == contact]
            good = [r for r in series if not r["contact_fault"]]
            fell = [r for r in series if r["contact_fault"]]
            style = dict(color=COLOURS[contact], marker=MARKERS.get(alpha, "^"), ms=4, lw=0.8)
            a.plot([r["spin_mean"] for r in good], [r["phi"] for r in good], **style,
                   label=f"{contact}, alpha {alpha}" + (f" ({slopes.get((top, alpha, contact), 0):.1e} s)"
                                                         if contact in BIG else ""))
            if fell:
                a.plot([r["spin0"] for r in fell], [a.get_ylim()[1]] * len(fell), "x", color=COLOURS[contact],
                       label=f"{contact}, alpha {alpha}: fell")
            if len(good) >= 2 and contact not in BIG:
                mean = sum(r["phi"] for r in good) / len(good)
                k = slopes.get((top, alpha, contact), float("nan"))
                b.plot([r["spin_mean"] for r in good], [1e6 * (r["phi"] - mean) for r in good], **style,
                       label=f"{contact}, alpha {alpha}: {k:.1e} s")
        a.set_title(f"{top} top on {plane}")
        a.set_xlabel("spin (window mean) [rad/s]")
        a.set_ylabel("phi [rad]")
        a.legend(fontsize=7)
        b.set_xlabel("spin (window mean) [rad/s]")
        b.set_ylabel("phi - series mean [microrad]")
        b.set_title("minus series mean; legend: fitted d phi/d omega", fontsize=9)
        b.legend(fontsize=7)
    fig.suptitle("Drift angle against spin, point contact vs Hertz patch (bench/phi_vs_spin_patch.py)")
    save(fig, out, "phi_vs_spin_patch")


if __name__ == "__main__":
    command_line(main, __doc__.split("\n")[2])
