#!/bin/bash
# Regenerates every measured table and figure of docs/performance.md (the tables in docs/performance/generated.md)
# at the checked-out commit, each table stamped
# with the commit, the time and the machine's load: the work-precision studies (docs/data/perf_*.csv), Google
# Benchmark (perf_bench.json), the work counts, a callgrind profile, the side-by-side comparison with earlier
# commits (scripts/bench_compare.sh), MuJoCo side by side (bench/peer_mujoco, where MuJoCo is found) and, with
# --node, many tops per node (bench/node_scale.py; needs the catkin build).
# usage: scripts/make_performance.sh [--quick] [--node] [BUILD_DIR]   (about 25 minutes on 2 cores; --quick: a smoke
#        run of the studies, one comparison round, 1 MuJoCo repetition)
# Environment: TOP_SIM_PERF_BASES (commits to compare with, default "c56d50f 8491f85"), TOP_SIM_BENCH_RUNS (5),
# TOP_SIM_BENCH_DIR (the comparison's builds, default BUILD_DIR/compare).
set -euo pipefail
source "$(dirname "$0")/lib.sh"
QUICK="" NODE=0
while [[ "${1:-}" == --* ]]; do
  case "$1" in
    --quick) QUICK="--quick" ;;
    --node) NODE=1 ;;
    *) top_sim_die "make_performance.sh: unknown option '$1' (allowed: --quick, --node)" ;;
  esac
  shift
done
BUILD=${1:-/tmp/build_perf}
ROOT=$TOP_SIM_REPO
DATA=$ROOT/docs/data
IMG=$ROOT/docs/img
GEN=$BUILD/generated
mkdir -p "$DATA" "$IMG" "$GEN"
rm -f "$GEN"/*.md

# "Measured at <commit> ...": what a table is true for. Uncommitted changes are named, never hidden.
stamp() {
  local rev dirty=""
  rev=$(git -C "$ROOT" rev-parse --short HEAD)
  git -C "$ROOT" diff --quiet HEAD -- src include bench cmake CMakeLists.txt scripts 2>/dev/null \
    || dirty=" plus uncommitted changes"
  echo "_Measured at ${rev}${dirty}, $(date -u '+%Y-%m-%d %H:%M') UTC, $(nproc) cores, load average" \
    "$(cut -d' ' -f1-3 /proc/loadavg) at the start; $1._"
}

cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DTOP_SIM_ROS=OFF -DTOP_SIM_TESTS=OFF \
  -DTOP_SIM_PYTHON=OFF > "$BUILD.cmake.log"
targets=(top_sim_study top_sim_run core_bench work_counts)
cmake --build "$BUILD" --target help | grep -w peer_mujoco > /dev/null && targets+=(peer_mujoco)
cmake --build "$BUILD" -j"$TOP_SIM_JOBS" --target "${targets[@]}" > "$BUILD.make.log"
BIN=$BUILD/bin

top_sim_log "work-precision studies"
{ stamp "top_sim_study: the work-precision, stability and per-scene tables that follow"; echo; } \
  > "$GEN/10_studies.md"
"$BIN/top_sim_study" $QUICK --config "$ROOT/config" --out "$DATA" all
/usr/bin/python3 "$ROOT/scripts/perf/plot_performance.py" "$DATA" "$IMG" "$GEN/11_study_tables.md"

top_sim_log "Google Benchmark"
"$BIN/core_bench" --benchmark_out="$DATA/perf_bench.json" --benchmark_out_format=json --benchmark_min_time=0.5 \
  --benchmark_repetitions=3 --benchmark_report_aggregates_only=true > /dev/null
/usr/bin/python3 "$ROOT/scripts/perf/bench_table.py" "$DATA/perf_bench.json" > "$BUILD/bench_table.md"
{ sed -n 1,2p "$BUILD/bench_table.md"; stamp "median of 3 repetitions"; sed -n '2,$p' "$BUILD/bench_table.md"; } \
  > "$GEN/20_bench.md"

top_sim_log "work counts"
{ echo "### Work counts (bench/work_counts.cpp): whole runs, one unread advance each"; echo
  stamp "deterministic counts: the same on any machine"; echo
  "$BIN/work_counts" "$ROOT/config"; echo; } > "$GEN/30_counts.md"

top_sim_log "callgrind"
if command -v valgrind > /dev/null; then
  scene=$(mktemp --suffix=.yaml)
  sed 's/^duration: .*/duration: 30.0/' "$ROOT/config/scenes/default.yaml" > "$scene"
  valgrind --tool=callgrind --callgrind-out-file="$BUILD/callgrind.out" "$BIN/top_sim_run" "$scene" \
    > "$BUILD.callgrind.log" 2>&1 || top_sim_die "callgrind of top_sim_run failed: $BUILD.callgrind.log"
  rm -f "$scene"
  callgrind_annotate --inclusive=no "$BUILD/callgrind.out" 2> /dev/null | sed -n '/PROGRAM TOTALS/,+31p' | cut -c1-160 \
    > "$DATA/perf_callgrind.txt"
  { echo "### callgrind: instructions per function, 30 s of the default scene"; echo
    stamp "instruction counts"; echo; echo '```'; cat "$DATA/perf_callgrind.txt"; echo '```'; } > "$GEN/90_callgrind.md"
