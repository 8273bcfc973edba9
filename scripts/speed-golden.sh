#!/usr/bin/env bash
# Golden-output matrix for performance work: every optimization must leave
# the simulator's results byte-identical.
#
#   scripts/speed-golden.sh record WASP_BINARY DIR   # reference outputs
#   scripts/speed-golden.sh check  WASP_BINARY DIR   # regenerate and cmp
#
# DIR holds the inputs (generated once by `record`), ref/ and new/.
# Nothing generated here is meant to be committed.
set -euo pipefail
mode=$1; W=$(realpath "$2"); D=$3
repo=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$D/in" "$D/ref" "$D/new"
out=$D/new; [ "$mode" = record ] && out=$D/ref

if [ "$mode" = record ]; then
  cp "$repo/configs/paper.toml" "$D/in/paper.toml"
  cp "$repo/configs/paper-width2.toml" "$D/in/width2.toml"
  sed -e 's/^max_warps = 64 /max_warps = 128/' -e 's/^input_queue = 64 /input_queue = 128/' \
    "$repo/configs/paper.toml" > "$D/in/w128.toml"
  sed -e 's/^max_warps = 64 /max_warps = 32 /' -e 's/^input_queue = 64 /input_queue = 32 /' \
    "$repo/configs/paper.toml" > "$D/in/w32.toml"
  for c in paper width2; do
    sed -e 's/^tile_size = 64 /tile_size = 8  /' "$D/in/$c.toml" > "$D/in/$c-t8.toml"
    grep -q '^tile_size = 8 ' "$D/in/$c-t8.toml"
  done
  # ALU and texture latencies beyond the core's 64-cycle wake-up wheel.
  sed -e 's/^alu_latency = 4 /alu_latency = 70/' -e 's/^texture_latency = 4 /texture_latency = 80/' \
    "$repo/configs/paper.toml" > "$D/in/slow.toml"
  grep -q '^alu_latency = 70' "$D/in/slow.toml"
  grep -q '^texture_latency = 80' "$D/in/slow.toml"
  grep -q '^max_warps = 128' "$D/in/w128.toml"
  grep -q '^max_warps = 32 ' "$D/in/w32.toml"
  cp "$repo/tests/traces/tiny.trace" "$D/in/tiny.trace"
  cp "$repo/tests/traces/synthetic-small.trace" "$D/in/small.trace"
  "$W" synth --out "$D/in/many.trace" --frame 3200x1600 --seed 7 > /dev/null
  "$W" render procedural-plane --trace-out "$D/in/plane.trace" -q 2> /dev/null
  "$W" render procedural-sprites --trace-out "$D/in/sprites.trace" -q 2> /dev/null
fi

jobs=()
traces=(default tiny small many plane sprites)
for cfg in paper width2; do
  for tr in "${traces[@]}"; do
    for pol in baseline fullpriority freemshr:10 wasp:4:mesh4 wasp:4:random; do
      case $pol in
        wasp:4:mesh4) p="--policy wasp:4 --subset mesh4" ;;
        wasp:4:random) p="--policy wasp:4 --subset random" ;;
        *) p="--policy $pol" ;;
      esac
      [ "$tr" = many ] && [ "$cfg" = width2 ] && continue
      t=""; [ "$tr" != default ] && t="--trace $D/in/$tr.trace"
      c=$cfg; [ "$tr" = tiny ] && c=$cfg-t8
      jobs+=("$cfg-$tr-${pol//:/_}.json|--config $D/in/$c.toml $t $p")
    done
    t=""; [ "$tr" != default ] && t="--trace $D/in/$tr.trace"
    c=$cfg; [ "$tr" = tiny ] && c=$cfg-t8
    jobs+=("$cfg-$tr-ideal.json|--config $D/in/$c.toml $t --ideal-memory")
  done
done
for cfg in w128 w32; do
  for tr in default plane; do
    t=""; [ "$tr" != default ] && t="--trace $D/in/$tr.trace"
    for pol in baseline wasp:4; do
      jobs+=("$cfg-$tr-${pol//:/_}.json|--config $D/in/$cfg.toml $t --policy $pol")
    done
  done
done

# Every priority subset, under WaSP and Fullpriority.
for sub in mesh2 mesh8 mesh16 hlines vlines top16 random:99; do
  for pol in wasp:4 fullpriority; do
    jobs+=("paper-plane-${pol//:/_}-${sub//:/_}.json|--config $D/in/paper.toml --trace $D/in/plane.trace --policy $pol --subset $sub")
  done
done
for pol in baseline wasp:4; do
  jobs+=("slow-small-${pol//:/_}.json|--config $D/in/slow.toml --trace $D/in/small.trace --policy $pol")
done
jobs+=("width2-sprites-wasp_2_1.5-mesh8.json|--config $D/in/width2.toml --trace $D/in/sprites.trace --policy wasp:2:1.5 --subset mesh8")
# The other dispatch mode and the fixed DRAM model.
for tr in default plane sprites; do
  t=""; [ "$tr" != default ] && t="--trace $D/in/$tr.trace"
  for pol in baseline wasp:4; do
    jobs+=("paper-$tr-${pol//:/_}-per-core-tile.json|--config $D/in/paper.toml $t --policy $pol --dispatch per-core-tile")
    jobs+=("paper-$tr-${pol//:/_}-fixed-dram.json|--config $D/in/paper.toml $t --policy $pol --set dram.model=fixed")
  done
done

printf '%s\n' "${jobs[@]}" | xargs -P 2 -I{} bash -c '
  name=${1%%|*}; args=${1#*|}
  "$2" run -q $args --json "$3/$name" > /dev/null' _ {} "$W" "$out"

# A short VCD window and its GTKWave save file.
"$W" run -q --config "$D/in/paper.toml" --trace "$D/in/small.trace" \
  --vcd "$out/window.vcd" --vcd-from 0 --vcd-to 2000 --json "$out/window.json" > /dev/null
"$W" run -q --config "$D/in/width2-t8.toml" --trace "$D/in/tiny.trace" --policy freemshr:10 \
  --vcd "$out/tiny.vcd" --json "$out/tiny-vcd.json" > /dev/null
"$W" run -q --config "$D/in/paper.toml" --trace "$D/in/plane.trace" --dispatch per-core-tile \
  --vcd "$out/per-core.vcd" --vcd-from 500 --vcd-to 1500 --json "$out/per-core-vcd.json" > /dev/null
sed -i "s#$out#OUT#g" "$out"/*.gtkw 2>/dev/null || true

n=$(ls "$out" | wc -l)
if [ "$mode" = record ]; then
  echo "recorded $n files in $out"
  exit 0
fi
bad=0
for f in "$D"/ref/*; do
  b=$(basename "$f")
  if ! cmp -s "$f" "$out/$b"; then echo "DIFFERS: $b"; bad=1; fi
done
[ "$(ls "$D/ref" | wc -l)" = "$n" ] || { echo "file count differs"; bad=1; }
[ $bad = 0 ] && echo "golden: all $n files byte-identical"
exit $bad
