#!/usr/bin/env bash
# Host instructions per simulated core-cycle of `Gpu::step` on the bench
# workload (the 8x4-tile synthetic frame of `wasp bench`, paper machine),
# counted by callgrind: deterministic, unaffected by machine load, so it can
# compare two builds where wall-clock timing on a shared machine cannot.
#
#   scripts/icount.sh [WASP_BINARY]     (default: target/release/wasp)
#
# Prints the count, then the inclusive cost per core-cycle of the functions
# callgrind sees (inlined code is charged to its caller). Needs valgrind.
# With ICOUNT_SIM=1 it also runs callgrind's branch predictor and cache
# models and prints mispredicted branches and L1 data misses per core-cycle
# (a simple model of the host, but deterministic: wall-clock timing on a
# shared machine cannot see a 3% change). Extra arguments of `wasp run` go in
# ICOUNT_ARGS, e.g. ICOUNT_ARGS="--dispatch per-core-tile". ICOUNT_TRACE=FILE
# counts a run of that trace instead of the bench workload (a real scene's,
# from `wasp render SCENE --trace-out FILE`; a trace of several frames, from
# `wasp trace-cat`, counts every frame's cycles).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
bin=$(realpath "${1:-$repo/target/release/wasp}")
command -v valgrind > /dev/null || { echo "icount: valgrind is not installed" >&2; exit 1; }
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
if [ -n "${ICOUNT_TRACE:-}" ]; then
  [ -r "$ICOUNT_TRACE" ] || { echo "icount: cannot read ICOUNT_TRACE=$ICOUNT_TRACE" >&2; exit 1; }
  ln -s "$(realpath "$ICOUNT_TRACE")" "$out/bench.trace"
else
  "$bin" synth --frame 512x256 --seed 1 --out "$out/bench.trace" > /dev/null
fi
sim=()
[ "${ICOUNT_SIM:-0}" = 1 ] && sim=(--branch-sim=yes --cache-sim=yes)
valgrind --tool=callgrind "${sim[@]}" --callgrind-out-file="$out/cg" \
  --toggle-collect='wasp_sim::gpu::Gpu*::step' \
  "$bin" run -q --trace "$out/bench.trace" ${ICOUNT_ARGS:-} --json "$out/run.json" > /dev/null 2> "$out/log"
python3 - "$out" <<'PY'
import json, re, signal, subprocess, sys
signal.signal(signal.SIGPIPE, signal.SIG_DFL)
out = sys.argv[1]
run = json.load(open(f"{out}/run.json"))
# Core-cycles; a trace of several frames runs every frame's cycles.
cycles = sum(f["cycles"] for f in run["frames"]) if "frames" in run else run["cycles"]
cc = cycles * len(run["occupancy"]["per_core_mean"])
lines = open(f"{out}/cg").read().splitlines()
names = next(l.split()[1:] for l in lines if l.startswith("events:"))
values = next(l.split()[1:] for l in lines if l.startswith(("summary:", "totals:")))
ev = dict(zip(names, map(int, values)))
total = ev["Ir"]
print(f"instr/core-cycle: {total / cc:.1f}  ({total} instructions, {cc} core-cycles)")
if "Bcm" in ev:
    print(f"mispredicted branches/core-cycle: {(ev['Bcm'] + ev['Bim']) / cc:.2f}  "
          f"L1 data misses/core-cycle: {(ev['D1mr'] + ev['D1mw']) / cc:.2f}")
ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", f"{out}/cg"],
                     capture_output=True, text=True).stdout
# A function appears once per source file of code inlined into it; its
# inclusive cost is the largest of those rows.
best = {}
for line in ann.splitlines():
    m = re.match(r"\s*([\d,]+) \(\s*[\d.]+%\)\s+(\S+):(wasp_\S+)", line)
    if m:
        n = int(m.group(1).replace(",", ""))
        best[m.group(3)] = max(best.get(m.group(3), 0), n)
for f, n in sorted(best.items(), key=lambda x: -x[1]):
    if n / cc >= 5:
        print(f"{n / cc:8.1f}  {f}")
PY
