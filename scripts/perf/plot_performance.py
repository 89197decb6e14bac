#!/usr/bin/python3
"""Figures and markdown tables of docs/performance.md from docs/data/perf_*.csv (written by top_sim_study)."""
import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display in CI or the sandbox
import matplotlib.pyplot as plt  # noqa: E402

DATA = Path(sys.argv[1] if len(sys.argv) > 1 else "docs/data")
IMG = Path(sys.argv[2] if len(sys.argv) > 2 else "docs/img")
TABLES = Path(sys.argv[3] if len(sys.argv) > 3 else DATA / "perf_tables.md")
MUJOCO_CPU = 0.018   # CPU s per simulated s, MuJoCo 3.12 RK4 dt 1e-3 (issue 5; not measurable here)
MUJOCO_ERR = 8e-5    # its contact-point error after 5 s [m]

MARKERS = {"euler": "v", "semi_implicit_euler": "^", "rk4": "s", "dopri5": "o", "rosenbrock4": "D", "switching": "*"}
COLORS = {"euler": "C0", "semi_implicit_euler": "C1", "rk4": "C2", "dopri5": "C3", "rosenbrock4": "C4", "switching": "C5"}


def rows(name):
    with open(DATA / name) as f:
        return list(csv.DictReader(f))


def num(x):
    try:
        v = float(x)
    except ValueError:
        return math.nan
    return v


def fmt(v, digits=2):
    return "—" if not math.isfinite(v) else f"{v:.{digits}g}" if abs(v) < 1e4 else f"{v:.3g}"


def work_precision(out):
    r = rows("perf_work_precision.csv")
    scenes = list(dict.fromkeys(x["scene"] for x in r))
    models = list(dict.fromkeys(x["model"] for x in r))
    fig, axes = plt.subplots(len(models), len(scenes), figsize=(5 * len(scenes), 4 * len(models)), squeeze=False)
    for j, sc in enumerate(scenes):
        for i, mo in enumerate(models):
            ax = axes[i][j]
            for meth, mk in MARKERS.items():
                pts = [(num(x["cpu_per_sim_s"]), num(x["err_pos_truth"])) for x in r
                       if x["scene"] == sc and x["model"] == mo and x["method"] == meth and x["ok"] == "1"]
                pts = [p for p in pts if math.isfinite(p[1]) and p[1] > 0]
                if pts:
                    pts.sort()
                    ax.loglog([p[0] for p in pts], [max(p[1], 1e-16) for p in pts], marker=mk, color=COLORS[meth],
                              label=meth)
            ax.set_title(f"{sc}, {mo}")
            ax.set_xlabel("CPU s per simulated s")
            ax.set_ylabel("contact-point error after T [m]")
            ax.grid(True, which="both", alpha=0.3)
            if i == 0 and j == 0:
                ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(IMG / "perf_work_precision.png", dpi=90)
    out.append("### Work-precision table\n")
    out.append("Error against the full constrained model at dopri5 rtol 1e-12 (`truth`) and against the tight"
               " reference of the same model (`own`: the numerical error alone). `—`: the run ended in a fault"
               " (numerical blow-up shows up as lift-off or a fallen top).\n")
    out.append("| scene | model | method | setting | CPU s / sim s | steps / sim s | pos. error truth [m] |"
               " pos. error own [m] | phi error truth [rad] | max energy residual |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")
    for x in r:
        ok = x["ok"] == "1"
        out.append(f"| {x['scene']} | {x['model']} | {x['method']} | {x['setting']} | {fmt(num(x['cpu_per_sim_s']))} |"
                   f" {fmt(num(x['steps_per_sim_s']), 3)} | {fmt(num(x['err_pos_truth'])) if ok else 'fault'} |"
                   f" {fmt(num(x['err_pos_own'])) if ok else '—'} | {fmt(num(x['err_phi_truth'])) if ok else '—'} |"
                   f" {fmt(num(x['residual']))} |")
    out.append("")


def stability(out):
    r = rows("perf_stability.csv")
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for meth in ("euler", "semi_implicit_euler", "rk4"):
        pts = [(num(x["spin"]), num(x["max_stable_dt"]), x["capped"] == "1") for x in r if x["method"] == meth]
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=MARKERS[meth], color=COLORS[meth], label=meth)
    nut = sorted({(num(x["spin"]), num(x["nutation_rate"])) for x in r})
    ax.loglog([p[0] for p in nut], [2.83 / p[1] for p in nut], "k--", lw=0.8, label="2.83 / nutation rate (RK4 limit)")
    ax.set_xlabel("spin [rad/s]")
    ax.set_ylabel("largest bounded step [s]")
    ax.set_ylim(1e-7, 1e-1)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(IMG / "perf_stability.png", dpi=90)
    spins = list(dict.fromkeys(x["spin"] for x in r))
    out.append("### Stability map\n")
    out.append("| spin [rad/s] | nutation [rad/s] | window [s] | euler | semi_implicit_euler | rk4 |")
    out.append("|---|---|---|---|---|---|")
    for s in spins:
        by = {x["method"]: x for x in r if x["spin"] == s}
        first = next(iter(by.values()))
        cells = []
        for m in ("euler", "semi_implicit_euler", "rk4"):
            v = num(by[m]["max_stable_dt"])
            cells.append(("≥ " if by[m]["capped"] == "1" else "") + fmt(v))
        out.append(f"| {fmt(num(s), 3)} | {fmt(num(first['nutation_rate']), 3)} | {fmt(num(first['window_s']))} | "
                   + " | ".join(cells) + " |")
    out.append("")


