#!/usr/bin/python3
"""Keeps the columns a figure needs and thins the rows of a top_sim_run CSV, so the committed data stays small.

usage: reduce_csv.py IN.csv OUT.csv --columns t,contact_x,... [--every N] [--dense-until T] [--digits D]
Rows with t <= --dense-until are all kept (fast transients); after that one row in N.
"""
import argparse
import csv
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("src")
    ap.add_argument("dst")
    ap.add_argument("--columns", required=True, help="comma-separated column names to keep")
    ap.add_argument("--every", type=int, default=1, help="keep one row in N (>= 1)")
    ap.add_argument("--dense-until", type=float, default=-1.0, help="keep every row up to this time [s]")
    ap.add_argument("--digits", type=int, default=9, help="significant digits of numbers (>= 3)")
    a = ap.parse_args()
    if a.every < 1:
        sys.exit(f"reduce_csv.py: --every = {a.every}: must be >= 1")
    if a.digits < 3:
        sys.exit(f"reduce_csv.py: --digits = {a.digits}: must be >= 3")
    columns = a.columns.split(",")
    with open(a.src, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in columns if c not in reader.fieldnames]
        if missing:
            sys.exit(f"reduce_csv.py: {a.src}: no column(s) {', '.join(missing)}; has {', '.join(reader.fieldnames)}")
        rows = list(reader)

    def fmt(v):
        try:
            return f"{float(v):.{a.digits}g}"
        except ValueError:
            return v

    with open(a.dst, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        sparse = 0
        for i, r in enumerate(rows):
            keep = float(r["t"]) <= a.dense_until or i == len(rows) - 1
            if not keep:
                keep = sparse % a.every == 0
                sparse += 1
            if keep:
                w.writerow([fmt(r[c]) for c in columns])


if __name__ == "__main__":
    main()
