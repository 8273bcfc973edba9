#!/usr/bin/env bash
# The paper's TBR machine beside the per-core-tile machine on every shipped
# scene: the tables of docs/results.md.
#
#   scripts/machines.sh [OUT_DIR]        (default OUT_DIR: target/machines)
#   WASP_CONFIG=FILE scripts/machines.sh DIR   (another machine file for every run)
#
# Builds the release binary, renders every shipped scene's trace once
# (cached in target/machines/traces; game data is fetched into the scene cache if
# missing), runs `wasp compare --with-ideal` (its default list: baseline,
# fullpriority, freemshr:10, the configuration's WaSP and wasp-m at its
# threshold; then the baseline with ideal memory) under each dispatch mode
# with configs/paper.toml (JSON in OUT_DIR/json), and writes the tables to
# OUT_DIR/machines.md with scripts/machines-report.py. Nothing is tuned per
# scene: every run uses the same configuration file.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$repo/target/machines}
mkdir -p "$repo/target/machines/traces" "$out/json"
cd "$repo"
cargo build --release --locked -q
W=$repo/target/release/wasp
# The study's scenes (docs/reproduce.md) and their traces
# (scripts/study-traces.sh).
. "$repo/scripts/study-traces.sh"
scenes=$(study_scenes "$W")
"$W" scenes fetch supertuxkart openarena teeworlds frozen-bubble >&2
start=$(date +%s)
# A trace rendered again (a new trace format or a new build of wasp) has
# its runs redone.
# shellcheck disable=SC2086
for s in $(study_traces "$W" "$repo" $scenes); do
  rm -f "$out/json/$s".*.json
done
for s in $scenes; do
  t=$repo/target/machines/traces/$s.trace
  for d in shared-tile per-core-tile; do
    j=$out/json/$s.$d.json
    if [ ! -s "$j" ]; then
      echo "== compare $s ($d)" >&2
      "$W" compare --trace "$t" --dispatch "$d" --with-ideal -q --json "$j.tmp" \
        ${WASP_CONFIG:+--config "$WASP_CONFIG"} > /dev/null
      mv "$j.tmp" "$j"
    fi
  done
done
python3 "$repo/scripts/machines-report.py" "$out/json" > "$out/machines.md"
echo "wrote $out/machines.md ($(( $(date +%s) - start )) s after the fetch)" >&2
