#!/usr/bin/env bash
# mutate.sh NAME OUTDIR -- write a copy of wasp_sched.v with one planted bug
# to OUTDIR/wasp_sched.v (the shipped file is never changed). Used by
# prove.sh --mutant, and with WASP_COSIM_VERILOG_DIR=OUTDIR by the
# co-simulation. NAME:
#   wrap_sub     real_free = free - product in 5 bits (wraps), zero-extended
#   off_by_one   priority_over_regular = real_free >= threshold
#   drop_finish  the non-blocked counter ignores prio_finished
#   hold_launches the launch rule `hold` launches a lone priority warp with
#                the gate closed (as `launch` does)
#   meter_wrap   wasp-m's CF meter: the accumulator wraps at 128 instead of
#                saturating at 127
#   list         print the names
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
names="wrap_sub off_by_one drop_finish hold_launches meter_wrap"

if [[ $# -ge 1 && $1 == list ]]; then
    echo "$names"
    exit 0
fi
if [[ $# -ne 2 ]]; then
    echo "usage: $0 {$(echo "$names" | tr ' ' '|')|list} OUTDIR" >&2
    exit 2
fi
name=$1
out=$2
src="$here/wasp_sched.v"
mkdir -p "$out"
dst="$out/wasp_sched.v"
[[ "$(cd "$out" && pwd)" != "$here" ]] || { echo "mutate.sh: OUTDIR must not be $here" >&2; exit 2; }

case $name in
wrap_sub)
    sed -e 's|^    assign real_free = {6'"'"'d0, free_mshrs} - {1'"'"'b0, product};$|    assign real_free = {6'"'"'d0, free_mshrs - product[4:0]}; // MUTANT wrap_sub|' \
        "$src" >"$dst" ;;
off_by_one)
    sed -e 's|^    assign priority_over_regular = \$signed(real_free) > \$signed({6'"'"'d0, cfg_threshold});$|    assign priority_over_regular = $signed(real_free) >= $signed({6'"'"'d0, cfg_threshold}); // MUTANT off_by_one|' \
        "$src" >"$dst" ;;
drop_finish)
    sed -e 's|^        - \$signed({{(EW-CNT_W){1'"'"'b0}}, finished});$|        ; // MUTANT drop_finish: prio_finished ignored|' \
        "$src" >"$dst" ;;
hold_launches)
    sed -e 's|^                    (prio_waiting \&\& cfg_launch_rule) ? 2'"'"'d2 :$|                    prio_waiting ? 2'"'"'d2 : // MUTANT hold_launches|' \
        "$src" >"$dst" ;;
meter_wrap)
    sed -e 's|^    wire \[6:0\] acc_sat    = sum\[7\] ? 7'"'"'d127 : sum\[6:0\];$|    wire [6:0] acc_sat    = sum[6:0]; // MUTANT meter_wrap|' \
        "$src" >"$dst" ;;
*)
    echo "mutate.sh: unknown mutant '$name' (one of: $names)" >&2
    exit 2 ;;
esac

if cmp -s "$src" "$dst" || [[ $(diff "$src" "$dst" | grep -c '^>') -ne 1 ]]; then
    echo "mutate.sh: the $name edit did not apply to exactly one line of $src" >&2
    exit 1
fi
echo "mutant $name -> $dst:" >&2
diff "$src" "$dst" | sed 's/^/    /' >&2 || true
