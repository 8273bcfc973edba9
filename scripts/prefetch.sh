#!/usr/bin/env bash
# The prefetchers beside WaSP on every shipped scene: the table of
# docs/machine.md, "Prefetchers".
#
#   scripts/prefetch.sh [OUT_DIR] [WASP_BINARY]   (default OUT_DIR: target/prefetch)
#
# Renders every shipped scene's trace once (cached in
# target/machines/traces, as scripts/machines.sh does; game data is fetched
# into the scene cache when a trace has to be rendered) and runs each on configs/paper.toml as
# the baseline, WaSP (wasp:0:3), the baseline and WaSP with each
# prefetcher, and the baseline with ideal memory (JSON in OUT_DIR/json),
# then writes the table to OUT_DIR/prefetch.md with
# scripts/prefetch-report.py. Every run uses the shipped configuration and
# the prefetchers' shipped defaults: nothing is tuned per scene.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$repo/target/prefetch}
W=${2:-}
if [ -z "$W" ]; then
  (cd "$repo" && cargo build --release --locked -q)
  W=$repo/target/release/wasp
fi
traces=$repo/target/machines/traces
mkdir -p "$traces" "$out/json"
scenes=$("$W" scenes list | awk 'NR > 1 && $1 != "scene" && NF >= 6 {print $1}')
fetched=0
for s in $scenes; do
  t=$traces/$s.trace
  if [ ! -s "$t" ]; then
    if [ $fetched = 0 ]; then
      "$W" scenes fetch supertuxkart openarena teeworlds frozen-bubble >&2
      fetched=1
    fi
    echo "== render $s" >&2
    "$W" render "$s" --trace-out "$t.tmp" -q && mv "$t.tmp" "$t"
  fi
done
# name|arguments of `wasp run`
runs=(
  "baseline|--policy baseline"
  "wasp|--policy wasp:0:3"
  "raster|--policy baseline --set prefetch.kind=raster"
  "wasp-raster|--policy wasp:0:3 --set prefetch.kind=raster"
  "oracle|--policy baseline --set prefetch.kind=oracle-tile"
  "wasp-oracle|--policy wasp:0:3 --set prefetch.kind=oracle-tile"
  "ideal|--policy baseline --ideal-memory"
)
jobs=()
for s in $scenes; do
  for r in "${runs[@]}"; do
    j=$out/json/$s.${r%%|*}.json
    [ -s "$j" ] || jobs+=("$j|$traces/$s.trace|${r#*|}")
  done
done
echo "${#jobs[@]} runs to do" >&2
printf '%s\n' "${jobs[@]}" | xargs -r -P 2 -I{} bash -c '
  IFS="|" read -r j t args <<< "$1"
  "$2" run -q --config "$3/configs/paper.toml" --trace "$t" $args --json "$j.tmp" > /dev/null
  mv "$j.tmp" "$j"' _ {} "$W" "$repo"
python3 "$repo/scripts/prefetch-report.py" "$out/json" > "$out/prefetch.md"
echo "wrote $out/prefetch.md" >&2
