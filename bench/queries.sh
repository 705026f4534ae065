#!/usr/bin/env bash
# Times every query of ontology/queries/ in `geotex query` (embedded) on a collection of N
# annotated level-L meshes, before and after issue 16 in one run, and prints a Markdown
# table (bench/RESULTS.md, "Queries", holds one):
#
#   [BEFORE=bc86672|none] [BEFORE_GEOTEX=path] [RUNS=3] [TIMEOUT=60] [JOBS=2] [WORK=dir] [KEEP=1] \
#     bench/queries.sh [GEOTEX] [N] [LEVEL]          (defaults: build/geotex 100 6)
#
# The collection: `geotex synth --level L` with layout seeds 1..N and varied shape counts
# (every fifth object half engraved), annotated by `geotex batch --scale 0.04` from three
# manifests: 80% with the default dictionary, 10% each with copies at versions 0.9 and 0.8
# (so that old-dictionary-version.rq has rows). Columns, each a wall time on JOBS cores:
# - before: geotex at the commit BEFORE (built from `git archive` in WORK, or BEFORE_GEOTEX
#   when given) with the queries as shipped at that commit;
# - old engine, new queries: the same binary with the working tree's queries, to tell what
#   the formulation gained from what the engine gained;
# - after: the working tree's geotex and queries; the median of RUNS runs, its peak RSS.
# A before run longer than TIMEOUT seconds is stopped and shown as "> TIMEOUT s" (BEFORE=none:
# the after column alone, e.g. again on the kept collection when the machine is quieter). The row
# "load only" is an ASK over the data: reading the files and building the store.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
geotex=$(readlink -f "${1:-$top/build/geotex}")
n=${2:-100}
level=${3:-6}
before=${BEFORE:-bc86672}
runs=${RUNS:-3}
timeout=${TIMEOUT:-60}
jobs=${JOBS:-2}
work=${WORK:-$(mktemp -d)}
mkdir -p "$work"
work=$(cd "$work" && pwd)
cleanup() { [ -n "${KEEP:-}" ] || rm -rf "$work"; }
trap cleanup EXIT

# --- the geotex of before ------------------------------------------------------------------
# Its sources from `git archive` (no worktree), or BEFORE_GEOTEX, a geotex built at BEFORE.
old_geotex=${BEFORE_GEOTEX:-}
if [ "$before" = none ]; then
  :
elif [ -z "$old_geotex" ]; then
  echo "building geotex at $before in $work/old ..." >&2
  mkdir -p "$work/old"
  git -C "$top" archive "$before" | tar -x -C "$work/old"
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S "$work/old" -B "$work/old/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGEOTEX_BUILD_TESTS=OFF \
    -DGEOTEX_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
  cmake --build "$work/old/build" --target geotex -j "$jobs" >/dev/null
  old_geotex="$work/old/build/geotex"
fi
old_queries="$work/old-queries"
mkdir -p "$old_queries"
if [ "$before" != none ]; then
  old_geotex=$(readlink -f "$old_geotex")
  for path in $(git -C "$top" ls-tree --name-only "$before" ontology/queries/ | grep '\.rq$'); do
    git -C "$top" show "$before:$path" >"$old_queries/$(basename "$path")"
  done
fi

