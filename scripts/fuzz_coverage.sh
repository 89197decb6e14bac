#!/usr/bin/env bash
# Source-based coverage (clang 14, llvm-profdata-14, llvm-cov-14) of the fuzz targets over a corpus, for the files of
# bodies of shapes, the patch law, the pair solve and the auto handover (docs/reliability.md, "Coverage of the new
# physics"). Builds $TOP_SIM_BUILD-cov (the libFuzzer targets with -fprofile-instr-generate -fcoverage-mapping),
# replays each corpus once (-runs=0) and prints one llvm-cov report per target, plus the pair solve's functions.
#   usage: scripts/fuzz_coverage.sh [corpus root, default $TOP_SIM_BUILD-fuzz/fuzz (what scripts/fuzz.sh left);
#          test/fuzz/corpus for the seeds] [target ...]
set -euo pipefail
source "$(dirname "$0")/lib.sh"

root=${1:-$TOP_SIM_BUILD-fuzz/fuzz}
[ "$#" -gt 0 ] && shift
targets=("$@")
[ "${#targets[@]}" -gt 0 ] || targets=(scene_loader command step)
build=$TOP_SIM_BUILD-cov
files=(src/core/shape_motion.cpp src/core/contact_shapes.cpp src/core/patch_law.hpp src/core/finite_contact.cpp
       src/core/auto_handover.cpp)
# The pair solve: two_shape_motion and its helpers in shape_motion.cpp (physics.md 13.4).
pair='pair_response|balance_friction|stuck_pair|both_slipping|two_shape_motion|touching_pair_motion|pair_contact_margin|apply_pair_stick_impulse'
flags="-fprofile-instr-generate -fcoverage-mapping"

CC=clang CXX=clang++ cmake -S "$TOP_SIM_REPO" -B "$build" -DTOP_SIM_FUZZ=ON -DTOP_SIM_ROS=OFF -DTOP_SIM_PYTHON=OFF \
  -DTOP_SIM_TESTS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS=-fprofile-instr-generate -DCMAKE_SHARED_LINKER_FLAGS=-fprofile-instr-generate >/dev/null
nice -n 19 cmake --build "$build" -j"$TOP_SIM_JOBS" --target "${targets[@]/#/fuzz_}" >/dev/null
mkdir -p "$build/cov"
cd "$TOP_SIM_REPO"
for t in "${targets[@]}"; do
  rm -f "$build/cov/$t.profraw"
  LLVM_PROFILE_FILE="$build/cov/$t.profraw" nice -n 19 "$build/bin/fuzz_$t" -runs=0 "$root/$t" 2>&1 | grep -E '^Done' || true
  llvm-profdata-14 merge -sparse "$build/cov/$t.profraw" -o "$build/cov/$t.profdata"
  objects=("$build/lib/libtop_sim_core.so" -object "$build/bin/fuzz_$t" -instr-profile="$build/cov/$t.profdata")
  echo "== $t over $(find "$root/$t" -type f | wc -l) files of $root/$t"
  llvm-cov-14 report "${objects[@]}" "${files[@]}" 2>/dev/null
  # Regions and lines of the pair solve's functions, summed from the per-function report.
  llvm-cov-14 report -show-functions "${objects[@]}" src/core/shape_motion.cpp 2>/dev/null |
    awk -v re="$pair" '$1 ~ re { n++; r += $2; rm += $3; l += $5; lm += $6 }
      END { printf "pair solve (%d functions): regions %d, missed %d (%.2f%%); lines %d, missed %d (%.2f%%)\n",
            n, r, rm, r ? 100 * (r - rm) / r : 0, l, lm, l ? 100 * (l - lm) / l : 0 }'
done
