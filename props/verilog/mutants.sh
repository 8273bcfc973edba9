#!/usr/bin/env bash
# mutants.sh -- show that the checks can fail. Plants each bug in a COPY
# (never in the shipped files) and runs the checks that should catch it:
#
#   Verilog twin (copy made by mutate.sh):
#     prove.sh --mutant NAME                      (the formal proofs)
#     WASP_COSIM_VERILOG_DIR=copy cargo test -p wasp-props --test cosim
#   Rust model (a copy of the workspace in a temporary directory, the same
#   bug planted in rtl/src):
#     cargo test -p wasp-props --test cosim       (Rust vs the good Verilog)
#
# Bugs: wrap_sub (5-bit wrapping free - product), off_by_one (>= instead of
# > against the threshold), drop_finish (the non-blocked counter ignores
# finished warps), hold_launches (the launch rule `hold` launches a lone
# priority warp with the gate closed), meter_wrap (wasp-m's CF meter lets
# its accumulator wrap instead of saturating). Prints which check caught
# which bug; exits non-zero if any bug went uncaught.
#
# usage: props/verilog/mutants.sh [--skip-rust] [--skip-prove] [--skip-cosim]
# Needs yosys, yosys-smtbmc, z3, iverilog, cargo. CARGO_TARGET_DIR for the
# workspace copy defaults to ${TMPDIR:-/tmp}/wasp-mutants-target.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
skip_rust=0 skip_prove=0 skip_cosim=0
for a in "$@"; do
    case $a in
    --skip-rust) skip_rust=1 ;;
    --skip-prove) skip_prove=1 ;;
    --skip-cosim) skip_cosim=1 ;;
    -h|--help) sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown option $a" >&2; exit 2 ;;
    esac
done

work="$(mktemp -d "${TMPDIR:-/tmp}/wasp-mutants.XXXXXX")"
trap 'rm -rf "$work"' EXIT
mutants="$("$here/mutate.sh" list)"
declare -A result
uncaught=0

caught() { # caught KEY STATUS_OF_CHECK(0 = passed)
    if [[ $2 -ne 0 ]]; then result[$1]="CAUGHT"; else result[$1]="missed"; uncaught=1; fi
}

# ---- Verilog mutants ----
for m in $mutants; do
    if [[ $skip_prove == 0 ]]; then
        echo "== prove.sh --mutant $m"
        # prove.sh --mutant exits 0 when some check failed (caught)
        if bash "$here/prove.sh" --mutant "$m" >"$work/prove_$m.log" 2>&1; then
            result[v_prove_$m]="CAUGHT: $(grep -E ' FAIL ' "$work/prove_$m.log" |
                awk '{print $1" "$2}' | paste -sd, -)"
        else
            result[v_prove_$m]="missed"; uncaught=1
        fi
        grep -E "^(P|COVER)" "$work/prove_$m.log" | grep -E "FAIL" | sed 's/^/    /'
    fi
    if [[ $skip_cosim == 0 ]]; then
        echo "== cosim vs Verilog mutant $m"
        "$here/mutate.sh" "$m" "$work/v_$m" 2>/dev/null
        (cd "$root" && WASP_REQUIRE_TOOLS=1 WASP_COSIM_VERILOG_DIR="$work/v_$m" \
            cargo test -q -p wasp-props --test cosim) >"$work/cosim_$m.log" 2>&1
        caught "v_cosim_$m" $?
        grep -m2 "cycles differ" "$work/cosim_$m.log" | sed 's/^/    /'
    fi
done

# ---- Rust mutants: the same bugs in a copy of rtl/src ----
plant_rust() { # plant_rust NAME DIR
    local f
    case $1 in
    wrap_sub)
        f="$2/rtl/src/datapath.rs"
        perl -0pi -e 's/SInt::<REAL_FREE_BITS>::wrapped\(free\.get\(\) as i64 - product\.get\(\) as i64\)/SInt::<REAL_FREE_BITS>::wrapped((free.get().wrapping_sub(product.get()) & 31) as i64)/' "$f" ;;
    off_by_one)
        f="$2/rtl/src/datapath.rs"
        perl -0pi -e 's/real_free\.get\(\) > threshold\.get\(\) as i32/real_free.get() >= threshold.get() as i32/' "$f" ;;
    drop_finish)
        f="$2/rtl/src/nonblocked.rs"
        perl -0pi -e 's/\n\s*- ev\.finished as i32;/;/' "$f" ;;
    hold_launches)
        f="$2/rtl/src/policy/mod.rs"
        perl -0pi -e 's/\} else if v\.priority_waiting && rule == LaunchRule::Launch \{/} else if v.priority_waiting {/' "$f" ;;
    meter_wrap)
        f="$2/rtl/src/cf_meter.rs"
        perl -0pi -e 's/\.saturating_add\(UInt::<ACC_BITS>::masked\(ev\.misses\.get\(\)\)\)/.wrapping_add(UInt::<ACC_BITS>::masked(ev.misses.get()))/' "$f" ;;
    esac
    ! cmp -s "$f" "$root/${f#"$2"/}"
}
if [[ $skip_rust == 0 ]]; then
    export CARGO_TARGET_DIR="${WASP_MUTANTS_TARGET:-${TMPDIR:-/tmp}/wasp-mutants-target}"
    for m in $mutants; do
        echo "== cosim, Rust mutant $m (workspace copy)"
        ws="$work/ws_$m"
        mkdir -p "$ws"
        (cd "$root" && tar --exclude=./target --exclude=./.git -cf - .) | (cd "$ws" && tar -xf -)
        # fresh mtimes: the copies share one target directory, and cargo
        # decides freshness by mtime, so every copy must look newer than the
        # artifacts of the previous one
        find "$ws" -name '*.rs' -exec touch {} +
        if ! plant_rust "$m" "$ws"; then
            echo "mutants.sh: could not plant $m in the Rust copy" >&2
            result[r_cosim_$m]="not planted"; uncaught=1; continue
        fi
        (cd "$ws" && WASP_REQUIRE_TOOLS=1 cargo test -q -p wasp-props --test cosim) >"$work/rust_$m.log" 2>&1
        caught "r_cosim_$m" $?
        grep -m2 "cycles differ" "$work/rust_$m.log" | sed 's/^/    /'
    done
fi

echo
printf '%-12s %-66s %-9s %-9s\n' mutant "formal (prove.sh --mutant): failed checks" "cosim(V)" "cosim(R)"
for m in $mutants; do
    printf '%-12s %-66s %-9s %-9s\n' "$m" "${result[v_prove_$m]:-skipped}" \
        "${result[v_cosim_$m]:-skipped}" "${result[r_cosim_$m]:-skipped}"
done
echo "cosim(V): Verilog mutant vs the Rust model; cosim(R): Rust mutant vs the shipped Verilog"
if [[ $uncaught -ne 0 ]]; then
    echo "SOME MUTANT WAS NOT CAUGHT"
    exit 1
fi
echo "every mutant was caught"
