#!/usr/bin/env bash
# env-loader of roslaunch's <machine> tag (launch/distributed.launch, docs/ros.md Distribution). On a remote host
# roslaunch runs, over ssh, `env ROS_MASTER_URI=URI THIS_SCRIPT roslaunch -c ...`: this sets up that host's ROS
# environment (the top_sim workspace, and the address other hosts reach this one at) and runs the command.
#   TOP_SIM_WS      workspace to source (default: the .catkin_ws beside this script, as scripts/lib.sh)
#   ROS_IP / ROS_HOSTNAME   kept when set; else ROS_IP = this host's source address on the route to the master
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
ws=${TOP_SIM_WS:-$here/../.catkin_ws}
die() { printf 'env_loader.sh on %s: %s\n' "$(hostname)" "$*" >&2; exit 1; }

[ "$#" -gt 0 ] || die "usage: env_loader.sh COMMAND [ARG ...]"
setup=$ws/devel/setup.bash
[ -f "$setup" ] || die "$setup not found: build top_sim on this host (scripts/build.sh) or set TOP_SIM_WS"
# catkin's setup scripts read unset variables.
set +u
source "$setup"
set -u

if [ -z "${ROS_IP:-}" ] && [ -z "${ROS_HOSTNAME:-}" ]; then
  [ -n "${ROS_MASTER_URI:-}" ] || die "neither ROS_IP, ROS_HOSTNAME nor ROS_MASTER_URI is set"
  master_host=${ROS_MASTER_URI#*://}
  master_host=${master_host%%[:/]*}
  master_ip=$(getent ahostsv4 "$master_host" | awk 'NR == 1 {print $1}' || true)
  [ -n "$master_ip" ] || die "cannot resolve the master's host '$master_host' (ROS_MASTER_URI=$ROS_MASTER_URI)"
  # The address this host sends from towards the master is one the master's host can reach it at.
  ROS_IP=$(ip -4 route get "$master_ip" 2>/dev/null | sed -n 's/.* src \([0-9.]*\).*/\1/p' || true)
  [ -n "$ROS_IP" ] || die "no route to the master $master_ip: set ROS_IP or ROS_HOSTNAME in this script's environment"
  export ROS_IP
fi
exec "$@"
