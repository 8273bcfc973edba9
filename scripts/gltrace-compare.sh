#!/usr/bin/env bash
# Compares wasp-gltrace's reading of an apitrace capture with
# `apitrace dump --verbose`: the number and name of every call, in order. Prints the
# call counts of both and the first difference, if any; exits 1 on a
# difference.
#   scripts/gltrace-compare.sh CAPTURE
set -euo pipefail
cd "$(dirname "$0")/.."
capture="$1"
command -v apitrace >/dev/null || { echo "apitrace is missing: apt-get install apitrace" >&2; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cargo build -q --release -p wasp-gltrace --example gltrace-calls
target/release/examples/gltrace-calls "$capture" > "$tmp/ours"
# `apitrace dump` lines that start a call: "NUMBER NAME(...". --verbose: by
# default dump hides the calls apitrace flags verbose (glXQueryExtensionsString,
# glGetError returning GL_NO_ERROR...); this reader returns every call.
apitrace dump --verbose --multiline=no --color=never "$capture" | sed -n 's/^\([0-9][0-9]*\) \([A-Za-z_0-9]*\)(.*/\1 \2/p' > "$tmp/theirs"
echo "wasp-gltrace: $(wc -l < "$tmp/ours") calls; apitrace dump: $(wc -l < "$tmp/theirs") calls"
if ! cmp -s "$tmp/ours" "$tmp/theirs"; then
    echo "first difference:"
    diff "$tmp/ours" "$tmp/theirs" | head -5
    exit 1
fi
echo "identical call numbers and names"
