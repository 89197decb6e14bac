#!/usr/bin/env bash
# The main job: top_sim_node streaming the default scene in real time (TopState, tf, markers, path),
# rviz off so it runs without a display. Extra arguments go to roslaunch, e.g. rviz:=true,
# scene:=$PWD/config/scenes/gyro_reversal.yaml, real_time_factor:=10, record:=true.
# Runs until Ctrl-C; steer it with: rostopic pub -1 /top_sim/inclination std_msgs/Float64 0.15
set -euo pipefail
export PATH=/usr/bin:$PATH
export ROS_HOSTNAME=${ROS_HOSTNAME:-localhost}
REPO=$(cd "$(dirname "$0")/.." && pwd)
WS=${TOP_SIM_WS:-$REPO/.catkin_ws}
set +u  # setup.bash reads unset variables
source "$WS/devel/setup.bash"
set -u
exec "$REPO/scripts/top_sim_launch" top_sim.launch rviz:=false "$@"  # roslaunch with the node's exit status
