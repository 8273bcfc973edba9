#!/usr/bin/env bash
# Builds tests/gl/quads.c with the system C compiler and records it with
# apitrace under a virtual X server (Mesa's software rasterizer).
#   tests/gl/capture.sh [OUT]     (OUT defaults to tests/gl/quads.trace)
# Needs: gcc libgl-dev libx11-dev xvfb xauth apitrace libgl1-mesa-dri.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:-$here/quads.trace}"
for t in cc:gcc xvfb-run:xvfb xauth:xauth apitrace:apitrace; do
    command -v "${t%%:*}" >/dev/null 2>&1 || {
        echo "capture.sh: ${t%%:*} is missing: apt-get install ${t##*:}" >&2
        exit 1
    }
done
bin="$(mktemp -d)/quads"
trap 'rm -rf "$(dirname "$bin")"' EXIT
cc -std=c99 -O1 -Wall -Wextra -Werror -o "$bin" "$here/quads.c" -lGL -lX11
rm -f "$out"
LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 320x240x24" \
    apitrace trace --api gl -o "$out" "$bin" >/dev/null
echo "capture.sh: wrote $out ($(stat -c %s "$out") bytes)"