def default_choice(out):
    r = rows("perf_default_choice.csv")
    out.append("### Default scene: whole runs\n")
    out.append("| start | T [s] | method | rtol | CPU [s] | real-time factor | steps | RHS | abs(phi_measured - phi*) [rad] |"
               " max energy residual |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")
    for x in r:
        out.append(f"| {x['scene'].replace('default_', '')} | {x['T']} | {x['method']} | {x['rtol']} |"
                   f" {fmt(num(x['cpu_s']), 3)} | {fmt(num(x['real_time_factor']), 3)} | {x['steps']} | {x['rhs']} |"
                   f" {fmt(num(x['phi_err']))} | {fmt(num(x['residual']))} |")
    out.append("")


def mujoco(out):
    r = rows("perf_mujoco.csv")
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for meth in ("rk4", "dopri5"):
        pts = sorted((num(x["cpu_per_sim_s"]), num(x["err_pos_m"])) for x in r if x["method"] == meth)
        pts = [p for p in pts if math.isfinite(p[1])]
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=MARKERS[meth], color=COLORS[meth],
                  label=f"top_sim {meth}")
    ax.loglog([MUJOCO_CPU], [MUJOCO_ERR], "rX", ms=10, label="MuJoCo 3.12 RK4 dt 1e-3 (issue 5)")
    ax.axhline(MUJOCO_ERR, color="r", lw=0.5)
    ax.set_xlabel("CPU s per simulated s")
    ax.set_ylabel("contact-point error after 5 s [m]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(IMG / "perf_mujoco.png", dpi=90)
    ok = [(num(x["cpu_per_sim_s"]), x) for x in r if math.isfinite(num(x["err_pos_m"])) and num(x["err_pos_m"]) <= MUJOCO_ERR]
    out.append("### MuJoCo comparison scene (frictionless, 5 s)\n")
    out.append("| method | setting | CPU s / sim s | contact-point error [m] |")
    out.append("|---|---|---|---|")
    for x in r:
        out.append(f"| {x['method']} | {x['setting']} | {fmt(num(x['cpu_per_sim_s']))} | {fmt(num(x['err_pos_m']))} |")
    if ok:
        best = min(ok, key=lambda p: p[0])
        out.append(f"\nCheapest run at or below {MUJOCO_ERR * 1e3:.2f} mm: {best[1]['method']} {best[1]['setting']},"
                   f" {best[0]:.3g} CPU s per simulated s, error {num(best[1]['err_pos_m']):.2g} m:"
                   f" **{MUJOCO_CPU / best[0]:.0f}x less CPU** than MuJoCo's {MUJOCO_CPU} s.")
    out.append("")


def model_choice(out):
    r = rows("perf_model_choice.csv")
    out.append("### Model and integrator per shipped scene\n")
    out.append("Errors against dopri5 rtol 1e-12 with the scene's own model, over the scene's duration.\n")
    out.append("| scene | T [s] | choice | model | method | rtol | CPU [s] | pos. error [m] | phi error [rad] |"
               " max energy residual |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")
    for x in r:
        ok = x["ok"] == "1"
        out.append(f"| {x['scene']} | {x['T']} | {x['choice']} | {x['model']} | {x['method']} | {x['rtol']} |"
                   f" {fmt(num(x['cpu_s']), 3)} | {fmt(num(x['err_pos_m'])) if ok else 'fault'} |"
                   f" {fmt(num(x['err_phi_rad'])) if ok else '—'} | {fmt(num(x['residual']))} |")
    out.append("")


def main():
    IMG.mkdir(parents=True, exist_ok=True)
    out = ["<!-- generated by scripts/perf/plot_performance.py from docs/data/perf_*.csv; do not edit -->", ""]
    for part, f in ((work_precision, "perf_work_precision.csv"), (stability, "perf_stability.csv"),
                    (default_choice, "perf_default_choice.csv"), (mujoco, "perf_mujoco.csv"),
                    (model_choice, "perf_model_choice.csv")):
        if (DATA / f).exists():
            part(out)
    TABLES.write_text("\n".join(out) + "\n")
    print(f"wrote {TABLES} and {IMG}/perf_*.png")


if __name__ == "__main__":
    main()
