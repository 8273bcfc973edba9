#!/usr/bin/env bash
# The issue order (`core.issue`) on every shipped scene: the baseline and
# the configuration's WaSP under loose round-robin and greedy-then-oldest,
# on the paper's machine (shared-tile). The table of docs/machine.md,
# "Issue order".
#
#   scripts/issue-orders.sh [OUT_DIR]     (default OUT_DIR: target/issue-orders)
#
# Builds the release binary, renders every shipped scene's trace once into
# the cache scripts/machines.sh uses (target/machines/traces; game data is
# fetched into the scene cache if missing), runs `wasp compare --policies
# baseline,wasp:0:3 --set core.issue=ORDER` per scene and order (JSON in
# OUT_DIR/json) and writes the table to OUT_DIR/issue-orders.md with
# scripts/issue-orders-report.py. Every run uses configs/paper.toml.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$repo/target/issue-orders}
traces=$repo/target/machines/traces
mkdir -p "$traces" "$out/json"
cd "$repo"
cargo build --release --locked -q
W=$repo/target/release/wasp
scenes=$("$W" scenes list | awk 'NR > 1 && $1 != "scene" && NF >= 6 {print $1}')
"$W" scenes fetch supertuxkart openarena teeworlds frozen-bubble >&2
version=$(sed -n 's/^pub const FORMAT_VERSION: u32 = \([0-9][0-9]*\);$/\1/p' trace/src/limits.rs)
[ -n "$version" ] || { echo "issue-orders.sh: no FORMAT_VERSION in trace/src/limits.rs" >&2; exit 1; }
policy=$(sed -n 's/^policy = "\([^"]*\)".*/\1/p' configs/paper.toml)
for s in $scenes; do
  t=$traces/$s.trace
  if [ -s "$t" ] && [ "$(head -n 1 "$t")" != "wasp-trace $version" ]; then
    rm -f "$t" "$out/json/$s".*.json
  fi
  if [ ! -s "$t" ]; then
    echo "== render $s" >&2
    "$W" render "$s" --trace-out "$t.tmp" -q && mv "$t.tmp" "$t"
  fi
  for order in lrr gto; do
    j=$out/json/$s.$order.json
    if [ ! -s "$j" ]; then
      echo "== compare $s ($order)" >&2
      "$W" compare --trace "$t" --policies "baseline,$policy" --set "core.issue=$order" \
        -q --json "$j.tmp" > /dev/null
      mv "$j.tmp" "$j"
    fi
  done
done
python3 "$repo/scripts/issue-orders-report.py" "$out/json" > "$out/issue-orders.md"
echo "wrote $out/issue-orders.md" >&2
