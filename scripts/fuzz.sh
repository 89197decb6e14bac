#!/usr/bin/env bash
# Fuzzes the core with libFuzzer (clang, docs/reliability.md "Fuzzing"): builds fuzz_scene_loader, fuzz_command and
# fuzz_step with ASan + UBSan in $TOP_SIM_BUILD-fuzz, runs each in turn for a bounded time on a copy of
# test/fuzz/corpus/<target>/ and prints one line per target: executions, exec/s, coverage (cov, ft), corpus size,
# findings. A finding (crash-*, timeout-*, oom-*, leak-*) lands in $TOP_SIM_BUILD-fuzz/fuzz/<target>/findings/;
# nothing is written into test/fuzz/corpus (add a fixed finding there by hand, named finding-*).
#   usage: scripts/fuzz.sh [seconds per target, default 60] [target ...]   (targets: scene_loader command step)
#   environment: TOP_SIM_FUZZ_TIMEOUT (s per input, default 30), TOP_SIM_FUZZ_RSS_MB (default 2048),
#   TOP_SIM_FUZZ_NICE (the fuzzers' niceness, default 19; at 19 other jobs' compilers starve them on a busy machine)
# Exit status: 0 when no target found anything, 1 when one did, 2 for a bad argument or a failed build.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

seconds=${1:-60}
[ "$#" -gt 0 ] && shift
[[ "$seconds" =~ ^[0-9]+$ ]] && [ "$seconds" -gt 0 ] || { top_sim_log "seconds must be a positive integer"; exit 2; }
targets=("$@")
[ "${#targets[@]}" -gt 0 ] || targets=(scene_loader command step)
build=$TOP_SIM_BUILD-fuzz
# Wall-clock, and nice 19 on a shared machine: the slowest inputs take ~2 s alone, 13 s were seen under load.
timeout_per_input=${TOP_SIM_FUZZ_TIMEOUT:-30}
rss_mb=${TOP_SIM_FUZZ_RSS_MB:-2048}
niceness=${TOP_SIM_FUZZ_NICE:-19}
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
command -v llvm-symbolizer >/dev/null 2>&1 && export ASAN_SYMBOLIZER_PATH=$(command -v llvm-symbolizer)

for t in "${targets[@]}"; do
  [ -d "$TOP_SIM_REPO/test/fuzz/corpus/$t" ] || { top_sim_log "unknown target '$t' (scene_loader, command, step)"; exit 2; }
done
command -v clang++ >/dev/null 2>&1 || { top_sim_log "clang++ not found (Debian: apt-get install clang)"; exit 2; }

top_sim_log "libFuzzer build (clang, ASan + UBSan) in $build (-j$TOP_SIM_JOBS)"
CC=clang CXX=clang++ cmake -S "$TOP_SIM_REPO" -B "$build" -DTOP_SIM_FUZZ=ON -DTOP_SIM_ROS=OFF -DTOP_SIM_PYTHON=OFF \
  -DTOP_SIM_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null || exit 2
nice -n 19 cmake --build "$build" -j"$TOP_SIM_JOBS" --target "${targets[@]/#/fuzz_}" >/dev/null || exit 2

# Runs one target on a fresh copy of its seeds; its log, corpus and findings stay in $build/fuzz/<target>/.
run_target() {
  local name=$1 work=$build/fuzz/$1
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/findings"
  cp -R "$TOP_SIM_REPO/test/fuzz/corpus/$name/." "$work/corpus/"
  local extra=()
  [ -f "$TOP_SIM_REPO/test/fuzz/$name.dict" ] && extra+=("-dict=$TOP_SIM_REPO/test/fuzz/$name.dict")
  top_sim_log "fuzzing $name for $seconds s (log: $work/log.txt)"
  local start=$SECONDS
  nice -n "$niceness" "$build/bin/fuzz_$name" "$work/corpus" "${extra[@]}" -max_total_time="$seconds" \
    -timeout="$timeout_per_input" -rss_limit_mb="$rss_mb" -max_len=4096 -print_final_stats=1 \
    -artifact_prefix="$work/findings/" >"$work/log.txt" 2>&1 || true
  echo $((SECONDS - start)) >"$work/seconds"   # a finding stops the target early
}

# One line from the log: the last status line's cov, ft and corpus, the final stats' executions and exec/s.
report_target() {
  local name=$1 work=$build/fuzz/$1 status execs rate cov ft findings
  status=$(grep -E '^#[0-9]+.*cov: ' "$work/log.txt" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$status")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$status")
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log.txt")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/log.txt")
  findings=$(find "$work/findings" -type f | wc -l)
  printf '%-13s %6s s  executions %-10s exec/s %-6s cov %-6s ft %-7s corpus %-5s findings %s\n' "$name" "$(cat "$work/seconds")" \
    "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$(find "$work/corpus" -type f | wc -l)" "$findings"
  [ "$findings" -eq 0 ] && ! grep -q -E '^==[0-9]+==ERROR|invariant broken|deadly signal' "$work/log.txt"
}

found=0
for t in "${targets[@]}"; do run_target "$t"; done
for t in "${targets[@]}"; do
  report_target "$t" || { found=1; top_sim_log "FINDING in $t: $build/fuzz/$t/findings/ (see $build/fuzz/$t/log.txt)"; }
done
exit "$found"
