#!/usr/bin/env bash
# Two commits side by side: builds each (plain CMake, Release, core + Python module, in scratch directories), then
# runs the core figures interleaved N times (BASE, HEAD, BASE, HEAD, ...) and prints each figure's CPU time per
# commit (median) and the ratio HEAD / BASE (median, min, max over the runs). Use it before any "not slower".
#   scripts/bench_compare.sh BASE [HEAD]          (HEAD defaults to the working tree's HEAD commit)
# Environment: TOP_SIM_BENCH_RUNS (default 5), TOP_SIM_BENCH_DIR (scratch, default /tmp/top_sim_bench_compare).
# Figures (CPU seconds as the tools report them; lower is better):
#   default_r1, default_r100, default_r1000: top_sim_run config/scenes/default.yaml --duration 300 --rate R (summary)
#   csv_us_per_row: (--rate 1000 --duration 60 with --csv) - (the same without), per row, in microseconds
#   hopping, coulomb: top_sim_run on config/scenes/hopping.yaml, coulomb.yaml (their durations)
#   python_trajectory: top_sim.Simulator('default').trajectory(60, 1000), process time
set -euo pipefail
export PATH=/usr/bin:$PATH
source "$(dirname "$0")/lib.sh"

[ $# -ge 1 ] || top_sim_die "usage: scripts/bench_compare.sh BASE [HEAD]"
base=$(git -C "$TOP_SIM_REPO" rev-parse --short "$1^{commit}") || top_sim_die "BASE = '$1': not a commit"
head=$(git -C "$TOP_SIM_REPO" rev-parse --short "${2:-HEAD}^{commit}") || top_sim_die "HEAD = '${2:-HEAD}': not a commit"
runs=${TOP_SIM_BENCH_RUNS:-5}
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || top_sim_die "TOP_SIM_BENCH_RUNS = '$runs': must be a whole number >= 1"
dir=${TOP_SIM_BENCH_DIR:-/tmp/top_sim_bench_compare}
mkdir -p "$dir"

# Sources of a commit (git archive: no checkout of the working tree) and a Release build of its core and module.
build() {
  local rev=$1 src=$dir/$1/src bld=$dir/$1/build
  if [ -z "$(tool "$rev")" ]; then
    rm -rf "$src" && mkdir -p "$src"
    git -C "$TOP_SIM_REPO" archive "$rev" | tar -x -C "$src"
    top_sim_log "building $rev in $bld"
    cmake -S "$src" -B "$bld" -DTOP_SIM_ROS=OFF -DCMAKE_BUILD_TYPE=Release -DTOP_SIM_TESTS=OFF \
      -DPython3_EXECUTABLE=/usr/bin/python3 >"$dir/$rev/cmake.log" 2>&1 \
      || top_sim_die "configure of $rev failed: $dir/$rev/cmake.log"
    cmake --build "$bld" -j"$TOP_SIM_JOBS" --target top_sim_run >"$dir/$rev/build.log" 2>&1 \
      || top_sim_die "build of $rev failed: $dir/$rev/build.log"
    [ -n "$(tool "$rev")" ] || top_sim_die "no top_sim_run built for $rev (see $dir/$rev/build.log)"
    cmake --build "$bld" -j"$TOP_SIM_JOBS" --target top_sim_python >>"$dir/$rev/build.log" 2>&1 \
      || top_sim_log "$rev has no Python module target: python_trajectory is left out for it"
  fi
}

# A commit's built top_sim_run (bin/ in plain builds; older commits may lay it out as catkin's devel/lib/top_sim).
tool() { find "$dir/$1/build" -name top_sim_run -type f -perm -u+x 2>/dev/null | head -1; }
# The directory to put on PYTHONPATH: the module's own (older commits: top_sim.cpython*.so) or the parent of the
# package top_sim/ that holds _core (since the physics module and the messages share one package).
python_dir() {
  local so
  so=$(find "$dir/$1/build" -name 'top_sim.cpython*.so' 2>/dev/null | head -1)
  if [ -n "$so" ]; then dirname "$so"; return 0; fi
  so=$(find "$dir/$1/build" -path '*/top_sim/_core.cpython*.so' 2>/dev/null | head -1)
  if [ -n "$so" ]; then dirname "$(dirname "$so")"; fi
  return 0
}

# CPU seconds top_sim_run reports on stdout ("... simulated in X s CPU ..."; older commits lack --quiet, and
# progress goes to stderr only on a terminal); "nan", after a message, when it reported none.
run_cpu() {
  local rev=$1; shift
  local cpu
  cpu=$("$(tool "$rev")" "$@" 2>/dev/null </dev/null | sed -n 's/.* simulated in \([0-9.e+-]*\) s CPU.*/\1/p' | head -1)
  [ -n "$cpu" ] || { echo "top_sim_run of $rev reported no CPU time for: $*" >&2; cpu=nan; }
  echo "$cpu"
}

# One round of every figure for one commit: lines "figure value".
round() {
  local rev=$1 src=$dir/$1/src
  for r in 1 100 1000; do echo "default_r$r $(run_cpu "$rev" "$src/config/scenes/default.yaml" --duration 300 --rate $r)"; done
  local with without
  with=$(run_cpu "$rev" "$src/config/scenes/default.yaml" --duration 60 --rate 1000 --csv "$dir/rows.csv")
  without=$(run_cpu "$rev" "$src/config/scenes/default.yaml" --duration 60 --rate 1000)
  echo "csv_us_per_row $(/usr/bin/python3 -c "print(max(0.0, (float('$with') - float('$without')) / 60001 * 1e6))")"
  echo "hopping $(run_cpu "$rev" "$src/config/scenes/hopping.yaml")"
  echo "coulomb $(run_cpu "$rev" "$src/config/scenes/coulomb.yaml")"
  local pydir
  pydir=$(python_dir "$rev")
  [ -n "$pydir" ] && [ "$pydir" != . ] || return 0
  echo "python_trajectory $(PYTHONPATH="$pydir" /usr/bin/python3 -c "
import time, top_sim
s = top_sim.Simulator('default'); t0 = time.process_time(); s.trajectory(60.0, 1000.0)
print(time.process_time() - t0)")"
}

build "$base"
build "$head"
results=$dir/results_${base}_${head}.txt
: >"$results"
for ((k = 1; k <= runs; ++k)); do
  top_sim_log "round $k of $runs"
  for rev in "$base" "$head"; do round "$rev" | sed "s/^/$k $rev /" >>"$results"; done
done

/usr/bin/python3 - "$results" "$base" "$head" <<'EOF'
import statistics, sys
path, base, head = sys.argv[1:4]
data = {}
for line in open(path):
    k, rev, fig, value = line.split()
    if value != 'nan':  # a run that reported nothing (said so on stderr) is left out
        data.setdefault(fig, {}).setdefault(rev, {})[int(k)] = float(value)
print(f"{'figure':22} {base + ' (median)':>18} {head + ' (median)':>18} {'ratio med':>10} {'min':>7} {'max':>7}")
for fig, by in data.items():
    b, h = by.get(base, {}), by.get(head, {})
    if not b or not h:
        print(f"{fig:22} (measured for {base if b else head} only)")
        continue
    ratios = [h[k] / b[k] for k in b if k in h and b[k] > 0]
    unit = ' us' if fig.endswith('us_per_row') else ' s'
    print(f"{fig:22} {statistics.median(b.values()):>16.4g}{unit} {statistics.median(h.values()):>16.4g}{unit} "
          f"{statistics.median(ratios):>10.3f} {min(ratios):>7.3f} {max(ratios):>7.3f}")
print(f"(interleaved runs; CPU times; ratio < 1: {head} is faster)")
EOF
