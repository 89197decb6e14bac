#!/usr/bin/env bash
# One command from a fresh Debian bookworm: install the packages, build everything, run the main job.
# Arguments go to scripts/run_main.sh (and so to roslaunch, e.g. rviz:=true).
set -euo pipefail
source "$(dirname "$0")/lib.sh"

bash "$TOP_SIM_REPO/scripts/install_deps.sh"
TOP_SIM_SKIP_DEPS=1 bash "$TOP_SIM_REPO/scripts/build.sh"
top_sim_log "running the main job: scripts/run_main.sh $*"
exec bash "$TOP_SIM_REPO/scripts/run_main.sh" "$@"
