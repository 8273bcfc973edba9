#!/usr/bin/env bash
# synth.sh -- generic-gate synthesis of wasp_sched.v (the scheduler logic
# only, no testbench) with yosys, for cost estimates:
#   yosys -p "read_verilog wasp_sched.v; chparam ...; synth -top wasp_sched; stat; stat -tech cmos"
# Prints cells, flip-flops and yosys' CMOS transistor estimate per block and
# in total, for the paper's machine by default (the module's defaults:
# WaSP, 16 MSHRs at the L0, queue 64, CF 2.5, threshold 4, Mesh4, 8-bit
# event counts), or with parameter overrides, e.g. CNT_W=2 POLICY=2.
#
# usage: props/verilog/synth.sh [--log DIR] [NAME=VALUE ...]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
logdir=""
if [[ ${1:-} == --log ]]; then logdir=${2:?}; shift 2; fi
command -v yosys >/dev/null || { echo "synth.sh: yosys not installed" >&2; exit 2; }

run() { # run LABEL "chparam args"
    local label=$1 ch=$2 tmp
    tmp="$(mktemp -d)"
    yosys -p "read_verilog $here/wasp_sched.v; ${ch:+chparam $ch wasp_sched;} synth -top wasp_sched; tee -q -o $tmp/stat.txt stat; tee -q -o $tmp/cmos.txt stat -tech cmos" >"$tmp/yosys.log" 2>&1 ||
        { tail -20 "$tmp/yosys.log" >&2; rm -rf "$tmp"; exit 1; }
    if [[ -n $logdir ]]; then mkdir -p "$logdir"; cp "$tmp/yosys.log" "$logdir/yosys.log"; cp "$tmp"/stat.txt "$tmp"/cmos.txt "$logdir/"; fi
    echo "== $label${ch:+ (chparam $ch)}"
    awk '
        function name(s) { sub(/^\$paramod(\$[0-9a-f]+)?\\/, "", s); sub(/\\.*/, "", s); return s }
        FNR == 1 { file++ }
        /^=== / { mod = ($2 == "design") ? "total" : name($2); if (file == 1 && !(mod in seen)) { seen[mod] = 1; order[++n] = mod } }
        file == 1 && /Number of cells:/ { cells[mod] = $4 }
        file == 1 && /\$_(S?DFF|DFFE|SDFFE|SDFFCE|ALDFF|DLATCH)[A-Z0-9_]*_ / { ff[mod] += $2 }
        file == 2 && /Estimated number of transistors:/ { tr[mod] = $5 }
        END {
            printf "   %-22s %7s %5s %12s\n", "block", "cells", "FFs", "transistors"
            for (i = 1; i <= n; i++) { m = order[i]
                printf "   %-22s %7s %5d %12s\n", m, cells[m], ff[m], tr[m] }
        }' "$tmp/stat.txt" "$tmp/cmos.txt"
    rm -rf "$tmp"
}

ch=""
for kv in "$@"; do ch+=" -set ${kv%%=*} ${kv#*=}"; done
run "wasp_sched" "${ch# }"
