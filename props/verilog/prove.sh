#!/usr/bin/env bash
# prove.sh -- solver-backed proofs of the Verilog twin (wasp_sched.v) with
# yosys + yosys-smtbmc + z3: for each property group, a bounded model check
# from reset (BMC, with --presat: the assumptions are satisfiable at every
# step) and a k-induction proof (yosys-smtbmc -i), plus a cover run showing
# that the interesting cases are reachable. Every configuration (policy,
# capacity, CF, threshold, N, queue capacity, launch rule) is covered at once: the
# wrapper drives them with $anyconst. The rows M and MCOVER prove wasp-m's
# CF meter alone (wasp_cf_meter_formal.sv). Prints a summary table; exits
# non-zero if any check fails. See README.md for the properties.
#
# usage: props/verilog/prove.sh [options]
#   --mutant NAME     prove a copy of wasp_sched.v with a planted bug
#                     (mutate.sh: wrap_sub, off_by_one, drop_finish,
#                     hold_launches, meter_wrap); the
#                     table says which checks caught it, and the exit
#                     status is then 0 if some check failed (the bug was
#                     caught) and 1 if every check passed (it was missed)
#   --src DIR         prove DIR/wasp_sched.v instead of the shipped file
#   --bmc-depth N     BMC steps (default 20)
#   --ind-depth K     induction steps (default 2)
#   --cover-depth N   cover steps (default 12; the meter's MCOVER: 48, to fill
#                     its accumulator and a window)
#   --only LIST       comma-separated rows (P34,P5,PM,P1,P2,P6,P7,P9,P8,COVER,
#                     M,MCOVER)
#   --jobs N          parallel solver runs (default: number of CPUs)
#   --keep            keep the work directory (models, logs, traces)
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
src_dir="$here"
mutant=""
bmc_depth=20
ind_depth=2
cover_depth=12
only=""
jobs="$(nproc 2>/dev/null || echo 2)"
keep=0

die() { echo "prove.sh: $*" >&2; exit 2; }
while [[ $# -gt 0 ]]; do
    case $1 in
    --mutant) mutant=${2:?}; shift 2 ;;
    --src) src_dir="$(cd "${2:?}" && pwd)"; shift 2 ;;
    --bmc-depth) bmc_depth=${2:?}; shift 2 ;;
    --ind-depth) ind_depth=${2:?}; shift 2 ;;
    --cover-depth) cover_depth=${2:?}; shift 2 ;;
    --only) only=${2:?}; shift 2 ;;
    --jobs) jobs=${2:?}; shift 2 ;;
    --keep) keep=1; shift ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown option $1 (see --help)" ;;
    esac
done

for tool in yosys yosys-smtbmc z3; do
    command -v "$tool" >/dev/null 2>&1 ||
        die "$tool not installed (Debian/Ubuntu: apt-get install yosys z3)"
done

work="$(mktemp -d "${TMPDIR:-/tmp}/wasp-prove.XXXXXX")"
cleanup() { if [[ $keep == 1 ]]; then echo "work directory kept: $work"; else rm -rf "$work"; fi; }
trap cleanup EXIT
if [[ -n $mutant ]]; then
    "$here/mutate.sh" "$mutant" "$work/src"
    src_dir="$work/src"
fi
design="$src_dir/wasp_sched.v"
[[ -f $design ]] || die "no $design"
meter_cover_depth=48

