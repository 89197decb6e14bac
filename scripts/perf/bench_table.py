#!/usr/bin/python3
"""Markdown table of bench/core_bench.cpp's JSON output (median of the repetitions), with real-time factors."""
import json
import sys

UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def main():
    data = json.load(open(sys.argv[1]))
    print("### Google Benchmark (bench/core_bench.cpp, median of 3 repetitions)\n")
    print("| benchmark | CPU time | steps | RHS | real-time factor | ns per RHS (incl. stepper) |")
    print("|---|---|---|---|---|---|")
    for b in data["benchmarks"]:
        if b.get("aggregate_name", "median") != "median":
            continue
        name = b["run_name"] if "run_name" in b else b["name"]
        cpu = b["cpu_time"] * UNIT[b["time_unit"]]
        steps = b.get("steps_per_sim_s", b.get("steps", float("nan")))
        rhs = b.get("rhs_per_sim_s", b.get("rhs", float("nan")))
        sim = 1.0 if "steps_per_sim_s" in b else b.get("sim_s", float("nan"))
        rtf = sim / cpu if sim == sim else float("nan")
        ns_rhs = cpu / rhs * 1e9 if rhs == rhs and rhs > 0 else float("nan")
        cell = lambda v, f: "—" if v != v else f.format(v)
        print(f"| {name} | {cpu * 1e3:.4g} ms | {cell(steps, '{:.0f}')} | {cell(rhs, '{:.0f}')} |"
              f" {cell(rtf, '{:,.0f}x')} | {cell(ns_rhs, '{:.0f}')} |" if cpu > 1e-6 else
              f"| {name} | {cpu * 1e9:.1f} ns | — | — | — | {cell(b.get('rhs_per_step', float('nan')), '{:.0f} RHS/step')} |")
    print()


if __name__ == "__main__":
    main()
