"""python3 -m top_sim.sweep: top_sim_sweep's grid (same flags, same CSV rows) on a Dask cluster, and Monte Carlo.

Every point runs the C++ sweep point of top_sim_sweep (src/studies/sweep_point.cpp, bound as top_sim._core), so a row
here equals top_sim_sweep's row of the same point (but for cpu_seconds). The flags are parsed by the same C++ parser
(src/studies/sweep_options.cpp): the same errors. docs/studies.md describes the options, the cluster and the costs.
Exit status: 0 ok, 2 bad argument, 3 some point ended in a contact fault (its row says so), 4 the cluster failed
(no scheduler, no worker, a point lost on every worker it ran on), 130 interrupted (the file keeps every row so far).
"""
import collections
import math
import os
import signal
import sys
import time

import numpy as np

from top_sim import _core

USAGE = ("usage: python3 -m top_sim.sweep [options]\n" + _core.SWEEP_USAGE +
         "  Cluster:\n"
         "  --scheduler ADDR    run the points on the Dask scheduler at ADDR (tcp://host:8786); without it, a local\n"
         "                      cluster of --threads worker processes on this machine\n"
         "  --connect-timeout S give up when the scheduler does not answer, or no worker joins it, within S seconds,\n"
         "                      in (0, 3600] (default 10)\n"
         "  --resume            keep the rows of a partial --out FILE and run only the points it lacks\n"
         "  --no-progress       no progress bar (there is none unless stderr is a terminal)\n"
         "  Monte Carlo (instead of the grid):\n"
         "  --samples N         N points, an integer in [1, 1000000]; --alpha, --spin, --mu-c and --s-c then each take\n"
         "                      one value or a distribution: uniform:LO:HI | normal:MEAN:SD | lognormal:MEDIAN:SIGMA\n"
         "                      (ln x normal with median MEDIAN and standard deviation SIGMA); a draw outside the\n"
         "                      flag's range is drawn again; the CSV gets a first column `sample`\n"
         "  --seed S            the random seed, an integer in [0, 2^63) (needed by --samples)\n")

DISTRIBUTIONS = ("uniform", "normal", "lognormal")
SAMPLED_FLAGS = ("--alpha", "--spin", "--mu-c", "--s-c")  # in the order they are drawn for each sample
OWN_FLAGS = {"--scheduler": True, "--connect-timeout": True, "--resume": False, "--no-progress": False,
             "--samples": True, "--seed": True}  # flag -> takes a value


class BadArgument(ValueError):
    """A bad flag or value; the message names the flag, the value and the allowed range."""


class ClusterError(RuntimeError):
    """The cluster cannot run the sweep (no scheduler, no worker, a point lost on every worker)."""


def run_point(point, settings):
    """One point on a worker: top_sim_sweep's simulation of it (the GIL is released while it runs)."""
    return _core.run_sweep_point(point, settings)


# ---- the command line ------------------------------------------------------------------------------------------

def split_arguments(argv):
    """This tool's own flags (a dict) and the rest, for top_sim_sweep's parser, in their order."""
    own, rest = {}, []
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in OWN_FLAGS:
            if OWN_FLAGS[a]:
                if i + 1 >= len(argv):
                    raise BadArgument(a + ": needs a value")
                own[a] = argv[i + 1]
                i += 1
            else:
                own[a] = True
        else:
            rest.append(a)
        i += 1
    return own, rest


def integer(flag, text, low, high, range_text):
    try:
        v = int(text, 10)
    except ValueError:
        raise BadArgument("%s = '%s': must be %s" % (flag, text, range_text)) from None
    if not low <= v <= high:
        raise BadArgument("%s = '%s': must be %s" % (flag, text, range_text))
    return v


def check_value(flag, value):
    """Raises top_sim_sweep's error when `value` (a number or its text) is outside `flag`'s range (the C++ parser
    decides)."""
    text = value if isinstance(value, str) else repr(float(value))
    try:
        _core.parse_sweep_options([flag, text])
    except _core.SweepArgumentError as e:
        raise BadArgument(str(e)) from None


def check_part(flag, text, name, part):
    """check_value for one number of a distribution, named in the message (uniform:LO:HI's HI = ...)."""
    try:
        check_value(flag, part)
    except BadArgument as e:
        reason = str(e).split("': ", 1)[-1]
        raise BadArgument("%s = '%s': %s = %s %s" % (flag, text, name, part, reason)) from None


def in_range(flag, value):
    try:
        check_value(flag, value)
        return True
    except BadArgument:
        return False


