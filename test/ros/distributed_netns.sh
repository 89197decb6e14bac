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
master=() launches=()   # process ids of what this script started in the namespaces
made_ns=()

t0=${EPOCHREALTIME//[!0-9]/}   # microseconds (whatever the locale's decimal separator)
# Microseconds since the script started.
elapsed_us() { echo $((${EPOCHREALTIME//[!0-9]/} - t0)); }

log() {
  local ds=$(($(elapsed_us) / 100000))
  printf '[distributed_netns %d.%d s] %s\n' $((ds / 10)) $((ds % 10)) "$*" >&2
}

# Process ids left in our namespaces.
leftovers() {
  local ns
  for ns in "${made_ns[@]}"; do ip netns pids "$ns" 2>/dev/null; done
}

# False once pid has exited (a zombie not yet reaped counts as exited).
running() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 1
  stat=${stat##*) }
  [ "${stat%% *}" != Z ]
}

any_running() {
  local pid
  for pid in "$@"; do running "$pid" && return 0; done
  return 1
}

# Sends signal $1 to the pids that follow and waits up to $2 tenths of a second for them to exit.
stop() {
  local sig=$1 tenths=$2 pid i
  shift 2
  for pid in "$@"; do kill "-$sig" "$pid" 2>/dev/null; done
  for ((i = 0; i < tenths; i++)); do
    any_running "$@" || return 0
    sleep 0.1
  done
}

# The roslaunches first (SIGINT: they stop their nodes and unregister), then the master (SIGTERM: it ignores
# SIGINT for seconds); whatever is left in our namespaces (the nodes run in their own sessions) is killed, then the
# namespaces (and the veth pair with them) are deleted.
cleanup() {
  local pid ns
  trap '' TERM INT   # a signal now (a caller's timeout) would cut the cleanup short; it is bounded by itself
  stop INT 50 "${launches[@]}"
  stop TERM 20 "${master[@]}"
  for pid in $(leftovers); do
    log "killing $pid, still running after SIGINT or SIGTERM: $(tr '\0' ' ' 2>/dev/null <"/proc/$pid/cmdline" | cut -c1-100)"
    kill -KILL "$pid" 2>/dev/null
  done
  for ns in "${made_ns[@]}"; do ip netns del "$ns" 2>/dev/null || log "could not delete network namespace $ns"; done
  rm -rf "$tmp"
  log "stopped and removed"
}
# Ignoring further signals at once: timeout(1) signals the script and then its whole process group.
trap cleanup EXIT
trap 'trap "" TERM INT; exit 143' TERM
trap 'trap "" TERM INT; exit 130' INT

# The environment of each host: B's ROS_IP is left to scripts/env_loader.sh.
env_a=(env -u ROS_HOSTNAME ROS_IP="$ip_a" ROS_MASTER_URI="$master_uri")
env_b=(env -u ROS_HOSTNAME -u ROS_IP ROS_MASTER_URI="$master_uri")

run_checker() {
  # -c /dev/null: no pytest configuration of the source tree applies; no cache directory is written.
  "$@" timeout -k 3 30 python3 -m pytest -c /dev/null --rootdir="$here" -p no:cacheprovider -W ignore::DeprecationWarning \
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

# True once the master listens in A and has a /run_id, false after 12 s. The probe is bash (Python costs seconds on
# a busy machine); /run_id is what roscore would set: without it the two roslaunches each set their own and one fails.
wait_for_master() {
  local deadline=$(($(elapsed_us) + 12000000))
  while [ "$(elapsed_us)" -lt "$deadline" ]; do
    if ip netns exec "$ns_a" bash -c "exec 3<>/dev/tcp/$ip_a/11311" 2>/dev/null; then
      ip netns exec "$ns_a" "${env_a[@]}" python3 -c \
        "import rosgraph, uuid; rosgraph.Master('/distributed_netns').setParam('/run_id', str(uuid.uuid1()))"
      return
    fi
    sleep 0.2
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
# The master alone, as roscore starts it (without rosout, which takes seconds to start on a busy machine).
ip netns exec "$ns_a" "${env_a[@]}" rosmaster --core -p 11311 >"$tmp/master.log" 2>&1 &
master+=("$!")
if wait_for_master; then log "master up"; else log "no master at $master_uri within 12 s:"; cat "$tmp/master.log" >&2; fi
ip netns exec "$ns_a" "${env_a[@]}" roslaunch top_sim distributed.launch groups:=a >"$tmp/group_a.log" 2>&1 &
launches+=("$!")
ip netns exec "$ns_b" "${env_b[@]}" bash "$repo/scripts/env_loader.sh" roslaunch top_sim distributed.launch \
  groups:=b alpha_b:="$alpha_b" spin_b:="$spin_b" >"$tmp/group_b.log" 2>&1 &
launches+=("$!")

TOP_SIM_NETNS_ADDRESS_A=$ip_a TOP_SIM_NETNS_ADDRESS_B=$ip_b TOP_SIM_NETNS_VETH_A=$veth_a \
  TOP_SIM_NETNS_ALPHA_B=$alpha_b TOP_SIM_NETNS_SPIN_B=$spin_b run_checker ip netns exec "$ns_a" "${env_a[@]}" &
wait "$!"   # in the background: a TERM (the caller's timeout) is handled at once, not after the checker
status=$?
if [ "$status" -ne 0 ]; then
  for f in master group_a group_b; do log "---- last lines of $f's output:"; tail -20 "$tmp/$f.log" >&2; done
fi
exit "$status"