# row | defines | modes | top (the wrapper, $here/TOP.sv; default the
# scheduler's). ASSUME_P34 / ASSUME_P5 / ASSUME_PM assume the invariants
# that rows P34 / P5 / PM prove (sound: P34 and P5 assume nothing but legal
# inputs, PM only P34, so the invariants hold in every reachable state and
# no row assumes what it is used to prove; see the wrapper).
rows=(
    "P34|ASSERT_P34|bmc ind"
    "P5|ASSERT_P5|bmc ind"
    "PM|ASSERT_PM ASSUME_P34|bmc ind"
    "P1|ASSERT_P1 ASSUME_P34 ASSUME_PM|bmc ind"
    "P2|ASSERT_P2|bmc ind"
    "P6|ASSERT_P6 ASSUME_P34|bmc ind"
    "P7|ASSERT_P7 ASSUME_P34 ASSUME_P5 ASSUME_PM|bmc ind"
    "P9|ASSERT_P9 ASSUME_P34 ASSUME_P5 ASSUME_PM|bmc ind"
    "P8|FAULT_MODE ASSERT_P8|bmc ind"
    "COVER|COVER|cover"
    "M|ASSERT_M|bmc ind|wasp_cf_meter_formal"
    "MCOVER|COVER|cover|wasp_cf_meter_formal"
)
declare -A what=(
    [P34]="P3 free == cap - outstanding <= cap; P4 nb == model <= 127"
    [P5]="occupancies == model, sum <= cap, refuse iff full, Mesh4"
    [PM]="wasp-m meter == its spec: launches <= 15, acc <= 127 saturating, CF <= 31  (assumes P34)"
    [P1]="priority launch only if 4*free - q*nb > 4*T (launch rule: or no regular warp)  (assumes P34, PM)"
    [P2]="x CF shift-add, subtract, compare == exact, every value"
    [P6]="no fault under legal inputs  (assumes P34)"
    [P7]="select/launch == reference policy, all 5, both launch rules  (assumes P34, P5, PM)"
    [P9]="hold: no priority launch, gate closed; launch: never idle with a warp waiting  (assumes P34, P5, PM)"
    [P8]="fault iff exact next out of range; hold (meter too) / load; reset"
    [COVER]="boundary launch, hold-back, full queue, free=0, hold idle, launch with gate closed, wasp-m ... reachable"
    [M]="CF meter alone, every state: next == spec, CF loaded <= 31, acc saturates, never wraps"
    [MCOVER]="CF meter: a window loads a new CF, the accumulator saturates, CF 31 loaded"
)

selected() { [[ -z $only ]] || [[ ",$only," == *",$1,"* ]]; }

# Build the SMT-LIB model of one row. The model is bit-blasted and
# AIG-optimized by yosys (techmap; abc -g AND) before write_smt2: z3 proves
# the same checks on it in seconds rather than minutes (on word-level
# arithmetic z3's incremental solver is slow for this design).
build() {
    local name=$1 defs=$2 top=$3 d="$work/$1"
    mkdir -p "$d"
    local flags="-DWASP_CFG_PORTS"
    for x in $defs; do flags+=" -D$x"; done
    cat >"$d/model.ys" <<EOF
read_verilog -formal $flags $design
read_verilog -formal $flags $here/$top.sv
prep -top $top
flatten
async2sync
techmap
opt -fast
abc -g AND
opt_clean
dffunmap
stat
write_smt2 -wires $d/model.smt2
EOF
    yosys -q -l "$d/yosys.log" "$d/model.ys" >/dev/null 2>&1
}

# seconds between two `date +%s%N` stamps, one decimal
secs() { local ms=$((($2 - $1) / 1000000)); printf '%d.%d' $((ms / 1000)) $((ms % 1000 / 100)); }

# run one check; writes "$d/$mode.result": result seconds
check() {
    local name=$1 mode=$2 d="$work/$1" args rc t0 t1
    case $mode in
    bmc) args=(--presat -t "$bmc_depth" --dump-vcd "$d/bmc_cex.vcd") ;;
    ind) args=(-i -t "$ind_depth" --dump-vcd "$d/ind_cex.vcd") ;;
    cover) args=(-c -t "$(depth_of "$name" cover)" --dump-vcd "$d/cover_%.vcd") ;;
    esac
    t0=$(date +%s%N)
    set +e
    yosys-smtbmc -s z3 "${args[@]}" "$d/model.smt2" >"$d/$mode.log" 2>&1
    rc=$?
    set -e
    t1=$(date +%s%N)
    local res
    if [[ $rc -eq 0 ]] && grep -q "Status: PASSED" "$d/$mode.log"; then
        res=PASS
    elif grep -q "Status: FAILED" "$d/$mode.log"; then
        res=FAIL
    else
        res=ERROR
    fi
    printf '%s %s\n' "$res" "$(secs "$t0" "$t1")" >"$d/$mode.result"
}