def parse_distribution(flag, text):
    """('fixed', value) or (name, a, b) from one value or DIST:A:B; raises BadArgument naming the flag."""
    form = "one value or uniform:LO:HI | normal:MEAN:SD | lognormal:MEDIAN:SIGMA"
    parts = text.split(":")
    if len(parts) == 1 and "," not in text:
        check_value(flag, text)
        return ("fixed", float(text))
    if len(parts) != 3 or parts[0] not in DISTRIBUTIONS:
        raise BadArgument("%s = '%s': with --samples, must be %s" % (flag, text, form))
    a, b = _number(flag, parts[1], form), _number(flag, parts[2], form)
    if parts[0] == "uniform":
        check_part(flag, text, "LO", parts[1])
        check_part(flag, text, "HI", parts[2])
        if not a < b:
            raise BadArgument("%s = '%s': uniform:LO:HI needs LO < HI" % (flag, text))
    else:
        check_part(flag, text, "MEAN" if parts[0] == "normal" else "MEDIAN", parts[1])  # a value of the parameter
        if not b > 0.0:
            raise BadArgument("%s = '%s': the spread of %s must be > 0" % (flag, text, parts[0]))
        if parts[0] == "lognormal" and not a > 0.0:
            raise BadArgument("%s = '%s': the median of lognormal must be > 0" % (flag, text))
    return (parts[0], a, b)


def _number(flag, text, form):
    try:
        v = float(text)
    except ValueError:
        raise BadArgument("%s = '%s': not a finite number (%s)" % (flag, text, form)) from None
    if not math.isfinite(v):
        raise BadArgument("%s = '%s': not a finite number (%s)" % (flag, text, form))
    return v


def draw(rng, flag, dist, sample_index):
    """One value of `dist`, drawn again while it falls outside the flag's range (the distribution truncated)."""
    if dist[0] == "fixed":
        return dist[1]
    for _ in range(1000):
        if dist[0] == "uniform":
            v = rng.uniform(dist[1], dist[2])
        elif dist[0] == "normal":
            v = rng.normal(dist[1], dist[2])
        else:
            v = math.exp(rng.normal(math.log(dist[1]), dist[2]))
        if in_range(flag, v):
            return float(v)
    raise BadArgument("%s = '%s:%r:%r': 1000 draws for sample %d all fell outside the flag's range"
                      % (flag, dist[0], dist[1], dist[2], sample_index))


def monte_carlo_points(base, dists, samples, seed):
    """`samples` points: `base` (top, plane) with each sampled flag drawn in SAMPLED_FLAGS order, sample by sample."""
    rng = np.random.default_rng(seed)
    keys = {"--alpha": "alpha", "--spin": "spin", "--mu-c": "mu_c", "--s-c": "s_c"}
    points = []
    for i in range(samples):
        p = dict(base)
        for flag in SAMPLED_FLAGS:
            if flag in dists:
                p[keys[flag]] = draw(rng, flag, dists[flag], i)
        points.append(p)
    return points


def parse_monte_carlo(own, rest):
    """The distributions of the sampled flags (taken out of `rest`), the sample count and the seed."""
    if "--seed" not in own:
        raise BadArgument("--samples needs --seed S (an integer in [0, 2^63)): a Monte Carlo sweep is reproducible")
    samples = integer("--samples", own["--samples"], 1, 1000000, "an integer in [1, 1000000]")
    seed = integer("--seed", own["--seed"], 0, 2 ** 63 - 1, "an integer in [0, 2^63)")
    dists, kept = {}, []
    i = 0
    while i < len(rest):
        if rest[i] in SAMPLED_FLAGS and i + 1 < len(rest):
            dists[rest[i]] = parse_distribution(rest[i], rest[i + 1])
            i += 2
        else:
            kept.append(rest[i])
            i += 1
    return dists, samples, seed, kept


def reject_distributions(rest):
    """Without --samples, a distribution is a mistake worth naming (top_sim_sweep would call it not a number)."""
    for flag, value in zip(rest, rest[1:]):
        if flag in SAMPLED_FLAGS and value.split(":")[0] in DISTRIBUTIONS:
            raise BadArgument("%s = '%s': a distribution needs --samples N and --seed S" % (flag, value))


class Plan:
    """What to run: the points with their row keys, the settings, the output and the cluster."""

    def __init__(self, **fields):
        self.__dict__.update(fields)