fi

top_sim_log "side by side with earlier commits"
bases=${TOP_SIM_PERF_BASES:-c56d50f 8491f85}
runs=${TOP_SIM_BENCH_RUNS:-5}
[ -n "$QUICK" ] && runs=1
head=$(git -C "$ROOT" rev-parse --short HEAD)
compare_dir=${TOP_SIM_BENCH_DIR:-$BUILD/compare}  # keeps each commit's build: a second run rebuilds nothing
results=()
{ echo "### Side by side with earlier commits (scripts/bench_compare.sh)"; echo
  stamp "$runs interleaved rounds per base; CPU times, median; ratio HEAD / base: median (min-max) of the rounds"
  echo; } > "$GEN/40_compare.md"
for base in $bases; do
  b=$(git -C "$ROOT" rev-parse --short "$base^{commit}")
  TOP_SIM_BENCH_RUNS=$runs TOP_SIM_BENCH_DIR=$compare_dir bash "$ROOT/scripts/bench_compare.sh" "$b" "$head" >&2
  results+=("$compare_dir/results_${b}_${head}.txt")
done
/usr/bin/python3 "$ROOT/scripts/perf/compare_table.py" "$head" "${results[@]}" >> "$GEN/40_compare.md"
echo >> "$GEN/40_compare.md"

if [ -x "$BIN/peer_mujoco" ]; then
  top_sim_log "MuJoCo side by side"
  reps=9
  [ -n "$QUICK" ] && reps=1
  { echo "### MuJoCo side by side (bench/peer_mujoco)"; echo
    stamp "$reps repetitions, thread CPU time, medians"; echo
    "$BIN/peer_mujoco" --config "$ROOT/config" --reps "$reps" --csv "$DATA/peer_mujoco.csv"; echo; } > "$GEN/50_mujoco.md"
else
  { echo "### MuJoCo side by side"; echo; echo "Not measured: bench/peer_mujoco is not built (MuJoCo not found)."
    echo; } > "$GEN/50_mujoco.md"
fi

if [ "$NODE" = 1 ]; then
  top_sim_log "many tops per node"
  [ -f "$TOP_SIM_WS/devel/setup.bash" ] || top_sim_die "--node needs the catkin build ($TOP_SIM_WS): bash scripts/build.sh"
  set +u; source "$TOP_SIM_WS/devel/setup.bash"; set -u
  { echo "### Many tops per node (bench/node_scale.py)"; echo
    stamp "15 s per configuration after 5 s of warm-up"; echo
    /usr/bin/python3 "$ROOT/bench/node_scale.py" --seconds 15 --warmup 5 \
      --configs "1000:200,1000:200:cpu$(( $(nproc) - 1 )),1000:200:notf,1000:50" \
      --json "$DATA/node_scale.json" | sed -n '/^|/p'; echo; } > "$GEN/60_node_scale.md"
fi

# Splice the generated tables into docs/performance/generated.md between its markers (the prose around them is
# hand-written).
cat "$GEN"/*.md > "$BUILD/perf_tables.md"
/usr/bin/python3 - "$ROOT/docs/performance/generated.md" "$BUILD/perf_tables.md" <<'PY'
import pathlib, sys
doc, tables = (pathlib.Path(p) for p in sys.argv[1:])
text = doc.read_text()
begin, end = "<!-- BEGIN GENERATED -->", "<!-- END GENERATED -->"
head, rest = text.split(begin, 1)
note = "<!-- generated by scripts/make_performance.sh; do not edit -->\n"
doc.write_text(head + begin + "\n" + note + "\n" + tables.read_text() + rest[rest.index(end):])
PY
echo "docs/performance/generated.md updated; figures in $IMG/perf_*.png"
