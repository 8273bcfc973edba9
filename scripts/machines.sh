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
# The study's scenes (docs/reproduce.md): a loader scene with an engine twin
# (NAME-engine) counts through its twin.
scenes=$("$W" scenes list | awk 'NR > 1 && $1 != "scene" && NF >= 6 {print $1}' \
  | awk '{ s[NR] = $1; have[$1] = 1 } END { for (i = 1; i <= NR; i++) if (!((s[i] "-engine") in have)) print s[i] }')
"$W" scenes fetch supertuxkart openarena teeworlds frozen-bubble >&2
# The trace format the front end writes (FORMAT_VERSION in trace/src/limits.rs).
version=$(sed -n 's/^pub const FORMAT_VERSION: u32 = \([0-9][0-9]*\);$/\1/p' trace/src/limits.rs)
[ -n "$version" ] || { echo "machines.sh: no FORMAT_VERSION in trace/src/limits.rs" >&2; exit 1; }
start=$(date +%s)
for s in $scenes; do
  t=$repo/target/machines/traces/$s.trace
  # A trace cached in an older format (before wasp-trace 3: no Early-Z-
  # rejected quads; before wasp-trace 4: no trilinear marks) is rendered
  # again, and the runs on it redone.
  if [ -s "$t" ] && [ "$(head -n 1 "$t")" != "wasp-trace $version" ]; then
    rm -f "$t" "$out/json/$s".*.json
  fi
  if [ ! -s "$t" ]; then
    echo "== render $s" >&2
    "$W" render "$s" --trace-out "$t.tmp" -q && mv "$t.tmp" "$t"
  fi
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
