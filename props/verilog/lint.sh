#!/usr/bin/env bash
# lint.sh -- verilator --lint-only -Wall on the Verilog twin (wasp_sched.v)
# in each of its forms: every POLICY 0..4 (the CF meter exists only under
# 4, wasp-m) with the default parameters; the narrowest widths (a one-slot
# queue, Mesh16, 1-bit event counts) under wasp-m; the formal build
# (WASP_CFG_PORTS); and the meter alone. Any warning fails (exit 1): the
# file is clean, each waiver a `verilator lint_off` comment in it that says
# why. Run by .ci/run.
#
# usage: props/verilog/lint.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
command -v verilator >/dev/null 2>&1 ||
    { echo "lint.sh: verilator not installed (Debian/Ubuntu: apt-get install verilator)" >&2; exit 2; }
echo "== $(verilator --version)"
forms=(
    "wasp_sched -GPOLICY=0"
    "wasp_sched -GPOLICY=1"
    "wasp_sched -GPOLICY=2"
    "wasp_sched -GPOLICY=3"
    "wasp_sched -GPOLICY=4"
    "wasp_sched -GPOLICY=4 -GQUEUE_CAP=1 -GMESH_BITS=4 -GCNT_W=1"
    "wasp_sched -DWASP_CFG_PORTS"
    "wasp_cf_meter"
)
fail=0
for form in "${forms[@]}"; do
    read -r top args <<<"$form"
    # shellcheck disable=SC2086
    if out=$(verilator --lint-only -Wall --top-module "$top" $args "$here/wasp_sched.v" 2>&1) &&
        [[ -z $out ]]; then
        echo "clean: $top $args"
    else
        echo "NOT CLEAN: $top $args"
        echo "$out"
        fail=1
    fi
done
exit $fail
