#!/usr/bin/env bash
# Builds top_sim (Release) in the catkin workspace $TOP_SIM_WS (default <repo>/.catkin_ws), installing the
# Debian packages first if any is missing (set TOP_SIM_SKIP_DEPS=1 to skip that check).
# Extra arguments go to catkin_make, e.g. `bash scripts/build.sh tests`.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

if [ "${TOP_SIM_SKIP_DEPS:-0}" != 1 ]; then
  bash "$TOP_SIM_REPO/scripts/install_deps.sh"
fi

# The workspace's only package is a symlink to this repository.
mkdir -p "$TOP_SIM_WS/src"
TOP_SIM_WS=$(cd "$TOP_SIM_WS" && pwd -P)   # physical path, as catkin_make records it in CMakeCache.txt
link=$TOP_SIM_WS/src/top_sim
if [ -L "$link" ]; then
  [ "$(readlink -f "$link")" = "$TOP_SIM_REPO" ] || ln -sfn "$TOP_SIM_REPO" "$link"
elif [ -e "$link" ]; then
  top_sim_die "$link exists and is not a symlink to $TOP_SIM_REPO; move it away or set TOP_SIM_WS"
else
  ln -s "$TOP_SIM_REPO" "$link"
fi

# A build tree configured for another source path (workspace moved or copied) cannot be reused.
cache=$TOP_SIM_WS/build/CMakeCache.txt
if [ -f "$cache" ]; then
  configured=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$cache")
  if [ "$configured" != "$TOP_SIM_WS/src" ]; then
    top_sim_log "build tree was configured for '$configured', not '$TOP_SIM_WS/src': removing build/ and devel/"
    rm -rf "$TOP_SIM_WS/build" "$TOP_SIM_WS/devel"
  fi
fi

top_sim_log "catkin_make in $TOP_SIM_WS (-j$TOP_SIM_JOBS) $*"
top_sim_catkin_make -j"$TOP_SIM_JOBS" "$@"

# catkin freezes the environment of run_tests (build/catkin_generated/setup_cached.sh) at configure time,
# before the first build creates the generated Python messages; without a second configure the Python
# rostests cannot import top_sim.msg.
cached=$TOP_SIM_WS/build/catkin_generated/setup_cached.sh
for pydir in "$TOP_SIM_WS"/devel/lib/python3*/dist-packages; do
  if [ -d "$pydir" ] && [ -f "$cached" ] && ! grep -qF "$pydir" "$cached"; then
    top_sim_log "configuring again so that run_tests sees $pydir"
    top_sim_catkin_make --force-cmake -j"$TOP_SIM_JOBS" "$@"
    grep -qF "$pydir" "$cached" || top_sim_die "$cached still lacks $pydir after a second configure"
  fi
done