# --- the collection ----------------------------------------------------------------------
cd "$work"
if [ ! -f collection.done ]; then
  echo "making $n level-$level objects in $work ..." >&2
  mkdir -p meshes
  seq 1 "$n" | xargs -P "$jobs" -I{} sh -c '
    i=$1; engraved=0; [ $((i % 5)) -eq 0 ] && engraved=0.5
    "$2" synth -q --level "$3" --layout-seed "$i" --threads 1 --engraved "$engraved" \
      --big-discs $((10 + i % 9)) --small-discs $((30 + i % 13)) --squares $((12 + i % 7)) \
      --rectangles $((14 + i % 8)) -o "meshes/m$i.ply" >/dev/null' _ {} "$geotex" "$level"
  rm -f meshes/*.truth.json
  for version in 0.9 0.8; do
    sed "s/^  version: \"[^\"]*\"\$/  version: \"$version\"/" "$top/dictionaries/default.yaml" >"default-$version.yaml"
  done
  first_old=$((n * 8 / 10 + 1))
  second_old=$((n * 9 / 10 + 1))
  { echo "mesh,id"; for i in $(seq 1 $((first_old - 1))); do echo "meshes/m$i.ply,m$i"; done; } >current.csv
  { echo "mesh,id"; for i in $(seq "$first_old" $((second_old - 1))); do echo "meshes/m$i.ply,m$i"; done; } >v09.csv
  { echo "mesh,id"; for i in $(seq "$second_old" "$n"); do echo "meshes/m$i.ply,m$i"; done; } >v08.csv
  "$geotex" batch current.csv -o out-current --jobs "$jobs" --scale 0.04 -q >/dev/null
  "$geotex" batch v09.csv -o out-v09 --jobs "$jobs" --scale 0.04 --dictionary default-0.9.yaml -q >/dev/null
  "$geotex" batch v08.csv -o out-v08 --jobs "$jobs" --scale 0.04 --dictionary default-0.8.yaml -q >/dev/null
  touch collection.done
fi
files=(out-*/objects/*/annotation.ttl)
triples=$(cat "${files[@]}" | rapper -q -i turtle -o ntriples - urn:x: | LC_ALL=C sort -u | wc -l | tr -d ' ')
echo "ASK { ?s ?p ?o }" >load-only.rq

# seconds QUERY BINARY [TIMEOUT]: one run's wall time, "> T" when stopped; the CSV in last.csv
seconds() {
  [ "$before" != none ] || { echo "-"; return; }
  local start end status
  start=$(date +%s.%N)
  set +e
  if [ -n "${3:-}" ]; then
    timeout "$3" "$2" query "$1" "${files[@]}" --format csv --threads "$jobs" >last.csv 2>last.err
  else
    "$2" query "$1" "${files[@]}" --format csv --threads "$jobs" >last.csv 2>last.err
  fi
  status=$?
  set -e
  end=$(date +%s.%N)
  if [ "$status" -eq 124 ]; then echo "> $3 s"; return; fi
  if [ "$status" -ne 0 ]; then echo "failed ($(head -c 60 last.err | tr '\n' ' '))"; return; fi
  awk -v s="$start" -v e="$end" 'BEGIN { printf "%.2f s", e - s }'
}

# after QUERY: the median of RUNS runs, the rows and the peak RSS of the last
after() {
  local times=() t
  for _ in $(seq 1 "$runs"); do
    /usr/bin/time -f '%M' -o rss.kb "$geotex" query "$1" "${files[@]}" --format csv --threads "$jobs" >last.csv 2>/dev/null &
    local pid=$! start end
    start=$(date +%s.%N)
    wait "$pid"
    end=$(date +%s.%N)
    t=$(awk -v s="$start" -v e="$end" 'BEGIN { printf "%.2f", e - s }')
    times+=("$t")
  done
  local median rows
  median=$(printf '%s\n' "${times[@]}" | sort -n | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }')
  rows=$(($(wc -l <last.csv) - 1))
  [ "$1" = load-only.rq ] && rows="-"
  printf '%s s | %s | %.0f' "$median" "$rows" "$(awk '{ print $1 / 1024 }' rss.kb)"
}

echo "| query | before: $before, its queries | $before, new queries | after: median of $runs | rows | MB |"
echo "|---|---|---|---|---|---|"
echo "| load only (ASK { ?s ?p ?o }) | $(seconds load-only.rq "$old_geotex" "$timeout") | - | $(after load-only.rq) |"
for q in "$top"/ontology/queries/*.rq; do
  name=$(basename "$q")
  old="-"
  if [ -f "$old_queries/$name" ]; then old=$(seconds "$old_queries/$name" "$old_geotex" "$timeout"); fi
  mixed=$(seconds "$q" "$old_geotex" "$timeout")
  echo "| $name | $old | $mixed | $(after "$q") |"
done
echo
echo "$n objects, level $level ($(( 20 * 4 ** level )) faces each), ${#files[@]} files, $triples distinct triples;" \
  "$(nproc) cores, --threads $jobs; load average at the end: $(cut -d' ' -f1-3 /proc/loadavg);" \
  "$(git -C "$top" rev-parse --short HEAD)$(git -C "$top" diff --quiet || echo ' (with changes)')."
