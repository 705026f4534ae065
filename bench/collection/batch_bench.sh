#!/usr/bin/env bash
# Batch throughput on a synthetic collection: N level-5 spheres (20,480 faces, the paper's
# shape mix with varied layouts) annotated by `geotex batch --jobs J`, then the same batch
# rerun (everything up to date) and rerun with another dictionary (annotation only, from the
# geometry cache). Prints total time, meshes per minute and peak memory of the batch process
# and of the largest child, for N and for N/4, so that flat memory shows as equal peaks.
#
#   bench/collection/batch_bench.sh [GEOTEX] [N] [JOBS]     (defaults: build/geotex 1000 2)
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
G=$(readlink -f "${1:-$here/build/geotex}")
N=${2:-1000}
JOBS=${3:-2}
work=${WORK:-$(mktemp -d)}
trap '[ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
cd "$work"

mkdir -p meshes
echo "generating $N level-5 meshes in $work ..." >&2
seq 1 "$N" | xargs -P "$JOBS" -I{} "$G" synth -q --level 5 --layout-seed {} -o meshes/m{}.ply >/dev/null
rm -f meshes/*.truth.json
mkdir -p quarter && ls meshes | head -n $((N / 4)) | while read -r f; do ln -s "../meshes/$f" "quarter/$f"; done

# run LABEL INPUT OUTDIR [options]: wall time and the peak RSS of the batch process (VmHWM,
# sampled) and of its largest child (getrusage of the waited children, via GNU time).
run() {
  local label=$1 input=$2 out=$3; shift 3
  local start end parent_kb=0
  start=$(date +%s.%N)
  /usr/bin/time -f '%M' -o child.kb "$G" batch "$input" -o "$out" --jobs "$JOBS" --scale 0.04 -q "$@" >/dev/null &
  local tpid=$! bpid=""
  while kill -0 "$tpid" 2>/dev/null; do
    [ -n "$bpid" ] || bpid=$(pgrep -P "$tpid" -f "geotex batch" | head -n 1 || true)
    if [ -n "$bpid" ] && [ -r "/proc/$bpid/status" ]; then
      kb=$(awk '/^VmHWM/ {print $2}' "/proc/$bpid/status" 2>/dev/null || echo 0)
      [ "${kb:-0}" -gt "$parent_kb" ] && parent_kb=$kb
    fi
    sleep 0.2
  done
  wait "$tpid" || true
  end=$(date +%s.%N)
  local n ok
  n=$(($(wc -l < "$out/summary.csv") - 1))
  ok=$(grep -c ',ok,\|,skipped,' "$out/summary.csv" || true)
  awk -v l="$label" -v n="$n" -v ok="$ok" -v s="$start" -v e="$end" -v p="$parent_kb" -v c="$(cat child.kb)" \
    'BEGIN { t = e - s; printf "| %-34s | %5d | %5d | %8.1f | %8.1f | %7.1f | %7.1f |\n", l, n, ok, t, n / t * 60, p / 1024, c / 1024 }'
}

echo "geotex batch on $(nproc) cores, --jobs $JOBS, level-5 spheres (20,480 faces), --scale 0.04"
echo
echo "| run | meshes | ok or up to date | seconds | meshes/min | batch process MB | largest process MB |"
echo "|---|---|---|---|---|---|---|"
run "N/4 meshes, first run" quarter out-quarter
run "N meshes, first run" meshes out
run "N meshes, rerun (all up to date)" meshes out
sed 's/^  version: "[^"]*"/  version: "0.9"/' "$here/dictionaries/default.yaml" > old.yaml
run "N meshes, new dictionary (cache)" meshes out --dictionary old.yaml
