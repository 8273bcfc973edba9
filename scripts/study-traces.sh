# Sourced by scripts/machines.sh and scripts/calibrate.sh: the study's
# scenes and their traces, cached in target/machines/traces.
#
#   study_scenes WASP              the study's scenes (docs/reproduce.md):
#                                  every scene, but a loader scene with an
#                                  engine twin (NAME-engine) counts through
#                                  its twin
#   study_traces WASP REPO SCENES  render each scene's trace unless the cache
#                                  holds one of this build and trace format;
#                                  prints the scenes it rendered, one a line

study_scenes() {
  "$1" scenes list | awk 'NR > 1 && $1 != "scene" && NF >= 6 {print $1}' \
    | awk '{ s[NR] = $1; have[$1] = 1 } END { for (i = 1; i <= NR; i++) if (!((s[i] "-engine") in have)) print s[i] }'
}

study_traces() {
  local w=$1 repo=$2 s t version stamp build_id
  shift 2
  local dir=$repo/target/machines/traces
  mkdir -p "$dir"
  # The trace format the front end writes (FORMAT_VERSION in
  # trace/src/limits.rs): a cached trace of another version (before
  # wasp-trace 3: no Early-Z-rejected quads; before 4: no trilinear marks)
  # is rendered again.
  version=$(sed -n 's/^pub const FORMAT_VERSION: u32 = \([0-9][0-9]*\);$/\1/p' "$repo/trace/src/limits.rs")
  [ -n "$version" ] || { echo "no FORMAT_VERSION in trace/src/limits.rs" >&2; return 1; }
  # A trace of another build may come from another loader: the cache holds
  # the traces of one build of wasp (its hash in .wasp-binary).
  stamp=$dir/.wasp-binary
  build_id=$(sha256sum "$w" | cut -c1-16)
  if [ "$(cat "$stamp" 2>/dev/null)" != "$build_id" ]; then
    rm -f "$dir"/*.trace
    echo "$build_id" > "$stamp"
  fi
  for s in "$@"; do
    t=$dir/$s.trace
    if [ -s "$t" ] && [ "$(head -n 1 "$t")" != "wasp-trace $version" ]; then
      rm -f "$t"
    fi
    if [ ! -s "$t" ]; then
      echo "== render $s" >&2
      "$w" render "$s" --trace-out "$t.tmp" -q && mv "$t.tmp" "$t"
      echo "$s"
    fi
  done
}
