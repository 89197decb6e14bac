#!/usr/bin/env bash
# Regenerates every figure and table of docs/results.md from the project's own tools:
# builds top_sim_run and top_sim_sweep (plain CMake, Release, -j2), runs the scenes and sweeps, thins the
# CSV files into docs/data/, draws docs/img/fig*.png with Debian's python3-matplotlib, and rewrites the
# phi* tables of docs/results.md; docs/img/stability_*.png, tippe_stability_sweep.png of docs/analysis.md
# (top_sim_stability); and docs/img/tippe_top_tilt.png of docs/physics.md section 11.
#
#   bash scripts/make_figures.sh
#
# Environment: TOP_SIM_BIN_DIR = directory already holding top_sim_run and top_sim_sweep (skips the build);
# TOP_SIM_FIG_BUILD = build directory (default ${TMPDIR:-/tmp}/top_sim_figures_build);
# TOP_SIM_JOBS = make -j (default 2); TOP_SIM_SWEEP_THREADS = sweep threads (default: all cores).
set -euo pipefail
export PATH=/usr/bin:$PATH   # Debian's python3 with matplotlib, not a pyenv one
REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
DATA=$REPO/docs/data
IMG=$REPO/docs/img
PLOTS=$REPO/scripts/plots
RAW=$(mktemp -d "${TMPDIR:-/tmp}/top_sim_figures.XXXXXX")
trap 'rm -rf "$RAW"' EXIT
log() { printf '[make_figures] %s\n' "$*" >&2; }

if [ -n "${TOP_SIM_BIN_DIR:-}" ]; then
  BIN=$TOP_SIM_BIN_DIR
else
  BUILD=${TOP_SIM_FIG_BUILD:-${TMPDIR:-/tmp}/top_sim_figures_build}
  log "building top_sim_run and top_sim_sweep in $BUILD"
  cmake -S "$REPO" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DTOP_SIM_ROS=OFF -DTOP_SIM_TESTS=OFF \
    -DTOP_SIM_PYTHON=OFF >"$RAW/cmake.log" 2>&1 \
    || { cat "$RAW/cmake.log" >&2; exit 1; }
  make -C "$BUILD" -j"${TOP_SIM_JOBS:-2}" top_sim_run top_sim_sweep top_sim_stability >"$RAW/make.log" 2>&1 \
    || { tail -50 "$RAW/make.log" >&2; exit 1; }
  BIN=$BUILD/bin
fi
RUN=$BIN/top_sim_run
SWEEP=$BIN/top_sim_sweep
[ -x "$RUN" ] && [ -x "$SWEEP" ] || { echo "make_figures.sh: no top_sim_run/top_sim_sweep in $BIN" >&2; exit 1; }
export TOP_SIM_CONFIG_DIR=$REPO/config
mkdir -p "$DATA" "$IMG"
THREADS=()
[ -n "${TOP_SIM_SWEEP_THREADS:-}" ] && THREADS=(--threads "$TOP_SIM_SWEEP_THREADS")

