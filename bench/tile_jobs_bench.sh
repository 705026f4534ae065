#!/bin/bash
# Time and peak memory of a tiled segmentation run as separate jobs (docs/tiles.md), against
# the whole run and the one-process tiled run, in one run of this script: every tile of every
# pass is its own job (--tile K), as a Slurm array task would be, so each job's peak is
# measured alone; then the join. The jobs run twice: each reading and repairing the mesh
# itself, and after a first job that does it once (--pass mesh) for the others to read, and
# cuts the tile meshes that the jobs of every pass but the features read alone.
# Checks that all give the same PLY.
#
#   bench/tile_jobs_bench.sh GEOTEX MESH SCALE TILES [segment options]
#
# Prints one row per run and per pass: wall seconds (sum over the pass's jobs, and the
# slowest job) and the largest peak resident memory.
set -euo pipefail
G=${1:?usage: tile_jobs_bench.sh GEOTEX MESH SCALE TILES [options]}
MESH=${2:?}
SCALE=${3:?}
TILES=${4:?}
shift 4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
opts=(--scale "$SCALE" "$@")
measure() {  # label command...: appends "label seconds kB"
  /usr/bin/time -f "%e %M" -o "$work/t" "$@" >/dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 1; }
  read -r s k <"$work/t"
  printf '%s %s %s\n' "$label" "$s" "$k"
}
row() { printf '| %s | %s | %s | %s |\n' "$1" "$(fmt "$2")" "$(fmt "$3")" "$4"; }
fmt() { [ -n "$1" ] && printf '%.2f' "$1" || true; }
echo "| run | seconds | slowest job, s | peak, MB |"
echo "|---|---|---|---|"
label=whole; read -r _ s k < <(measure "$G" segment "$MESH" "${opts[@]}" -o "$work/whole.ply" -q)
row "whole mesh" "$s" "" "$((k / 1024))"
label=tiles; read -r _ s k < <(measure "$G" segment "$MESH" "${opts[@]}" --tiles "$TILES" -o "$work/one.ply" -q)
row "--tiles $TILES, one process" "$s" "" "$((k / 1024))"
jobs() {  # DIR what [--pass mesh first]
  local dir=$1 what=$2 mesh=${3:-}
  total=0
  if [ -n "$mesh" ]; then
    label=mesh; read -r _ s k < <(measure "$G" segment "$MESH" "${opts[@]}" --tiles "$TILES" \
      --tile-dir "$dir" --pass mesh -q)
    total=$s
    row "$what: pass mesh (1 job)" "$s" "" "$((k / 1024))"
  fi
  for pass in depth texels rims depth-without-rims texels-without-rims features; do
    sum=0; slowest=0; peak=0
    for t in $(seq 1 "$TILES"); do
      label=$pass; read -r _ s k < <(measure "$G" segment "$MESH" "${opts[@]}" --tiles "$TILES" \
        --tile-dir "$dir" --pass "$pass" --tile "$t" -q)
      sum=$(echo "$sum + $s" | bc); total=$(echo "$total + $s" | bc)
      (( $(echo "$s > $slowest" | bc) )) && slowest=$s
      (( k > peak )) && peak=$k
    done
    [ -d "$dir/$pass" ] && row "$what: pass $pass ($TILES jobs)" "$sum" "$slowest" "$((peak / 1024))" \
      || row "$what: pass $pass (not needed)" "$sum" "$slowest" "$((peak / 1024))"
  done
  label=join; read -r _ s k < <(measure "$G" segment "$MESH" "${opts[@]}" --tiles "$TILES" --tile-dir "$dir" -o "$dir.ply" -q)
  total=$(echo "$total + $s" | bc)
  row "$what: join" "$s" "" "$((k / 1024))"
  row "$what, all" "$total" "" ""
}
jobs "$work/parts" "jobs"
jobs "$work/prepared" "jobs after --pass mesh" mesh
echo "parts on disk: $(du -sm "$work/parts" | cut -f1) MB"
cmp -s "$work/whole.ply" "$work/one.ply" || echo "DIFFERENT: one-process tiles vs whole"
cmp -s "$work/whole.ply" "$work/parts.ply" || echo "DIFFERENT: joined jobs vs whole"
cmp -s "$work/whole.ply" "$work/prepared.ply" || echo "DIFFERENT: joined jobs after --pass mesh vs whole"
echo "mesh.part: $(du -m "$work/prepared/mesh.part" | cut -f1) MB, the tile meshes: $(du -sm "$work/prepared/mesh" | cut -f1) MB"
for pass in depth texels rims depth-without-rims texels-without-rims features; do
  [ -d "$work/parts/$pass" ] || continue
  for k in $(seq 1 "$TILES"); do
    cmp -s "$work/parts/$pass/tile-$k.part" "$work/prepared/$pass/tile-$k.part" ||
      echo "DIFFERENT: $pass part $k from its tile mesh"
  done
done
