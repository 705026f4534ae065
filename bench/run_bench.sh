#!/usr/bin/env bash
# Timings and peak memory of the pipeline (not a test). Each configuration runs in its own
# process so that the peak memory is that of the configuration.
#   bench/run_bench.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
build=${1:-build}
out=${2:-bench/out}
mkdir -p "$out"
bench="$build/geotex_bench"
geotex="$build/geotex"
report="$out/pipeline.md"
{
  echo "# geotex pipeline benchmark"
  echo
  echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo); $(date -u +%Y-%m-%d); commit $(git rev-parse --short HEAD 2>/dev/null || echo '?')"
  echo
  echo "## Stage times (seconds) on the synthetic sphere-1, scale 0.04, all cores"
  echo
  first=1
  for level in 5 6 7 8; do
    extra=""
    [ "$level" -le 7 ] && extra="--stock"
    if [ $first -eq 1 ]; then "$bench" --levels "$level" --dir "$out" $extra; first=0
    else "$bench" --levels "$level" --dir "$out" $extra | tail -n 1; fi
  done
  echo
  echo "The last column (level <= 7) is the stock CGAL path: read_polygon_mesh, an AABB tree"
  echo "over the faces and the closest point of every vertex, one thread."
  echo
  echo "## One thread vs all cores, level 7"
  echo
  "$bench" --levels 7 --threads 1 --dir "$out"
  echo
  echo "## End to end with the command line (read, segment, write PLY and JSON), level 7"
  echo
  "$geotex" synth -o "$out/s7.ply" --quiet >/dev/null
  for t in 1 2; do
    /usr/bin/time -f "threads $t: %e s wall, %M KB peak" "$geotex" segment "$out/s7.ply" --scale 0.04 \
      -o "$out/s7.seg.ply" --json "$out/s7.json" --threads $t --quiet 2>&1 >/dev/null
  done
} | tee "$report"
echo "wrote $report"