# the depth of a row's check
depth_of() {
    case $2 in
    bmc) echo "$bmc_depth" ;;
    ind) echo "$ind_depth" ;;
    cover) if [[ $1 == MCOVER ]]; then echo "$meter_cover_depth"; else echo "$cover_depth"; fi ;;
    esac
}

echo "== wasp_sched formal: $design${mutant:+ (mutant $mutant)}"
echo "   yosys $(yosys -V | awk '{print $2}'), z3 $(z3 --version | awk '{print $3}'), BMC depth $bmc_depth, induction depth $ind_depth, cover depth $cover_depth, $jobs jobs"

t_start=$(date +%s%N)
tasks=()
for row in "${rows[@]}"; do
    IFS='|' read -r name defs modes top <<<"$row"
    selected "$name" || continue
    if ! build "$name" "$defs" "${top:-wasp_sched_formal}"; then
        echo "prove.sh: yosys failed for $name:" >&2
        tail -20 "$work/$name/yosys.log" >&2
        exit 1
    fi
    for m in $modes; do tasks+=("$name $m"); done
done
[[ ${#tasks[@]} -gt 0 ]] || die "no rows selected by --only $only"

running=0
for t in "${tasks[@]}"; do
    # shellcheck disable=SC2086
    check $t &
    running=$((running + 1))
    if [[ $running -ge $jobs ]]; then
        wait -n || true
        running=$((running - 1))
    fi
done
wait
t_total=$(secs "$t_start" "$(date +%s%N)")

# what failed in a run, for the table: the labels of the failed
# assertions, unreached covers, or unsatisfiable assumptions
where_failed() {
    local log=$1 labels
    labels=$(grep -oE "Assert failed in [^:]+: [^ ]+" "$log" | awk '{print $NF}' | sort -u | paste -sd, -)
    if [[ -n $labels ]]; then
        local step
        step=$(grep -oE "(Checking assertions|Trying induction) in step [0-9]+" "$log" | tail -1 | awk '{print $NF}')
        echo "failed: $labels (step ${step:-?})"
    elif grep -q "Unreached cover" "$log"; then
        echo "unreached: $(grep -oE "Unreached cover statement at [^ ]+" "$log" | awk '{print $NF}' | sed 's/\.$//' | paste -sd, -)"
    elif grep -qi "assumptions are unsatisfiable\|PREUNSAT" "$log"; then
        echo "assumptions unsatisfiable"
    fi
}

fail=0
printf '\n%-16s %-6s %6s %-6s %8s  %s\n' property mode depth result time note
printf '%-16s %-6s %6s %-6s %8s  %s\n' "----------------" ------ ------ ------ -------- ----
for row in "${rows[@]}"; do
    IFS='|' read -r name defs modes _top <<<"$row"
    selected "$name" || continue
    for m in $modes; do
        read -r res took <"$work/$name/$m.result"
        depth=$(depth_of "$name" "$m")
        note="${what[$name]}"
        if [[ $res != PASS ]]; then
            fail=1
            note="$(where_failed "$work/$name/$m.log")"
            [[ -n $note ]] || note="see $m.log"
            keep=1
        fi
        printf '%-16s %-6s %6s %-6s %7ss  %s\n' "$name" "$m" "$depth" "$res" "$took" "$note"
    done
done
printf '\ntotal wall clock %ss\n' "$t_total"
if [[ -n $mutant ]]; then
    if [[ $fail -ne 0 ]]; then
        echo "mutant $mutant: CAUGHT (logs and counterexample traces in $work)"
        exit 0
    fi
    echo "mutant $mutant: MISSED -- every check passed on the planted bug"
    exit 1
fi
if [[ $fail -ne 0 ]]; then
    echo "FAILED: logs and counterexample traces (*.vcd) in $work"
    exit 1
fi
echo "all proofs passed"
