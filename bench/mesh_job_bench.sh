#!/bin/bash
# Time and peak memory of the mesh job of a tiled run (`--pass mesh`: read, repair, write
# DIR/mesh.part, cut the tile meshes; docs/tiles.md) for several geotex binaries, alternated,
# with each stage's time and the resident memory sampled every 0.2 s during it: all of it, and
# the anonymous part (RssAnon: what the job holds; the rest is pages of mapped files, which the
# system drops again when memory is short). Checks that every binary writes the same files, byte
# for byte.
#
#   bench/mesh_job_bench.sh [--join DIR] MESH TILES ROUNDS GEOTEX... [-- segment options]
#
# e.g. bench/mesh_job_bench.sh s11.ply 16 2 ./geotex-old build/geotex -- --scale 0.01
# With --join DIR, the last job instead: the join of the parts in DIR (every pass made, with
# the same options) into a segmentation PLY and a JSON report, which every binary must write
# the same.
# Prints one row per run: the binary, wall seconds, GNU time's peak (MB of 2^20 bytes) and,
# per stage, its seconds, the largest sampled RSS and the largest sampled RssAnon.
set -euo pipefail
JOIN=""
if [ "${1:-}" = "--join" ]; then
  JOIN=${2:?--join needs the directory of the parts}
  shift 2
fi
MESH=${1:?usage: mesh_job_bench.sh [--join DIR] MESH TILES ROUNDS GEOTEX... [-- options]}
TILES=${2:?}
ROUNDS=${3:?}
shift 3
binaries=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do binaries+=("$1"); shift; done
[ $# -gt 0 ] && shift
opts=("$@")
[ ${#opts[@]} -gt 0 ] || opts=(--scale 0.01)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {  # index binary: one run into $work/d$index, its row on stdout
  local i=$1 g=$2 dir=$work/d$1 job
  rm -rf "$dir"
  if [ -n "$JOIN" ]; then
    mkdir "$dir"
    job=(-o "$dir/seg.ply" --json "$dir/seg.json")
    dir=$JOIN
  else
    job=(--pass mesh)
  fi
  # Each stage line ("geotex: repair   24.2 s") stamped with the time it came, its stage's end.
  /usr/bin/time -f "%e %M" -o "$work/time" "$g" segment "$MESH" "${opts[@]}" --tiles "$TILES" \
    --tile-dir "$dir" "${job[@]}" >/dev/null \
    2> >(while IFS= read -r line; do echo "$(date +%s.%N) $line"; done >"$work/err") &
  local pid=$! child=""
  : >"$work/rss"
  while kill -0 $pid 2>/dev/null; do
    # The geotex process under GNU time ($! is the stamping's process substitution).
    [ -n "$child" ] || child=$(pgrep -f -- "^$g segment .*--tile-dir $dir " | head -1 || true)
    [ -n "$child" ] && awk -v t="$(date +%s.%N)" '/VmRSS/ {r = $2} /RssAnon/ {a = $2}
      END {if (r != "") print t, r, a}' \
      /proc/"$child"/status >>"$work/rss" 2>/dev/null || true
    sleep 0.2
  done
  wait
  sleep 0.2  # the stamping of the last lines
  # GNU time puts "Command exited with non-zero status N" before its numbers when the job fails.
  if grep -q '^Command ' "$work/time"; then
    echo "mesh_job_bench.sh: $g failed ($(head -1 "$work/time")): $(tail -1 "$work/err" | cut -d' ' -f2-)" >&2
    exit 1
  fi
  read -r s k <"$work/time"
  local stages
  stages=$(awk -v rssfile="$work/rss" '
    BEGIN { n = 0; while ((getline line < rssfile) > 0) { split(line, a, " "); t[n] = a[1]; r[n] = a[2]; h[n] = a[3]; n++ } }
    $2 == "geotex:" && $NF == "s" {
      end = $1; secs = $(NF - 1); name = ""
      for (f = 3; f < NF - 1; f++) name = name (f > 3 ? " " : "") $f
      peak = 0; held = 0
      for (i = 0; i < n; i++) if (t[i] >= end - secs && t[i] <= end) {
        if (r[i] > peak) peak = r[i]
        if (h[i] > held) held = h[i]
      }
      printf "%s %.1f s %d MB (held %d); ", name, secs, peak / 1024, held / 1024 }' "$work/err")
  printf '| %s | %.1f | %d | %s|\n' "$g" "$s" $((k / 1024)) "$stages"
}
echo "| binary | seconds | peak, MB | stages: seconds, largest sampled RSS (and RssAnon), MB |"
echo "|---|---|---|---|"
for ((round = 0; round < ROUNDS; round++)); do
  for i in "${!binaries[@]}"; do run "$i" "${binaries[$i]}"; done
done
for i in "${!binaries[@]}"; do
  [ "$i" = 0 ] && continue
  if diff -rq "$work/d0" "$work/d$i" >/dev/null; then
    echo "same files: ${binaries[0]} and ${binaries[$i]}"
  else
    echo "DIFFERENT files: ${binaries[0]} and ${binaries[$i]}" >&2
    exit 1
  fi
done
