#!/usr/bin/env bash
# Reading speed of every mesh format (issue 21), not a test. The sphere-1 of LEVEL is written
# as binary and ASCII PLY, OBJ, OFF, ASCII and binary STL by geotex_read_bench, which times
# read_mesh_file on each (best of 3). With OLD_BUILD_DIR (a build of an earlier commit, e.g.
# the one before the text readers of our own), each file is also read by both commands'
# `geotex render` (its "reading" stage time), and `geotex segment` runs on the OBJ and the
# binary PLY with both, whose outputs must be the same bytes.
#   bench/read_bench.sh [BUILD_DIR] [OLD_BUILD_DIR] [OUT_DIR] [LEVEL]
# e.g. bench/read_bench.sh build ../main/build /tmp/read 8 (OUT_DIR default: $TMPDIR)
set -euo pipefail
build=${1:-build}
old=${2:-}
out=${3:-${TMPDIR:-/tmp}/geotex_read_bench}  # about 550 MB of meshes at level 8
level=${4:-8}
mkdir -p "$out"
new_geotex="$build/geotex"

echo "machine: $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg); $(date -u +%Y-%m-%d); commit $(git rev-parse --short HEAD 2>/dev/null || echo '?')"
echo
"$new_geotex" synth --level "$level" -o "$out/sphere.ply" --quiet >/dev/null
echo "### read_mesh_file, level $level"
echo
"$build/geotex_read_bench" "$out/sphere.ply" --dir "$out" --repeat 3
[ -n "$old" ] || exit 0
old_geotex="$old/geotex"

# The "reading" stage of `geotex render` (read_mesh_file alone), in seconds.
read_seconds() {
  "$1" render "$2" -o "$out/render.png" --size 16x16 --supersample 1 --threads 1 \
    --replace-read-only 2>&1 >/dev/null | awk '$2 == "reading" {print $3}'
}
best_of() {  # best_of N geotex file
  local best="" t
  for _ in $(seq "$1"); do
    t=$(read_seconds "$2" "$3")
    best=$(awk -v a="$best" -v b="$t" 'BEGIN {print (a == "" || b < a) ? b : a}')
  done
  echo "$best"
}
echo
echo "### geotex render's reading stage: before ($old_geotex, one run) and now (best of 3)"
echo
echo "| file | MB | before (s) | before MB/s | now (s) | now MB/s | speed-up |"
echo "|---|---|---|---|---|---|---|"
for f in mesh.ply mesh_ascii.ply mesh.obj mesh.off mesh_ascii.stl mesh_binary.stl; do
  mb=$(awk -v b="$(stat -c %s "$out/$f")" 'BEGIN {printf "%.1f", b / 1e6}')
  before=$(best_of 1 "$old_geotex" "$out/$f")
  now=$(best_of 3 "$new_geotex" "$out/$f")
  awk -v f="$f" -v mb="$mb" -v a="$before" -v b="$now" 'BEGIN {
    printf "| %s | %s | %.3f | %.0f | %.3f | %.0f | %.1f× |\n", f, mb, a, mb / a, b, mb / b, a / b }'
done

echo
echo "### geotex segment --scale 0.04 (all cores), wall time and peak memory"
echo
echo "| input | before | now | outputs |"
echo "|---|---|---|---|"
for f in mesh.ply mesh.obj; do
  row="| $f"
  for g in "$old_geotex" "$new_geotex"; do
    tag=$([ "$g" = "$old_geotex" ] && echo before || echo now)
    stats=$( { /usr/bin/time -f "%e s, %M KB" "$g" segment "$out/$f" --scale 0.04 --quiet \
      -o "$out/seg-$tag-$f.ply" --replace-read-only >/dev/null; } 2>&1 | tail -n 1)
    row="$row | $stats"
  done
  if cmp -s "$out/seg-before-$f.ply" "$out/seg-now-$f.ply"; then same="same bytes"; else same="DIFFER"; fi
  echo "$row | $same |"
done