def parse_arguments(argv):
    """The Plan of a command line (None after -h/--help); raises BadArgument or, for a bad point, SceneError."""
    own, rest = split_arguments(argv)
    if "-h" in rest or "--help" in rest:
        return None
    monte_carlo = "--samples" in own
    if "--seed" in own and not monte_carlo:
        raise BadArgument("--seed = '%s': only with --samples N" % own["--seed"])
    dists = {}
    if monte_carlo:
        if "--alpha" not in rest:
            raise BadArgument("--samples needs --alpha (one value or a distribution)")
        dists, samples, seed, rest = parse_monte_carlo(own, rest)
        for flag, dist in dists.items():  # one value each, so that the grid is the one base point
            rest += [flag, repr(dist[1])]
    else:
        reject_distributions(rest)
    try:
        parsed = _core.parse_sweep_options(rest)
    except _core.SweepArgumentError as e:
        raise BadArgument(str(e)) from None
    if parsed is None:
        return None
    scheduler = own.get("--scheduler")
    if scheduler is not None and "--threads" in rest:
        raise BadArgument("--threads: the scheduler's workers run the points; give --threads only without --scheduler")
    if own.get("--resume") and parsed["out"] == "-":
        raise BadArgument("--resume: needs --out FILE (the partial file to complete)")
    timeout = _number("--connect-timeout", own.get("--connect-timeout", "10"), "seconds")
    if not 0.0 < timeout <= 3600.0:
        raise BadArgument("--connect-timeout = '%s': must be in (0, 3600] [s]" % own["--connect-timeout"])
    points = parsed["points"]
    if monte_carlo:
        if len(points) != 1:
            raise BadArgument("--top, --plane, --patch-radius: with --samples, one top, one plane and one patch "
                              "radius (%d combinations given)"
                              % len(points))
        points = monte_carlo_points(points[0], dists, samples, seed)
    keys = point_keys(points, parsed["settings"], monte_carlo)
    header = ("sample," if monte_carlo else "") + _core.SWEEP_HEADER
    return Plan(points=points, keys=keys, settings=parsed["settings"], out=parsed["out"],
                threads=parsed["threads"] or os.cpu_count() or 1, scheduler=scheduler, timeout=timeout,
                resume=bool(own.get("--resume")), progress=not own.get("--no-progress"), monte_carlo=monte_carlo,
                header=header)


def number_text(v):
    """A number as the CSV writes it (sweep_point.cpp's num: 10 significant digits, nan)."""
    return "nan" if not math.isfinite(v) else "%.10g" % v


def patch_text(patch):
    """The patch_radius column as the CSV writes it: hertz, or the number."""
    return patch if isinstance(patch, str) else number_text(patch)


def point_keys(points, settings, monte_carlo):
    """Each point's row key: its first columns as the row will print them (top, plane, mu_c, s_c, spin, alpha;
    the sample number first in Monte Carlo) and its last, patch_radius. Builds every point's scene first, as
    top_sim_sweep does."""
    keys = []
    for i, p in enumerate(points):
        mu_c, s_c = _core.sweep_scene_law(p, settings)
        key = (p["top"], p["plane"], number_text(mu_c), number_text(s_c), number_text(p["spin"]),
               number_text(p["alpha"]), patch_text(p.get("patch_radius", 0.0)))
        keys.append(((str(i),) + key) if monte_carlo else key)
    return keys


def row_key(plan, row):
    """The key of a row: the columns point_keys names, the patch_radius column last (where the CSV has it)."""
    columns = row.split(",")
    return tuple(columns[:len(plan.keys[0]) - 1] + columns[-1:])


# ---- the CSV file ----------------------------------------------------------------------------------------------

def read_partial(plan):
    """The complete rows of a partial --out file (an unfinished last line is cut off the file); raises BadArgument
    when the file is not a partial file of this sweep."""
    with open(plan.out, "rb") as f:
        data = f.read()
    lines = data.decode("utf-8", "replace").split("\n")
    if lines[0] != plan.header:
        raise BadArgument("--resume: '%s' does not start with this sweep's header (%s)" % (plan.out, plan.header))
    columns = plan.header.count(",") + 1
    complete = lines[1:-1]  # the last piece has no newline: empty, or a row cut short
    good = [row for row in complete if row.count(",") + 1 == columns]
    if len(good) != len(complete):
        raise BadArgument("--resume: '%s' has rows with other than %d columns" % (plan.out, columns))
    if lines[-1]:
        with open(plan.out, "r+b") as f:
            f.truncate(len(data) - len(lines[-1].encode("utf-8")))
    known = collections.Counter(plan.keys)
    for row in good:
        key = row_key(plan, row)
        if known[key] <= 0:
            raise BadArgument("--resume: '%s' has a row for a point this sweep does not have (%s); another grid, "
                              "seed or distribution?" % (plan.out, ",".join(key)))
        known[key] -= 1
    return good


