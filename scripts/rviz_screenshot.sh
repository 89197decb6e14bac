#!/usr/bin/env bash
# Renders docs/img/rviz.png: the node and rviz under Xvfb (Mesa software GL), a few seconds of the scene, one
# screenshot of the rviz window, then a clean shutdown. No display or roscore needed.
#   scripts/rviz_screenshot.sh [OUT.png]
# Environment: TOP_SIM_SCENE (a scene file, default config/scenes/default.yaml, or a shipped scene's name, e.g.
# top_life, passed to the launch as it is), TOP_SIM_SHOT_RTF (real-time factor, default 2; `scene` passes none, so the
# node uses the scene's view.real_time_factor),
# TOP_SIM_SHOT_WAIT (wall seconds of streaming before the shot, default 8), TOP_SIM_SHOT_SIZE (default 1280x800),
# TOP_SIM_SHOT_LAUNCH (launch file of the package, default top_sim.launch; TOP_SIM_SCENE is passed only to that
# one), TOP_SIM_SHOT_TOPIC (a TopState topic that shows streaming has started, default /top_sim/top_state),
# TOP_SIM_SHOT_ARGS (more launch arguments, e.g. "color_by:=mode") and TOP_SIM_SHOT_SETUP (bash commands run once
# streaming has started, e.g. rosservice calls that spawn tops).
# Three tops:
#   TOP_SIM_SHOT_SETUP='rosservice call /top_sim/spawn b "$(printf "initial: {spin: -200.0, position: [0.08, 0.0]}")"' \
#     TOP_SIM_SHOT_RTF=1 scripts/rviz_screenshot.sh docs/img/rviz_three_tops.png
# The geometric-phase figure:
#   TOP_SIM_SHOT_LAUNCH=geometric_phase.launch TOP_SIM_SHOT_TOPIC=/spin400/top_sim/top_state TOP_SIM_SHOT_RTF=1 \
#     TOP_SIM_SHOT_WAIT=18 scripts/rviz_screenshot.sh docs/img/geometric_phase.png
# Needs the Debian packages xvfb, x11-utils (xwininfo) and python3-pil.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

OUT=$(realpath -m "${1:-$TOP_SIM_REPO/docs/img/rviz.png}")
SCENE=${TOP_SIM_SCENE:-$TOP_SIM_REPO/config/scenes/default.yaml}
# A name (no '/', no .yaml) is a shipped scene the launch finds; a path is made absolute for the node.
case "$SCENE" in */*|*.yaml) SCENE=$(realpath -m "$SCENE") ;; esac
RTF=${TOP_SIM_SHOT_RTF:-2}
RTF_ARG="real_time_factor:=$RTF"
if [ "$RTF" = scene ]; then RTF_ARG=""; fi
WAIT=${TOP_SIM_SHOT_WAIT:-8}
SIZE=${TOP_SIM_SHOT_SIZE:-1280x800}
LAUNCH=${TOP_SIM_SHOT_LAUNCH:-top_sim.launch}
TOPIC=${TOP_SIM_SHOT_TOPIC:-/top_sim/top_state}
LAUNCH_ARGS=""
if [ "$LAUNCH" = top_sim.launch ]; then LAUNCH_ARGS="scene:=$SCENE"; fi
LAUNCH_ARGS="$LAUNCH_ARGS ${TOP_SIM_SHOT_ARGS:-}"
SETUP=${TOP_SIM_SHOT_SETUP:-}

for tool in xvfb-run xwininfo; do
  command -v "$tool" >/dev/null 2>&1 || top_sim_die "$tool not found (Debian packages: xvfb, x11-utils)"
done
/usr/bin/python3 -c 'from PIL import ImageGrab' 2>/dev/null || top_sim_die "python3 PIL not found (Debian package: python3-pil)"
case "$SCENE" in
  /*) [ -f "$SCENE" ] || top_sim_die "scene file $SCENE does not exist" ;;
  *) [ -f "$TOP_SIM_REPO/config/scenes/$SCENE.yaml" ] || top_sim_die "no shipped scene $SCENE (config/scenes/$SCENE.yaml)" ;;
esac

# Use the workspace's devel space unless top_sim is already on the ROS package path.
if ! rospack find top_sim >/dev/null 2>&1; then
  [ -f "$TOP_SIM_WS/devel/setup.bash" ] || top_sim_die "no $TOP_SIM_WS/devel/setup.bash: build first (scripts/build.sh)"
  set +u; source "$TOP_SIM_WS/devel/setup.bash"; set -u
fi

# A private master on a free port, so a running roscore or another session is left alone.
PORT=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://localhost:$PORT
LOG=$(mktemp -d /tmp/top_sim_shot.XXXXXX)
top_sim_log "rviz screenshot: $LAUNCH $LAUNCH_ARGS, real_time_factor $RTF, ${WAIT} s; logs in $LOG"

export OUT LAUNCH LAUNCH_ARGS TOPIC RTF_ARG WAIT PORT LOG TOP_SIM_REPO SETUP
# Software GL: Xvfb has no GPU; rviz's OGRE renders through Mesa llvmpipe.
export LIBGL_ALWAYS_SOFTWARE=1
xvfb-run -a -s "-screen 0 ${SIZE}x24" bash -c '
  set -m   # job control: the background roslaunch receives SIGINT like from a terminal
  roslaunch -p "$PORT" top_sim "$LAUNCH" $LAUNCH_ARGS rviz:=true $RTF_ARG \
    >"$LOG/roslaunch.log" 2>&1 &
  launch=$!
  status=0
  # Streaming has started once one TopState arrives (rostopic fails at once while the master is not up yet).
  streaming=false
  for _ in $(seq 30); do
    if timeout 10 rostopic echo -n 1 "$TOPIC/sim_time" >"$LOG/first_state.txt" 2>&1; then
      streaming=true; break
    fi
    kill -0 "$launch" 2>/dev/null || break
    sleep 1
  done
  if $streaming && [ -n "$SETUP" ]; then
    bash -c "$SETUP" >"$LOG/setup.log" 2>&1 || { echo "TOP_SIM_SHOT_SETUP failed (see $LOG/setup.log)" >&2; status=1; }
  fi
  if $streaming && [ $status = 0 ]; then
    sleep "$WAIT"
    /usr/bin/python3 "$TOP_SIM_REPO/scripts/grab_window.py" --title RViz --out "$OUT" --timeout 30 || status=$?
    rostopic echo -n 1 "$TOPIC/sim_time" >"$LOG/last_state.txt" 2>&1 || true
    rostopic echo -n 1 "$TOPIC/regime" >"$LOG/last_regime.txt" 2>&1 || true
  else
    echo "no TopState on $TOPIC within 60 s (see $LOG/roslaunch.log)" >&2
    status=1
  fi
  kill -INT "$launch" 2>/dev/null || true
  for _ in $(seq 50); do kill -0 "$launch" 2>/dev/null || break; sleep 0.2; done
  kill -TERM "$launch" 2>/dev/null || true
  wait "$launch" 2>/dev/null || true
  exit $status
'
top_sim_log "simulated time at the shot: $(head -1 "$LOG/last_state.txt" 2>/dev/null || echo unknown) s, regime $(head -1 "$LOG/last_regime.txt" 2>/dev/null || echo unknown)"
top_sim_log "wrote $OUT"
