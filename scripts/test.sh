#!/usr/bin/env bash
# Runs the whole test suite, installing and building first if needed. Two builds, one per configuration:
#   1. the catkin package in Release (scripts/build.sh, as quickstart.sh builds it: the core, its tools and Python
#      module, the node), then `catkin_make tests` (the core's GoogleTest suite, the header check, the ROS tests);
#   2. the core's tests through ctest in that build (GoogleTest in shards, pytest of the Python module, the
#      install/find_package check, the MuJoCo and LCM checks), two at a time;
#   3. the core's GoogleTest suite again under AddressSanitizer + UBSan, a plain CMake build without ROS
#      (TOP_SIM_SANITIZERS=0 skips it), in two shards at once;
#   4. the ROS package's gtests and rostests through catkin's run_tests, one at a time.
# Prints every test case, a summary, and as the last line `N passed, N failed`.
# Exit 0 only if the builds succeeded, at least one test ran, and no test failed or errored.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

status=0   # becomes 1 on any failure; the counts line is printed in every case
sanitizer_failed=0
timeout_s=${TOP_SIM_TEST_TIMEOUT:-3000}
mkdir -p "$TOP_SIM_WS"
TOP_SIM_WS=$(cd "$TOP_SIM_WS" && pwd -P)
results=$TOP_SIM_WS/build/test_results          # catkin's run_tests
package_build=$TOP_SIM_WS/build/top_sim         # the package's own build directory in the workspace
core_results=$package_build/test_results        # ctest's and the sanitized suite's (TOP_SIM_TEST_RESULTS)
rm -rf "$results" "$core_results"   # only this run's results are counted

if ! bash "$TOP_SIM_REPO/scripts/install_deps.sh"; then
  top_sim_log "INSTALLING THE DEBIAN PACKAGES FAILED"; status=1
fi

# ---- 1. the catkin package in Release, then its tests' binaries -------------------------------------------------
if [ "$status" -eq 0 ] && ! TOP_SIM_SKIP_DEPS=1 bash "$TOP_SIM_REPO/scripts/build.sh"; then
  top_sim_log "BUILD FAILED"; status=1
fi
if [ "$status" -eq 0 ]; then
  top_sim_log "building the tests (catkin_make tests: the core's and the ROS package's)"
  if ! top_sim_catkin_make -j"$TOP_SIM_JOBS" tests; then
    top_sim_log "BUILD FAILED (tests)"; status=1
  fi
fi

# LCM's default UDP multicast URL needs a multicast route; a sandbox without one gets it on loopback.
if [ "$(id -u)" -eq 0 ] && command -v ip >/dev/null 2>&1 && [ -z "$(ip route show 224.0.0.0/4 2>/dev/null)" ]; then
  ip route add 224.0.0.0/4 dev lo 2>/dev/null && top_sim_log "added multicast route 224.0.0.0/4 dev lo" || true
fi

# ---- 2. the core's tests through ctest (catkin's own _ctest_ entries run in step 4) -----------------------------
if [ "$status" -eq 0 ]; then
  top_sim_log "running the core's tests (ctest in $package_build, -j$TOP_SIM_JOBS)"
  # ctest's verdict is read from the JUnit XML below; a non-zero exit here is a failing test, already counted.
  timeout --kill-after=30 "$timeout_s" ctest --test-dir "$package_build" -E '^_ctest_' -j"$TOP_SIM_JOBS" \
    --output-on-failure --output-junit "$core_results/ctest.xml" \
    || top_sim_log "ctest reported failures (listed below)"
fi

# ---- 3. the core's tests again under AddressSanitizer + UBSan (TOP_SIM_SANITIZERS=0 skips) ---------------------
if [ "$status" -eq 0 ] && [ "${TOP_SIM_SANITIZERS:-1}" != 0 ]; then
  if ! top_sim_sanitized_build; then
    top_sim_log "SANITIZER BUILD FAILED"; status=1
  else
    top_sim_log "running the core's tests under AddressSanitizer + UBSan (2 shards at once)"
    # A sanitizer report aborts the test binary: its XML is then missing or failing, and counted below.
    sanitized=$core_results/sanitized
    mkdir -p "$sanitized"
    pids=()
    for shard in 0 1; do
      mkdir -p "$sanitized/tmp$shard"
      GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=$shard TEST_TMPDIR="$sanitized/tmp$shard/" \
        timeout --kill-after=30 "$timeout_s" "$TOP_SIM_BUILD-sanitize/bin/top_sim_core_tests" \
        --gtest_output="xml:$sanitized/core_tests_asan_ubsan_$shard.xml" >"$sanitized/log$shard.txt" 2>&1 &
      pids+=($!)
    done
    for shard in 0 1; do
      if ! wait "${pids[$shard]}"; then
        top_sim_log "SANITIZED CORE TESTS FAILED (shard $shard; last lines of its log:)"
        tail -40 "$sanitized/log$shard.txt" >&2
        sanitizer_failed=1   # the ROS stage still runs; the verdict below counts this
      fi
    done
  fi