def pending_points(plan, done_rows):
    """The (index, point) pairs whose rows `done_rows` lacks, in grid order (duplicates of a point counted)."""
    have = collections.Counter(row_key(plan, row) for row in done_rows)
    todo = []
    for i, (key, p) in enumerate(zip(plan.keys, plan.points)):
        if have[key] > 0:
            have[key] -= 1
        else:
            todo.append((i, p))
    return todo


def open_output(plan):
    """The output stream, header written, and the rows it already holds (with --resume)."""
    if plan.out == "-":
        sys.stdout.write(plan.header + "\n")
        sys.stdout.flush()
        return sys.stdout, []
    if plan.resume and os.path.exists(plan.out) and os.path.getsize(plan.out) > 0:  # empty: not even the header
        done = read_partial(plan)
        return open(plan.out, "a", encoding="utf-8"), done
    try:
        out = open(plan.out, "w", encoding="utf-8")
    except OSError as e:
        raise BadArgument("--out = '%s': cannot open for writing (%s)" % (plan.out, e.strerror)) from None
    out.write(plan.header + "\n")
    out.flush()
    return out, []


def write_in_grid_order(plan, rows):
    """Rewrites the finished file with its rows in the grid's order (top_sim_sweep's), atomically (a rename)."""
    by_key = collections.defaultdict(collections.deque)
    for row in rows:
        by_key[row_key(plan, row)].append(row)
    tmp = plan.out + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(plan.header + "\n")
        for key in plan.keys:
            f.write(by_key[key].popleft() + "\n")
    os.replace(tmp, plan.out)


# ---- the cluster ------------------------------------------------------------------------------------------------

def connect(plan, workers):
    """A Client of the scheduler at --scheduler (and a worker on it), or of a new local cluster of `workers`
    processes; raises ClusterError within --connect-timeout."""
    import logging
    from distributed import Client, LocalCluster
    if plan.scheduler is None:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                               memory_limit=0, silence_logs=logging.ERROR)
        client = Client(cluster)
        try:  # a worker that cannot start (top_sim not importable in it) would otherwise be restarted forever
            client.wait_for_workers(workers, timeout=max(plan.timeout, 60.0))
        except Exception:
            client.close(timeout=5)
            cluster.close(timeout=5)
            raise ClusterError("the local cluster's %d workers did not start within %g s" % (
                workers, max(plan.timeout, 60.0))) from None
        return client, cluster
    try:
        client = Client(plan.scheduler, timeout=plan.timeout)
    except Exception as e:  # OSError, TimeoutError, ValueError for a malformed address
        raise ClusterError("--scheduler = '%s': no Dask scheduler answered within %g s (%s: %s)"
                           % (plan.scheduler, plan.timeout, type(e).__name__, e)) from None
    try:
        client.wait_for_workers(1, timeout=plan.timeout)
    except Exception:
        client.close(timeout=5)
        raise ClusterError("--scheduler = '%s': the scheduler answered but no worker joined it within %g s"
                           % (plan.scheduler, plan.timeout)) from None
    return client, None


def progress_bar(plan, total, initial):
    from tqdm import tqdm
    enabled = plan.progress and sys.stderr.isatty()
    return tqdm(total=total, initial=initial, disable=not enabled, file=sys.stderr, unit="pt", dynamic_ncols=True)


def run_points(plan, todo, out, rows):
    """Runs `todo` on the cluster, writing and flushing each row as it arrives (appended to `rows`); returns the
    worker count and the points the cluster could not run ((index, message) pairs)."""
    from distributed import as_completed
    workers = min(plan.threads, len(todo))
    client, cluster = connect(plan, workers)
    lost = []
    try:
        if cluster is None:
            workers = len(client.scheduler_info()["workers"])
        futures = client.map(run_point, [p for _, p in todo], settings=plan.settings, pure=False)
        index = {f.key: i for f, (i, _) in zip(futures, todo)}
        with progress_bar(plan, len(plan.points), len(plan.points) - len(todo)) as bar:
            for f in as_completed(futures):
                i = index[f.key]
                try:
                    r = f.result()
                except Exception as e:  # distributed.KilledWorker: the point took down every worker it ran on
                    lost.append((i, "%s: %s" % (type(e).__name__, e)))
                    continue
                row = ("%d,%s" % (i, r["row"])) if plan.monte_carlo else r["row"]
                out.write(row + "\n")
                out.flush()
                rows.append(row)
                bar.set_postfix_str("%s alpha %.4g: %s" % (plan.points[i]["top"], plan.points[i]["alpha"],
                                                            r["outcome"]), refresh=False)
                bar.update(1)
    finally:
        client.close(timeout=10)
        if cluster is not None:
            cluster.close(timeout=10)
    return workers, lost


