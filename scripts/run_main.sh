#!/usr/bin/env bash
# The main job: the default scene. (Run by scripts/quickstart.sh after the build.)
set -euo pipefail
export PATH=/usr/bin:$PATH
REPO=$(cd "$(dirname "$0")/.." && pwd)
WS=${TOP_SIM_WS:-$REPO/.catkin_ws}
source "$WS/devel/setup.bash"
exec "$WS/devel/lib/top_sim/top_sim_run" "$REPO/config/scenes/default.yaml" --summary - "$@"
