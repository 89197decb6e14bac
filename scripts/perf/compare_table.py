#!/usr/bin/python3
"""Markdown table of scripts/bench_compare.sh results against one or more bases, HEAD the same in all:

  compare_table.py HEAD RESULTS_BASE1_HEAD.txt [RESULTS_BASE2_HEAD.txt ...]

A results file has lines "round commit figure value". Columns: each base's median, HEAD's median (from the first
file that measured it), and HEAD / base as median (min-max) of the per-round ratios."""
import statistics
import sys

LABELS = {
    "default_r1": "default scene 300 s, summary only, 1 sample/s",
    "default_r100": "the same, 100 samples/s",
    "default_r1000": "the same, 1000 samples/s",
    "csv_us_per_row": "CSV, per row (default columns)",
    "hopping": "hopping scene (0.5 s at 5000 rad/s)",
    "coulomb": "Coulomb scene (5 s)",
    "python_trajectory": "Python `trajectory(60, 1000)`",
}


def load(path):
    data = {}
    for line in open(path):
        k, rev, fig, value = line.split()
        if value != "nan":
            data.setdefault(fig, {}).setdefault(rev, {})[int(k)] = float(value)
    return data


def fmt(fig, seconds):
    if fig.endswith("us_per_row"):
        return f"{seconds:.3g} us"
    return f"{seconds * 1e3:.3g} ms"


def ratio_cell(by, base, head):
    b, h = by.get(base, {}), by.get(head, {})
    ratios = [h[k] / b[k] for k in b if k in h and b[k] > 0]
    if not ratios:
        return "-"
    return f"{statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f})"


def main():
    head, paths = sys.argv[1], sys.argv[2:]
    runs = [(path.rsplit("_", 2)[-2], load(path)) for path in paths]  # results_BASE_HEAD.txt
    bases = [b for b, _ in runs]
    print("| figure | " + " | ".join(bases) + f" | {head} | " + " | ".join(f"{head} / {b}" for b in bases) + " |")
    print("|---" * (2 + 2 * len(bases)) + "|")
    for fig, label in LABELS.items():
        cells, head_value = [], None
        for base, data in runs:
            by = data.get(fig, {})
            cells.append(fmt(fig, statistics.median(by[base].values())) if by.get(base) else "-")
            if head_value is None and by.get(head):
                head_value = statistics.median(by[head].values())
        ratios = [ratio_cell(data.get(fig, {}), base, head) for base, data in runs]
        head_cell = fmt(fig, head_value) if head_value is not None else "-"
        print(f"| {label} | " + " | ".join(cells) + f" | {head_cell} | " + " | ".join(ratios) + " |")


if __name__ == "__main__":
    main()
