#!/bin/bash
# Regenerates every table and figure of docs/performance.md: builds top_sim_study and core_bench, runs the studies
# (docs/data/perf_*.csv), the benchmark (docs/data/perf_bench.json), a callgrind profile, and the plots.
# usage: scripts/make_performance.sh [BUILD_DIR]    (about 10 minutes on 2 cores; --quick for a smoke run)
set -euo pipefail
export PATH=/usr/bin:$PATH
ROOT=$(cd "$(dirname "$0")/.." && pwd)
QUICK=""
if [[ "${1:-}" == "--quick" ]]; then QUICK="--quick"; shift; fi
BUILD=${1:-/tmp/build_perf}
DATA=$ROOT/docs/data
IMG=$ROOT/docs/img
mkdir -p "$DATA" "$IMG"

cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DTOP_SIM_ROS=OFF -DTOP_SIM_TESTS=OFF \
  -DTOP_SIM_PYTHON=OFF > "$BUILD.cmake.log"
make -C "$BUILD" -j2 top_sim_study top_sim_run core_bench > "$BUILD.make.log"
STUDY=$BUILD/bin/top_sim_study
BENCH=$BUILD/bin/core_bench

"$STUDY" $QUICK --config "$ROOT/config" --out "$DATA" all
"$BENCH" --benchmark_out="$DATA/perf_bench.json" --benchmark_out_format=json --benchmark_min_time=0.5 \
  --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

# Where the cost is: instructions per function for 30 s of the default scene (repeatable, unlike timings).
if command -v valgrind > /dev/null; then
  SCENE=$(mktemp --suffix=.yaml)
  sed 's/^duration: .*/duration: 30.0/' "$ROOT/config/scenes/default.yaml" > "$SCENE"
  valgrind --tool=callgrind --callgrind-out-file="$BUILD/callgrind.out" "$(find_bin top_sim_run)" "$SCENE" \
    > /dev/null 2>&1 || true
  callgrind_annotate --inclusive=no "$BUILD/callgrind.out" 2> /dev/null | sed -n '1,40p' | cut -c1-160 \
    > "$DATA/perf_callgrind.txt"
  rm -f "$SCENE"
fi

/usr/bin/python3 "$ROOT/scripts/perf/plot_performance.py" "$DATA" "$IMG" "$BUILD/perf_tables.md"
/usr/bin/python3 "$ROOT/scripts/perf/bench_table.py" "$DATA/perf_bench.json" >> "$BUILD/perf_tables.md"
# Splice the generated tables into docs/performance.md between its markers (the prose around them is hand-written).
/usr/bin/python3 - "$ROOT/docs/performance.md" "$BUILD/perf_tables.md" "$DATA/perf_callgrind.txt" <<'PY'
import pathlib, sys
doc, tables, cg = (pathlib.Path(p) for p in sys.argv[1:])
text = doc.read_text()
begin, end = "<!-- BEGIN GENERATED -->", "<!-- END GENERATED -->"
gen = tables.read_text()
if cg.exists():
    gen += "\n### callgrind: instructions per function, 30 s of the default scene\n\n```\n" + cg.read_text() + "```\n"
head, rest = text.split(begin, 1)
doc.write_text(head + begin + "\n" + gen + rest[rest.index(end):])
PY
echo "docs/performance.md updated; figures in $IMG/perf_*.png"
