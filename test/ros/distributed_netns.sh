#!/usr/bin/env bash
# Two hosts, one ROS graph: network namespaces A and B joined by a veth pair (10.213.0.1/24 and .2/24, names with this
# process id, so parallel runs do not collide). A runs the master, group_a of launch/distributed.launch and the
# checker (test_distributed.py, pytest); B runs group_b through scripts/env_loader.sh, as roslaunch's <machine>
# tag would over ssh, with ROS_MASTER_URI on A's address and no ROS_IP (the loader finds it).
# Where namespaces are not permitted (not root, no `ip`, `ip netns add` fails) the checker reports one skipped case.
#   distributed_netns.sh RESULT.xml CATKIN_WORKSPACE      (run by catkin run_tests; with the workspace sourced)
# Writes JUnit XML to RESULT.xml; stops and removes everything it started on any exit.
set -uo pipefail

result=$1
export TOP_SIM_WS=$2   # the workspace env_loader.sh sources in B
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
repo=$(cd "$here/../.." && pwd -P)
ns_a=top_sim_a_$$ ns_b=top_sim_b_$$
veth_a=tsa$$ veth_b=tsb$$   # interface names: at most 15 characters
ip_a=10.213.0.1 ip_b=10.213.0.2
master_uri=http://$ip_a:11311   # each namespace has its own ports: no clash with other masters
alpha_b=0.15 spin_b=-150.0      # group_b's start values, given to the launch and checked by the checker
tmp=$(mktemp -d /tmp/top_sim_netns.XXXXXX)
export ROS_HOME=$tmp/ros_home ROS_LOG_DIR=$tmp/log
started=()   # process ids of what this script started in the namespaces
made_ns=()

t0=${EPOCHREALTIME/./}   # microseconds
log() {
  local ds=$(((${EPOCHREALTIME/./} - t0) / 100000))
  printf '[distributed_netns %d.%d s] %s\n' $((ds / 10)) $((ds % 10)) "$*" >&2
}

# False once pid has exited (a zombie not yet reaped counts as exited).
running() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 1
  stat=${stat##*) }
  [ "${stat%% *}" != Z ]
}

# The last started first (the roslaunches, then the master they unregister from): SIGINT lets roslaunch stop its
# nodes, up to 5 s each; whatever is left in our namespaces (the nodes run in their own sessions) is then killed.
cleanup() {
  local pid ns i j
  for ((i = ${#started[@]} - 1; i >= 0; i--)); do
    pid=${started[i]}
    kill -INT "$pid" 2>/dev/null || continue
    for ((j = 0; j < 50; j++)); do running "$pid" || break; sleep 0.1; done
  done
  for ns in "${made_ns[@]}"; do
    for pid in $(ip netns pids "$ns" 2>/dev/null); do log "killing $pid, left in $ns"; kill -KILL "$pid" 2>/dev/null; done
    ip netns del "$ns" 2>/dev/null || log "could not delete network namespace $ns"
  done
  rm -rf "$tmp"
  log "stopped and removed"
}
trap cleanup EXIT
trap 'exit 143' TERM
trap 'exit 130' INT

# The environment of each host: B's ROS_IP is left to scripts/env_loader.sh.
env_a=(env -u ROS_HOSTNAME ROS_IP="$ip_a" ROS_MASTER_URI="$master_uri")
env_b=(env -u ROS_HOSTNAME -u ROS_IP ROS_MASTER_URI="$master_uri")

run_checker() {
  # -c /dev/null: no pytest configuration of the source tree applies; no cache directory is written.
  "$@" timeout -k 5 35 python3 -m pytest -c /dev/null --rootdir="$here" -p no:cacheprovider -W ignore::DeprecationWarning \
    -q -s -o junit_family=xunit1 \
    -o junit_suite_name=distributed_netns --junitxml="$result" "$here/test_distributed.py"
}

# Why network namespaces cannot be used here (empty when they can): root and `ip` are needed.
skip_reason() {
  if [ "$(id -u)" -ne 0 ]; then echo "network namespaces need root (uid $(id -u))"; return; fi
  command -v ip >/dev/null 2>&1 || echo "no 'ip' command (Debian package iproute2)"
}

# Namespace B, the veth pair, addresses, loopback; false with a message on the first failure.
make_hosts() {
  ip netns add "$ns_b" && made_ns+=("$ns_b") &&
    ip link add "$veth_a" netns "$ns_a" type veth peer name "$veth_b" netns "$ns_b" &&
    ip -n "$ns_a" addr add "$ip_a/24" dev "$veth_a" && ip -n "$ns_b" addr add "$ip_b/24" dev "$veth_b" &&
    ip -n "$ns_a" link set lo up && ip -n "$ns_b" link set lo up &&
    ip -n "$ns_a" link set "$veth_a" up && ip -n "$ns_b" link set "$veth_b" up
}

wait_for_master() {
  local i
  for ((i = 0; i < 100; i++)); do
    ip netns exec "$ns_a" "${env_a[@]}" python3 -c 'import rosgraph, sys; sys.exit(0 if rosgraph.is_master_online() else 1)' 2>/dev/null && return 0
    sleep 0.1
  done
  return 1
}

reason=$(skip_reason)
if [ -z "$reason" ]; then
  if err=$(ip netns add "$ns_a" 2>&1); then made_ns+=("$ns_a"); else reason="'ip netns add' is not permitted: $err"; fi
fi
if [ -n "$reason" ]; then
  log "SKIPPED: $reason"
  TOP_SIM_NETNS_SKIP="$reason" run_checker env
  status=$?
  [ "$status" -eq 5 ] && exit 0   # pytest: no test ran (the module skipped itself); the XML says skipped
  exit "$status"
fi
rospack find top_sim >/dev/null || { log "top_sim not found by rospack: source the workspace's setup.bash"; exit 1; }
make_hosts || { log "setting up the namespaces failed (see above)"; exit 1; }
log "namespaces $ns_a ($ip_a, $veth_a) and $ns_b ($ip_b, $veth_b); master $master_uri"

# Started as simple commands, so that $! is the process itself (ip netns exec and env exec it).
ip netns exec "$ns_a" "${env_a[@]}" roscore -p 11311 >"$tmp/roscore.log" 2>&1 &
started+=("$!")
if wait_for_master; then log "master up"; else log "no master at $master_uri within 10 s:"; cat "$tmp/roscore.log" >&2; fi
ip netns exec "$ns_a" "${env_a[@]}" roslaunch top_sim distributed.launch groups:=a >"$tmp/group_a.log" 2>&1 &
started+=("$!")
ip netns exec "$ns_b" "${env_b[@]}" bash "$repo/scripts/env_loader.sh" roslaunch top_sim distributed.launch \
  groups:=b alpha_b:="$alpha_b" spin_b:="$spin_b" >"$tmp/group_b.log" 2>&1 &
started+=("$!")

TOP_SIM_NETNS_ADDRESS_A=$ip_a TOP_SIM_NETNS_ADDRESS_B=$ip_b TOP_SIM_NETNS_VETH_A=$veth_a \
  TOP_SIM_NETNS_ALPHA_B=$alpha_b TOP_SIM_NETNS_SPIN_B=$spin_b run_checker ip netns exec "$ns_a" "${env_a[@]}"
status=$?
if [ "$status" -ne 0 ]; then
  for f in roscore group_a group_b; do log "---- last lines of $f's output:"; tail -20 "$tmp/$f.log" >&2; done
fi
exit "$status"
