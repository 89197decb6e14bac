# Shared helpers for scripts/*.sh: source it (bash), do not run it.
# Sets TOP_SIM_REPO (repository root) and TOP_SIM_WS (catkin workspace), the environment every script needs,
# and the Debian package list.

TOP_SIM_REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
export TOP_SIM_WS=${TOP_SIM_WS:-$TOP_SIM_REPO/.catkin_ws}
export TOP_SIM_JOBS=${TOP_SIM_JOBS:-2}
# The plain CMake build of the core, tools and Python module (no ROS).
export TOP_SIM_BUILD=${TOP_SIM_BUILD:-$TOP_SIM_REPO/build}
# /usr/bin first: a pyenv python3 earlier on PATH has no ROS modules.
export PATH=/usr/bin:$PATH
export ROS_HOSTNAME=${ROS_HOSTNAME:-localhost}

# Everything the build, the ROS node, LCM, plots and screenshots need (all exist in Debian bookworm).
TOP_SIM_PACKAGES=(
  ros-core-dev catkin libtf2-ros-dev libtf2-eigen-dev libtf2-geometry-msgs-dev librostest-dev python3-rostest
  ros-message-generation libstd-srvs-dev libgeometry-msgs-dev libvisualization-msgs-dev libnav-msgs-dev
  python3-rosbag librosbag-storage-dev rviz libeigen3-dev libboost-dev libyaml-cpp-dev liblcm-dev liblcm-bin
  libglib2.0-dev libgtest-dev google-mock libbenchmark-dev python3-geometry-msgs python3-tf2-msgs
  python3-visualization-msgs python3-tf2-ros libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libdiagnostic-updater-dev python3-matplotlib xvfb cmake g++ make git iproute2
  pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed python3-tqdm
  librviz-dev pluginlib-dev libinteractive-markers-dev libmujoco-dev tf-tools nlohmann-json3-dev libcli11-dev
)

# Every catkin_make call gets the same CMake arguments: catkin_make re-runs cmake whenever they change.
TOP_SIM_CMAKE_ARGS=(-DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3)

top_sim_log() { printf '[top_sim] %s\n' "$*" >&2; }
top_sim_die() { printf '[top_sim] error: %s\n' "$*" >&2; exit 1; }

# Runs a command as root: directly when root, else through sudo.
top_sim_as_root() {
  if [ "$(id -u)" -eq 0 ]; then
    "$@"
  elif command -v sudo >/dev/null 2>&1; then
    sudo "$@"
  else
    top_sim_die "installing packages needs root; run as root or install sudo (command: $*)"
  fi
}

# Prints the packages of TOP_SIM_PACKAGES that are not fully installed, one per line.
top_sim_missing_packages() {
  local p
  for p in "${TOP_SIM_PACKAGES[@]}"; do
    dpkg-query -W -f='${db:Status-Abbrev}\n' "$p" 2>/dev/null | grep -q '^ii' || echo "$p"
  done
}

# catkin_make in the workspace with the project's CMake arguments; extra arguments (targets, -jN) follow.
top_sim_catkin_make() {
  (cd "$TOP_SIM_WS" && catkin_make "${TOP_SIM_CMAKE_ARGS[@]}" "$@")
}

# The core's tests under AddressSanitizer + UndefinedBehaviorSanitizer: a plain build in $TOP_SIM_BUILD-sanitize,
# -O1 -g1: line tables, so a report names file and line, at less than half the compile time of -O2 -g (fit.cpp:
# 44 s against 110 s).
top_sim_sanitized_build() {
  top_sim_log "AddressSanitizer + UBSan build of the core's tests in $TOP_SIM_BUILD-sanitize (-j$TOP_SIM_JOBS)"
  cmake -S "$TOP_SIM_REPO" -B "$TOP_SIM_BUILD-sanitize" -DTOP_SIM_ROS=OFF -DTOP_SIM_PYTHON=OFF \
    -DTOP_SIM_SANITIZE=address,undefined -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" >/dev/null &&
    cmake --build "$TOP_SIM_BUILD-sanitize" -j"$TOP_SIM_JOBS" --target top_sim_core_tests top_sim_run top_sim_sweep top_sim_stability
}
