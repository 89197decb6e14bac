#!/usr/bin/env bash
# top_sim_lcm_echo prints top_sim_run --lcm's stream: two messages, each with every field of lcm/top_state_t.lcm,
# regime_name and paused among them. Usage: lcm_echo_test.sh TOP_SIM_RUN TOP_SIM_LCM_ECHO SOURCE_DIR
set -euo pipefail
run=$1 echo_tool=$2 src=$3
url='udpm://239.255.76.67:7669?ttl=0'
out=$(mktemp)
trap 'rm -f "$out"; kill "$runner" 2>/dev/null || true' EXIT
"$echo_tool" --url "$url" --channel ECHO_TEST -n 2 --timeout 20 >"$out" &
echo_pid=$!
sleep 0.5
"$run" "$src/config/scenes/default.yaml" --duration 3 --rate 20 --lcm "$url" --lcm-channel ECHO_TEST --quiet \
  >/dev/null &
runner=$!
wait "$echo_pid" || { echo "top_sim_lcm_echo failed: $(cat "$out")"; exit 1; }
[ "$(grep -c '^---$' "$out")" = 2 ] || { echo "expected 2 messages:"; cat "$out"; exit 1; }
fields=$(sed -n 's/^ *\(int64_t\|double\|boolean\|int8_t\|string\) *\([a-z_]*\).*/\2/p' "$src/lcm/top_state_t.lcm")
[ -n "$fields" ] || { echo "no fields read from top_state_t.lcm"; exit 1; }
for f in $fields; do
  grep -q "^$f: " "$out" || { echo "field $f not printed:"; cat "$out"; exit 1; }
done
grep -q '^regime_name: "' "$out" && grep -q '^paused: False' "$out" && grep -q '^requested_real_time_factor: 1$' "$out" \
  || { echo "regime_name / paused / requested_real_time_factor wrong:"; cat "$out"; exit 1; }
echo "top_sim_lcm_echo: 2 messages, $(echo $fields | wc -w) fields each"