fi

# ---- 4. the ROS package's tests: catkin's run_tests --------------------------------------------------------------
if [ "$status" -eq 0 ]; then
  # One test at a time (-j1): tests share 2 cores, ROS masters and LCM channels. The timeout stops a hung test.
  top_sim_log "running the ROS package's tests"
  set +e
  timeout --kill-after=30 "$timeout_s" bash -c \
    'source "$1/scripts/lib.sh" && top_sim_catkin_make -j1 run_tests' _ "$TOP_SIM_REPO"
  rc=$?
  set -e
  # run_tests exits 0 even when tests fail (the verdict comes from the XML below); non-zero means it broke.
  if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
    top_sim_log "run_tests TIMED OUT after $timeout_s s"; status=1
  elif [ "$rc" -ne 0 ]; then
    top_sim_log "run_tests FAILED (exit $rc)"; status=1
  fi
fi

[ "$sanitizer_failed" -eq 0 ] || status=1
set +e
/usr/bin/python3 - "$status" "$core_results" "$results" <<'PY'
# Counts test cases in the JUnit XML files of catkin's test_results directory.
import os, sys
import xml.etree.ElementTree as ET

earlier_failure = sys.argv[1] != '0'   # install, build or run_tests failed before any XML was read
root_dirs = sys.argv[2:]
files = []
for root_dir in root_dirs:
    for dirpath, dirnames, filenames in os.walk(root_dir):
        dirnames.sort()
        files += [(root_dir, os.path.join(dirpath, f)) for f in sorted(filenames) if f.endswith('.xml')]

def first_lines(text, n=20):
    lines = text.strip().splitlines()
    return lines[:n] + (['... (%d more lines)' % (len(lines) - n)] if len(lines) > n else [])

def wrapper_duplicate(path, case, failed):
    # rostest writes rostest-*.xml with one case "test<node>" per test node next to the node's own
    # rosunit-<node>.xml; a passing wrapper case only says that file exists, so it is not counted twice.
    base = os.path.basename(path)
    name = case.get('name', '')
    # ctest.xml has one case per ctest test; a passing one whose suite wrote <name>.xml is counted there.
    if base == 'ctest.xml':
        return not failed and os.path.isfile(os.path.join(os.path.dirname(path), name + '.xml'))
    return (base.startswith('rostest-') and not failed and name.startswith('test')
            and os.path.isfile(os.path.join(os.path.dirname(path), 'rosunit-%s.xml' % name[4:])))

passed = failed = skipped = 0
per_file = []
for root_dir, path in files:
    name = ('core/' if root_dir == root_dirs[0] else 'catkin/') + os.path.relpath(path, root_dir)
    out = ['== %s' % name]
    try:
        tree = ET.parse(path)
    except ET.ParseError as e:
        # An unreadable result file means a test that did not finish cleanly.
        print('\n'.join(out))
        print('FAIL  %s (unreadable JUnit XML: %s)' % (name, e))
        failed += 1
        per_file.append((name, 0, 1, 0))
        continue
    fp = ff = fs = 0
    for case in tree.getroot().iter('testcase'):
        label = '%s.%s' % (case.get('classname', ''), case.get('name', ''))
        problems = case.findall('failure') + case.findall('error')
        if wrapper_duplicate(path, case, bool(problems)):
            continue
        if problems:
            ff += 1
            out.append('FAIL  %s (%s s)' % (label, case.get('time', '?')))
            for p in problems:
                message, text = (p.get('message') or '').strip(), (p.text or '').strip()
                body = text if message in text else message + '\n' + text
                for line in first_lines(body):
                    out.append('        ' + line)
        elif case.find('skipped') is not None or case.get('status') == 'notrun' \
                or case.get('result') in ('skipped', 'suppressed'):
            fs += 1
            out.append('SKIP  %s' % label)
        else:
            fp += 1
            out.append('PASS  %s (%s s)' % (label, case.get('time', '?')))
    if len(out) == 1 and os.path.basename(path).startswith('rostest-'):
        continue   # a rostest wrapper whose nodes all reported: their own files hold the cases
    print('\n'.join(out))
    passed += fp; failed += ff; skipped += fs
    per_file.append((name, fp, ff, fs))

print()
print('Summary (%s):' % ', '.join(root_dirs))
for name, fp, ff, fs in per_file:
    print('  %-56s %4d passed %4d failed %4d skipped' % (name, fp, ff, fs))
if not files:
    print('  no JUnit result files: no test ran')
if skipped:
    print('%d skipped or disabled (not counted below)' % skipped)
if failed or passed == 0 or earlier_failure:
    print('TEST SUITE FAILED' + (' (install, build or run_tests failed: see above)' if earlier_failure else ''))
print('%d passed, %d failed' % (passed, failed))
sys.exit(1 if failed or passed == 0 else 0)
PY
verdict=$?
set -e
[ "$verdict" -eq 0 ] || status=1
exit "$status"   # nothing printed after the counts: they stay the last line