# ---- Fig. 4: tan(phi*/2) against tan(alpha), two planes, three tops -------------------------------------
# Tilted start (at rest, the paper's experiment) over the whole range; launched start (sleeping state with
# 0.01 rad extra tilt) near the critical inclination, where a top started at rest can run away.
for pair in aluminium:pmma steel:pmma steel:steel wood:steel; do
  top=${pair%%:*} plane=${pair##*:}
  log "fig4: sweep $top on $plane (tilted start)"
  "$SWEEP" --top "$top" --plane "$plane" --alpha 0.01:0.30:30 "${THREADS[@]}" --out "$DATA/fig4_${top}_${plane}.csv"
done
for pair in aluminium:pmma steel:steel; do
  top=${pair%%:*} plane=${pair##*:}
  log "fig4: sweep $top on $plane (launched start)"
  "$SWEEP" --top "$top" --plane "$plane" --alpha 0.14:0.30:17 --start launched "${THREADS[@]}" \
    --out "$DATA/fig4_${top}_${plane}_launched.csv"
done

# ---- Fig. 5: linearized law, k = 1 ----------------------------------------------------------------------
log "fig5: config/scenes/fig5_linearized.yaml"
"$RUN" "$REPO/config/scenes/fig5_linearized.yaml" --duration 60 --rate 400 --csv "$RAW/fig5.csv" 2>/dev/null
python3 "$PLOTS/reduce_csv.py" "$RAW/fig5.csv" "$DATA/fig5_linearized_60s.csv" --dense-until 4 --every 8 --digits 7 \
  --columns t,com_x,com_y,com_z,vcm_x,vcm_y,vcm_z,f_x,f_y,f_z,s,phi
"$RUN" "$REPO/config/scenes/fig5_linearized.yaml" --rate 2 --csv "$RAW/fig5_long.csv" 2>/dev/null
python3 "$PLOTS/reduce_csv.py" "$RAW/fig5_long.csv" "$DATA/fig5_linearized_600s.csv" --columns t,contact_x,contact_y,phi,s,spin,regime

# ---- Fig. 2: three spins --------------------------------------------------------------------------------
for spin in 100 200 400; do
  log "fig2: config/scenes/fig2_spin$spin.yaml"
  # Equal scaled-time sampling: 20 samples per (spin / 200) seconds.
  "$RUN" "$REPO/config/scenes/fig2_spin$spin.yaml" --rate $((4000 / spin)) --csv "$RAW/fig2_$spin.csv"
  python3 "$PLOTS/reduce_csv.py" "$RAW/fig2_$spin.csv" "$DATA/fig2_spin$spin.csv" --dense-until 0 --every 2 \
    --columns t,contact_x,contact_y,phi,spin,regime
done

# ---- Fig. 3: the gyroscope-loaded top -------------------------------------------------------------------
log "fig3: config/scenes/gyro_reversal.yaml"
"$RUN" "$REPO/config/scenes/gyro_reversal.yaml" --rate 50 --csv "$RAW/fig3.csv"
python3 "$PLOTS/reduce_csv.py" "$RAW/fig3.csv" "$DATA/fig3_gyro_reversal.csv" \
  --columns t,contact_x,contact_y,u_x,u_y,spin,rotor_spin,phi,regime

# ---- physics.md section 11: the tippe top's tilt (Cohen's sphere and its prolate variant) -----------------
for scene in tippe_top tippe_top_tumbling; do
  log "tippe top: config/scenes/$scene.yaml"
  "$RUN" "$REPO/config/scenes/$scene.yaml" --duration 20 --rate 100 --csv "$RAW/$scene.csv"
  python3 "$PLOTS/reduce_csv.py" "$RAW/$scene.csv" "$DATA/$scene.csv" --digits 7 --columns t,f_z,omega_z,spin,s,regime
done

# ---- figures and tables ---------------------------------------------------------------------------------
log "plots"
python3 "$PLOTS/fig4_tan_half_phi.py" "$DATA" "$IMG/fig4_tan_half_phi.png"
python3 "$PLOTS/fig5_linearized.py" "$DATA" "$IMG/fig5_linearized.png"
python3 "$PLOTS/fig2_spins.py" "$DATA" "$IMG/fig2_spins.png"
python3 "$PLOTS/fig3_gyro.py" "$DATA" "$IMG/fig3_gyro_reversal.png"
python3 "$PLOTS/tippe_top_tilt.py" "$DATA" "$IMG/tippe_top_tilt.png"
python3 "$PLOTS/phi_table.py" "$DATA" "$REPO/docs/results.md"

# ---- docs/analysis.md: linear stability of the sleeping state -------------------------------------------
if [ -x "$BIN/top_sim_stability" ]; then
  log "stability: sweeps over alpha (default scene) and shell spin (gyro_reversal)"
  (cd "$REPO" && TOP_SIM_PLOTS_DIR=$PLOTS "$BIN/top_sim_stability" config/scenes/default.yaml \
     --sweep-alpha 0.005:0.244:48 --plot "$IMG/stability_alpha.png" >/dev/null)
  (cd "$REPO" && TOP_SIM_PLOTS_DIR=$PLOTS "$BIN/top_sim_stability" config/scenes/gyro_reversal.yaml \
     --sweep-spin -2:2:81 --plot "$IMG/stability_gyro.png" >/dev/null)
  log "stability: the tippe top's spinning upright and inverted states against the spin"
  (cd "$REPO" && TOP_SIM_PLOTS_DIR=$PLOTS "$BIN/top_sim_stability" config/scenes/tippe_top.yaml \
     --sweep-spin 0:100:201 --plot "$IMG/tippe_stability_sweep.png" >/dev/null)
fi
log "done: $IMG/fig*.png, $DATA/*.csv, tables in docs/results.md"
