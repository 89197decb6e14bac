"""Shared helpers of the figure scripts: CSV loading, the Agg backend, the paper law's branches."""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

plt.rcParams.update({"figure.dpi": 110, "savefig.dpi": 110, "font.size": 9, "axes.grid": True, "grid.alpha": 0.3})

# Alternate colours per simulated second, as in the paper's Fig. 5 caption (red, then green).
SECOND_COLOURS = ("tab:red", "tab:green")


def load(path):
    """Columns of a CSV file: numeric columns as float arrays, the others as lists of text."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{path}: no rows")
    cols = {}
    for name in rows[0]:
        values = [r[name] for r in rows]
        try:
            cols[name] = np.array([float(v) for v in values])
        except ValueError:
            cols[name] = values
    return cols


def paper_branches(tan_alpha, mu_c, s_c):
    """physics.md section 5: the roots s = s_c (1 -+ sqrt(1 - tan(alpha)/mu_c)) of the paper law (stable, unstable)."""
    root = np.sqrt(np.clip(1.0 - np.asarray(tan_alpha) / mu_c, 0.0, None))
    return s_c * (1.0 - root), s_c * (1.0 + root)


def paper_phi_star(alpha, mu_c, s_c):
    return 2.0 * math.atan(s_c * (1.0 - math.sqrt(1.0 - math.tan(alpha) / mu_c)))


def by_second(ax, t, x, y, **kw):
    """Draws y(x) in pieces of one simulated second, alternating the two colours."""
    second = np.floor(t).astype(int)
    for k in np.unique(second):
        idx = np.nonzero(second == k)[0]
        if idx[-1] + 1 < len(t):
            idx = np.append(idx, idx[-1] + 1)  # join to the next piece
        ax.plot(x[idx], y[idx], color=SECOND_COLOURS[k % 2], **kw)


def continuous_angle(phi):
    """phi without the 2 pi jumps where it wraps at +-pi (a direction near pi, e.g. a negative-spin top's phi*)."""
    return np.unwrap(np.asarray(phi, dtype=float))


def levels_in(values, level):
    """level + 2 pi k for every integer k that lies within the range of values (phi* on an unwrapped phi axis);
    the nearest one when none does."""
    lo, hi = float(np.min(values)), float(np.max(values))
    k_lo, k_hi = math.ceil((lo - level) / (2 * math.pi)), math.floor((hi - level) / (2 * math.pi))
    if k_lo > k_hi:
        k = round((0.5 * (lo + hi) - level) / (2 * math.pi))
        return [level + 2 * math.pi * k]
    return [level + 2 * math.pi * k for k in range(k_lo, k_hi + 1)]


def save(fig, out, name=None):
    """Lays the figure out, writes it to out and says so (as name) when a name is given."""
    fig.tight_layout()
    fig.savefig(out)
    if name:
        print(f"{name}: wrote {out}")


def command_line(main, usage, counts=(2,)):
    """Calls main with the command line's arguments when their number is one of counts, else exits with usage."""
    if len(sys.argv) - 1 not in counts:
        raise SystemExit(usage)
    main(*sys.argv[1:])
