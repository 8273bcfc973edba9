#!/usr/bin/env bash
# The binary works outside its source tree: build wasp from a copy of the
# tracked sources, delete the copy, and use the binary from another folder
# with an empty home (no scene cache): the worked example, the scene list,
# a procedural render and run, a scene from --scenes-dir, and `wasp cost`
# (the embedded Verilog twin, when yosys is installed). Run by .ci/run.
#
#   scripts/moved-binary.sh        (build cache: target/moved)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/src" "$work/bin" "$work/elsewhere" "$work/home" "$work/defs"
(cd "$repo" && git ls-files -z | xargs -0 cp --parents -t "$work/src")
(cd "$work/src" && CARGO_TARGET_DIR="$repo/target/moved" cargo build --locked -q --bin wasp)
cp "$repo/target/moved/debug/wasp" "$work/bin/wasp"
rm -rf "$work/src"
cd "$work/elsewhere"
export HOME="$work/home"
unset WASP_SCENES WASP_SCENES_DIR XDG_CACHE_HOME
W="$work/bin/wasp"
fail() { echo "moved-binary: $*" >&2; exit 1; }

"$W" -q > example.txt
grep -q "cycles" example.txt || fail "the worked example printed no cycles"
"$W" scenes list > shipped.txt
n=$(awk 'NR > 1 && $1 != "scene" && NF >= 6' shipped.txt | wc -l)
[ "$n" -ge 16 ] || fail "scenes list shows $n scenes, expected the 16 shipped"
"$W" render procedural-plane --size 256x128 --trace-out plane.trace -q 2> /dev/null
"$W" run --trace plane.trace -q --json plane.json > /dev/null
grep -q '"cycles"' plane.json || fail "run wrote no statistics"
sed -e 's/^name = .*/name = "moved-plane"/' -e 's/^width = .*/width = 128/' \
    -e 's/^height = .*/height = 64/' > "$work/defs/moved-plane.toml" <<'TOML'
name = "x"
game = "procedural"
map = "plane"
camera = "ground"
width = 1
height = 1
TOML
"$W" scenes list --scenes-dir "$work/defs" > list.txt
grep -q "^moved-plane " list.txt || fail "--scenes-dir did not add its scene"
WASP_SCENES_DIR="$work/defs" "$W" render moved-plane --trace-out moved.trace -q 2> /dev/null
if command -v yosys > /dev/null; then
  "$W" cost > cost.txt
  grep -qi "yosys" cost.txt || fail "wasp cost did not synthesize the embedded twin"
  grep -q "not found" cost.txt && fail "wasp cost looked for the twin on disk"
fi
echo "moved-binary: the binary works outside its source tree" >&2
