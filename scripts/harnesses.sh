#!/usr/bin/env bash
# Every Kani harness of the tree, run as a test under the shim (the
# `kani-shim` feature of wasp-props, crate kani-shim/): each harness body is
# run on every case of its domain when the domain has at most 2^20 cases,
# else on 20,000 seeded random cases (props/README.md). The shim samples;
# Kani proves (`cargo kani -p wasp-props`, where Kani is installed).
#
# Finds every line that is exactly `#[kani::proof]` in the tree's .rs files
# and the function under it, lists the tests the shim build compiled, runs
# those tests, and ends with
#   kani harnesses: N compiled, N ran (E exhaustive, S sampled), N passed; Kani not run
# (E and S counted from the shim's report of this run; the script never runs
# Kani itself, and the last words say so.)
# Fails (exit 1) unless all three are N, the number of attributes found: a
# harness that is not compiled (e.g. a proofs module still under
# `cfg(kani)` alone, or a crate this script does not build), not run, or
# failing fails the script. Run by .ci/run.
#
# usage: scripts/harnesses.sh [--verbose]   (--verbose: print cargo's output)
#   knobs (read by the shim): WASP_KANI_SHIM_LIMIT, WASP_KANI_SHIM_SAMPLES,
#   WASP_KANI_SHIM_SEED
set -euo pipefail
cd "$(dirname "$0")/.."
verbose=0
[[ ${1:-} == --verbose ]] && verbose=1

tmp="$(mktemp -d "${TMPDIR:-/tmp}/wasp-harnesses.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

# 1. The harnesses in the tree: "file:line<TAB>name" per attribute.
grep -rlE --include='*.rs' --exclude-dir=target --exclude-dir=.git \
    '^[[:space:]]*#\[kani::proof\][[:space:]]*$' . | sort |
    xargs -r awk '
        FNR == 1 && want != "" { print want "\t?"; want = "" }
        /^[[:space:]]*#\[kani::proof\][[:space:]]*$/ {
            if (want != "") print want "\t?"
            want = FILENAME ":" FNR; next
        }
        want != "" && match($0, /fn[[:space:]]+[A-Za-z_][A-Za-z0-9_]*/) {
            s = substr($0, RSTART, RLENGTH); sub(/^fn[[:space:]]+/, "", s)
            print want "\t" s; want = ""
        }
        END { if (want != "") print want "\t?" }' >"$tmp/found"
n=$(wc -l <"$tmp/found")
sed -i 's|^\./||' "$tmp/found"
if [[ $n -eq 0 ]]; then
    echo "harnesses.sh: no #[kani::proof] attribute found" >&2
    echo "kani harnesses: 0 compiled, 0 ran, 0 passed; Kani not run"
    exit 1
fi
dups=$(cut -f2 "$tmp/found" | sort | uniq -d)
if [[ -n $dups ]]; then
    echo "harnesses.sh: harness names must be unique (tests are matched by name): $dups" >&2
    exit 1
fi

# 2. What the shim build compiled.
cargo=(cargo test -p wasp-props --features kani-shim --lib --locked)
if ! "${cargo[@]}" -- --list >"$tmp/list" 2>"$tmp/build.log"; then
    cat "$tmp/build.log" >&2
    echo "harnesses.sh: the shim build failed" >&2
    echo "kani harnesses: 0 compiled, 0 ran, 0 passed; Kani not run"
    exit 1
fi
[[ $verbose == 1 ]] && cat "$tmp/build.log" >&2
sed -n 's/: test$//p' "$tmp/list" >"$tmp/tests"
paths=()
compiled=0
while IFS=$'\t' read -r at name; do
    p=$(grep -E "(^|::)${name}\$" "$tmp/tests" || true)
    if [[ $name != "?" && $(grep -c . <<<"$p") -eq 1 && -n $p ]]; then
        paths+=("$p")
        compiled=$((compiled + 1))
        printf '%s\t%s\t%s\n' "$at" "$name" "$p" >>"$tmp/compiled"
    else
        echo "harnesses.sh: $at: harness ${name} is not among the tests the shim build compiled" >&2
    fi
done <"$tmp/found"

# 3. Run them.
status=0
if [[ ${#paths[@]} -gt 0 ]]; then
    set +e
    WASP_KANI_SHIM_REPORT="$tmp/report" "${cargo[@]}" -- --exact "${paths[@]}" \
        >"$tmp/out" 2>&1
    status=$?
    set -e
fi
touch "$tmp/report" "$tmp/compiled"
[[ $verbose == 1 || $status != 0 ]] && cat "$tmp/out"

# 4. The table and the counts.
ran=0
passed=0
exhaustive=0
sampled=0
printf '%-58s %-10s %9s %9s %10s %6s\n' harness mode cases discarded "est. cases" secs
while IFS=$'\t' read -r at name p; do
    res=$(awk -v p="$p" '$1 == "test" && $2 == p && $3 == "..." { print $4; exit }' "$tmp/out")
    case $res in
    ok) ran=$((ran + 1)); passed=$((passed + 1)) ;;
    FAILED) ran=$((ran + 1)) ;;
    *) echo "harnesses.sh: $at: harness $name did not run (${res:-no result})" >&2 ;;
    esac
    line=$(awk -F'\t' -v p="$p" '$1 == p' "$tmp/report" | head -1)
    if [[ -n $line ]]; then
        IFS=$'\t' read -r _ mode cases disc est _seed secs <<<"$line"
    else
        mode="-" cases="-" disc="-" est="-" secs="-"
    fi
    if [[ $res == ok || $res == FAILED ]]; then
        case $mode in
        exhaustive) exhaustive=$((exhaustive + 1)) ;;
        sampled) sampled=$((sampled + 1)) ;;
        esac
    fi
    [[ $res == ok ]] || mode="${res:-not run}"
    printf '%-58s %-10s %9s %9s %10s %6s\n' "$p" "$mode" "$cases" "$disc" "$est" "$secs"
done <"$tmp/compiled"

summary="$compiled compiled, $ran ran ($exhaustive exhaustive, $sampled sampled), $passed passed; Kani not run"
if [[ $compiled -ne $n || $ran -ne $n || $passed -ne $n ]]; then
    echo "harnesses.sh: FAILED: $n #[kani::proof] attributes in the tree" >&2
    echo "kani harnesses: $summary"
    exit 1
fi
echo "kani harnesses: $summary"
