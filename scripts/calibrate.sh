#!/usr/bin/env bash
# One suite-wide sweep that sets the MSHR counts and WaSP's CF and
# threshold of the shipped configuration (docs/calibration.md says why and
# how). Every point runs on every scene; nothing is chosen per scene.
#
#   scripts/calibrate.sh [OUT]       default OUT: target/calibrate
#
# Stages (each point = every scene of `wasp scenes list`):
#   A. MSHRs, scanline baseline only, so the machine does not depend on
#      the policy it is later used to judge: L2 over L2_SET with L0 and L1
#      at their largest, then L1 over L1_SET with L0 at its largest, then L0
#      over L0_SET (at most 31: the 5-bit free-MSHR register). Each stage
#      keeps the smallest count whose suite geomean cycles are within
#      KNEE (1%) of the best count of the stage.
#   B. CF: the suite mean of the scenes' measured CF (unique blocks per
#      warp, the paper's definition), in the datapath's quarter steps.
#   C. Threshold: WaSP at that CF for every threshold in 0..L0 MSHRs-1 (step
#      THRESHOLD_STEP), the best suite geomean speedup over the baseline.
#
# Traces come from scripts/machines.sh's cache (target/machines/traces),
# rendered there if missing. WASP_CONFIG names the starting configuration
# (default: the embedded configs/paper.toml); SCENES limits the scenes
# (space separated) for a quick look, which is then not a calibration;
# JOBS caps the simulations run at once (default: the machine's cores);
# STOP_AFTER=A stops after the MSHR stage.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$repo/target/calibrate}
mkdir -p "$out/json" "$repo/target/machines/traces"
cd "$repo"
cargo build --release -q
W=$repo/target/release/wasp
cfg_args=()
[ -n "${WASP_CONFIG:-}" ] && cfg_args=(--config "$WASP_CONFIG")

L2_SET=${L2_SET:-"32 64 128 256"}
L1_SET=${L1_SET:-"8 16 32 64"}
L0_SET=${L0_SET:-"4 8 12 16 20 24 31"}
THRESHOLD_STEP=${THRESHOLD_STEP:-2}
KNEE=${KNEE:-0.01}
export KNEE

# The suite is the study's (docs/reproduce.md); its traces are cached by
# scripts/study-traces.sh.
. "$repo/scripts/study-traces.sh"
scenes=${SCENES:-$(study_scenes "$W")}
# shellcheck disable=SC2086
study_traces "$W" "$repo" $scenes > /dev/null

# run NAME POLICIES SET...: every scene, one JSON per scene, cached.
run() {
  local name=$1 policies=$2
  shift 2
  local sets=()
  for kv in "$@"; do sets+=(--set "$kv"); done
  for s in $scenes; do
    local j=$out/json/$name.$s.json
    [ -s "$j" ] && continue
    "$W" compare "${cfg_args[@]}" ${JOBS:+--jobs "$JOBS"} --trace "$repo/target/machines/traces/$s.trace" \
      --policies "$policies" "${sets[@]}" -q --json "$j.tmp" >/dev/null
    mv "$j.tmp" "$j"
  done
}
pick() { python3 "$repo/scripts/calibrate-report.py" pick "$out" "$@"; }

start=$(date +%s)
echo "== A. L2 MSHRs: $L2_SET" >&2
for n in $L2_SET; do run "l2-$n" baseline l0.mshrs=31 l1.mshrs=64 "l2.mshrs=$n"; done
l2=$(pick l2 $L2_SET)
echo "   L2 MSHRs = $l2" >&2
echo "== A. L1 MSHRs: $L1_SET" >&2
for n in $L1_SET; do run "l1-$n.l2-$l2" baseline l0.mshrs=31 "l1.mshrs=$n" "l2.mshrs=$l2"; done
l1=$(pick "l1" $L1_SET -- ".l2-$l2")
echo "   L1 MSHRs = $l1" >&2
echo "== A. L0 MSHRs: $L0_SET" >&2
for n in $L0_SET; do run "l0-$n.l1-$l1.l2-$l2" baseline scheduler.policy=baseline "l0.mshrs=$n" "l1.mshrs=$l1" "l2.mshrs=$l2"; done
l0=$(pick "l0" $L0_SET -- ".l1-$l1.l2-$l2")
echo "   L0 MSHRs = $l0" >&2
mshrs=("l0.mshrs=$l0" "l1.mshrs=$l1" "l2.mshrs=$l2")
base="l0-$l0.l1-$l1.l2-$l2"
if [ "${STOP_AFTER:-}" = A ]; then
  echo "== stopped after stage A: $base" >&2
  exit 0
fi

echo "== B. CF" >&2
cf=$(python3 "$repo/scripts/calibrate-report.py" cf "$out" "$base")
echo "   CF = $cf" >&2

echo "== C. threshold at CF $cf (and at the paper's 2.5)" >&2
policies=baseline
for ((t = 0; t < l0; t += THRESHOLD_STEP)); do
  policies+=",wasp:$t:$cf"
  [ "$cf" != "2.5" ] && policies+=",wasp:$t:2.5"
done
run "wasp.$base" "$policies" scheduler.policy=baseline "${mshrs[@]}"

python3 "$repo/scripts/calibrate-report.py" report "$out" "$base" "$cf" \
  "$l0" "$l1" "$l2" "$L0_SET" "$L1_SET" "$L2_SET" "$scenes"
echo "== done in $(($(date +%s) - start)) s: $out/calibration.md, $out/calibration.json" >&2
