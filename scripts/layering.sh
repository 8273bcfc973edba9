#!/usr/bin/env bash
# The crates' layering holds (README, "A tour"): SplitMix64
# (wasp-splitmix) alone under everything; rtl, waves and trace at
# the bottom; the cycle model (wasp-sim) on them with no image or archive
# crate; the front end (wasp-frontend) on trace and rtl, never the model;
# the properties (wasp-props) on the model, never the front end; the Kani
# shim (wasp-kani-shim) on no crate of the workspace but wasp-splitmix;
# and no import cycle between the modules of a crate (scripts/import-cycles.py). Run by
# .ci/run; fails naming the crate and the dependency (or the cycle and the
# lines that make it) that breaks it.
set -euo pipefail
cd "$(dirname "$0")/.."
deps() { cargo tree --locked -p "$1" -e normal --prefix none | awk '{print $1}' | sort -u; }
fail=0
forbid() {
  local crate=$1; shift
  local have
  have=$(deps "$crate")
  for d in "$@"; do
    if grep -qx "$d" <<< "$have"; then
      echo "layering: $crate depends on $d" >&2
      fail=1
    fi
  done
}
forbid wasp-splitmix wasp-rtl wasp-trace wasp-gltrace wasp-waves wasp-sim wasp-frontend wasp-props wasp-kani-shim
forbid wasp-trace wasp-rtl wasp-waves wasp-sim wasp-frontend wasp-props
forbid wasp-gltrace wasp-trace wasp-rtl wasp-waves wasp-sim wasp-frontend wasp-props
forbid wasp-waves wasp-rtl wasp-trace wasp-sim wasp-frontend wasp-props
forbid wasp-rtl wasp-trace wasp-sim wasp-frontend wasp-props
forbid wasp-sim wasp-frontend wasp-props image zip flate2 roxmltree
forbid wasp-frontend wasp-sim wasp-props
forbid wasp-props wasp-frontend image zip flate2 roxmltree
# The Kani shim stands alone but for SplitMix64 (wasp-props uses it under its feature kani-shim).
forbid wasp-kani-shim wasp-rtl wasp-trace wasp-waves wasp-sim wasp-frontend wasp-props
# Inside every crate, no import cycle between modules (siblings at any
# depth), and the check itself finds the cycles it plants in a test crate.
python3 scripts/import-cycles.py --self-test || fail=1
python3 scripts/import-cycles.py || fail=1
[ "$fail" = 0 ] || exit 1
echo "layering: splitmix < rtl, waves, trace, gltrace < sim, frontend < wasp; props on sim and rtl; kani shim alone" >&2