# ---- the summary --------------------------------------------------------------------------------------------------

def column(plan, rows, name):
    k = plan.header.split(",").index(name)
    return [row.split(",")[k] for row in rows]


def spread(values):
    v = np.array(values, dtype=float)
    q = np.quantile(v, [0.05, 0.5, 0.95])
    sd = float(np.std(v, ddof=1)) if len(v) > 1 else 0.0
    return ("mean %.9g rad, standard deviation %.3g rad, 5 / 50 / 95 %% quantiles %.9g / %.9g / %.9g rad"
            % (float(np.mean(v)), sd, q[0], q[1], q[2]))


def monte_carlo_summary(plan, rows):
    """The spread of phi* over the samples: measured (the sleeping ones) and analytic, and the outcomes."""
    outcomes = column(plan, rows, "outcome")
    counts = collections.Counter(outcomes)
    lines = ["top_sim.sweep: Monte Carlo, %d samples: %s" % (len(rows), ", ".join(
        "%d %s" % (n, name) for name, n in sorted(counts.items())))]
    measured = [float(v) for v, o in zip(column(plan, rows, "phi_measured"), outcomes) if o == "sleeping"]
    analytic = [float(v) for v in column(plan, rows, "phi_star") if v != "nan"]
    if measured:
        lines.append("  phi* measured (%d sleeping samples): %s" % (len(measured), spread(measured)))
    if analytic:
        lines.append("  phi* analytic (%d samples with a sleeping state): %s" % (len(analytic), spread(analytic)))
    return "\n".join(lines)


def report(plan, rows, resumed, workers, wall, lost):
    """The summary on stderr; the exit status (3 when some row is a contact fault, 4 when points were lost)."""
    cpu = sum(float(c) for c in column(plan, rows, "cpu_seconds"))
    faults = 0
    for row, outcome in zip(rows, column(plan, rows, "outcome")):
        if outcome == "contact_fault":
            faults += 1
            print("top_sim.sweep: contact fault at %s" % row, file=sys.stderr)
    for i, message in lost:
        print("top_sim.sweep: point %d (%s) not run: %s" % (i, ",".join(plan.keys[i]), message), file=sys.stderr)
    print("top_sim.sweep: %d points (%d of them from the resumed file) on %d workers in %.3g s wall, %.4g s CPU"
          % (len(rows), resumed, workers, wall, cpu), file=sys.stderr)
    if plan.monte_carlo and rows:
        print(monte_carlo_summary(plan, rows), file=sys.stderr)
    return 4 if lost else 3 if faults else 0


def sweep(plan):
    """Runs the plan; the exit status. The file holds a header and complete rows at every moment."""
    wall0 = time.monotonic()
    out, rows = open_output(plan)
    resumed = len(rows)
    todo = pending_points(plan, rows)
    workers, lost = 0, []
    try:
        if todo:
            workers, lost = run_points(plan, todo, out, rows)
    except KeyboardInterrupt:
        print("\ntop_sim.sweep: interrupted; %s holds %d of %d points (--resume runs the rest)"
              % (plan.out, len(rows), len(plan.points)), file=sys.stderr)
        return 130
    finally:
        if out is not sys.stdout:
            out.close()
    if plan.out != "-" and not lost:
        write_in_grid_order(plan, rows)
    return report(plan, rows, resumed, workers, time.monotonic() - wall0, lost)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    try:
        plan = parse_arguments(argv)
        if plan is None:
            sys.stdout.write(USAGE)
            return 0
    except (BadArgument, _core.SceneError) as e:
        what = "bad grid point: " if isinstance(e, _core.SceneError) else ""
        sys.stderr.write("top_sim.sweep: %s%s\n%s" % (what, e, USAGE if not what else ""))
        return 2
    # SIGINT (also when started in the background, which ignores it) and SIGTERM as Ctrl-C: the rows so far stay.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    try:
        return sweep(plan)
    except BadArgument as e:
        sys.stderr.write("top_sim.sweep: %s\n" % e)
        return 2
    except ClusterError as e:
        sys.stderr.write("top_sim.sweep: %s\n" % e)
        return 4


if __name__ == "__main__":
    sys.exit(main())
