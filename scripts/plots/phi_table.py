#!/usr/bin/python3
"""Tables of analytic against simulated phi* per alpha, from top_sim_sweep's CSV files, written into
docs/results.md between the markers <!-- phi-table:begin --> and <!-- phi-table:end -->.

usage: phi_table.py DATA_DIR RESULTS.md
"""
import math
import os
import sys

from plotlib import load

PAIRS = (("aluminium", "pmma"), ("steel", "steel"))
BEGIN, END = "<!-- phi-table:begin -->", "<!-- phi-table:end -->"


def table(path):
    d = load(path)
    top, plane, mu_c, s_c = d["top"][0], d["plane"][0], d["mu_c"][0], d["s_c"][0]
    lines = [f"**{top} top on {plane}** (paper law mu_c = {mu_c:g}, s_c = {s_c:g}; alpha_c = atan(mu_c) = "
             f"{math.atan(mu_c):.4f} rad; started tilted 0.1 rad at rest, 200 rad/s; file `docs/data/{os.path.basename(path)}`)",
             "",
             "| alpha [rad] | tan alpha | phi* analytic [rad] | phi simulated [rad] | simulated - analytic [rad] "
             "| tan(phi/2) simulated | outcome | simulated [s] | CPU [s] |",
             "|---:|---:|---:|---:|---:|---:|:---|---:|---:|"]
    for i in range(len(d["alpha"])):
        star = d["phi_star"][i]
        phi = d["phi_measured"][i]
        has_star = not math.isnan(star)
        lines.append("| {:.3f} | {:.4f} | {} | {:.7f} | {} | {:.6f} | {} | {:.0f} | {:.3f} |".format(
            d["alpha"][i], d["tan_alpha"][i], f"{star:.7f}" if has_star else "none (alpha > alpha_c)", phi,
            f"{phi - star:+.1e}" if has_star else "-", d["tan_half_phi_measured"][i], d["outcome"][i],
            d["sim_seconds"][i], d["cpu_seconds"][i]))
    return "\n".join(lines)


def main(data_dir, results):
    body = "\n\n".join(table(f"{data_dir}/fig4_{top}_{plane}.csv") for top, plane in PAIRS)
    text = open(results).read()
    if BEGIN not in text or END not in text:
        raise SystemExit(f"phi_table.py: {results} has no {BEGIN} ... {END} markers")
    head, rest = text.split(BEGIN, 1)
    tail = rest.split(END, 1)[1]
    with open(results, "w") as f:
        f.write(head + BEGIN + "\n" + body + "\n" + END + tail)
    print(f"phi_table: wrote the tables into {results}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2])
