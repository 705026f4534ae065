#!/usr/bin/env bash
# Triples per second into Virtuoso: `geotex publish` through the Graph Store HTTP Protocol
# (a graph per object, and one graph for the collection) against the bulk loader fed with
# `geotex publish --nquads`. Each way loads into a new private instance (scripts/virtuoso.sh,
# loopback, started and stopped here). OUTDIR is only read: publish writes its record and
# report into a scratch directory whose objects/ links to OUTDIR's.
#
#   bench/collection/store_load.sh OUTDIR [GEOTEX]        (GEOTEX: default build/geotex)
#   bench/collection/store_load.sh --make N OUTDIR [GEOTEX]
#       first makes OUTDIR: N synthetic objects (icosphere level 4, tests/make_outdir.py;
#       about 4,000 triples and 0.2 s each)
#
# Prints a table; numbers include everything the way costs (geotex parsing and sending,
# the store's parsing, indexing and, for the loader, the checkpoint).
set -euo pipefail

here=$(cd "$(dirname "$0")/../.." && pwd)
make_n=0
if [ "${1:-}" = "--make" ]; then make_n=$2; shift 2; fi
[ $# -ge 1 ] || { sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 1; }
outdir=$1
geotex=$(realpath "${2:-$here/build/geotex}")
virtuoso="$here/scripts/virtuoso.sh"

if [ "$make_n" -gt 0 ]; then
    specs=()
    for i in $(seq 1 "$make_n"); do specs+=("obj-$(printf %04d "$i"):4:$i"); done
    python3 "$here/tests/make_outdir.py" "$geotex" "$outdir" "${specs[@]}"
fi
[ -d "$outdir/objects" ] || { echo "store_load: $outdir: not a geotex batch directory" >&2; exit 1; }

work=$(mktemp -d)
current=""
cleanup() {
    [ -n "$current" ] && "$virtuoso" stop "$current" >/dev/null 2>&1 || true
    rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

start() {  # start DIR: a new instance; sets $http
    local ports
    ports=$(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
    current=$1
    "$virtuoso" start "$1" $ports >/dev/null
    http=$(sed -n 's/^http=//p' "$1/ports")
}
stop() { "$virtuoso" stop "$current"; current=""; }
now() { date +%s.%N; }
store_triples() {  # all quads of the instance (a new one holds a few of its own)
    curl -sf "http://127.0.0.1:$http/sparql" -H 'Accept: text/csv' \
        --data-urlencode 'query=SELECT (COUNT(*) AS ?n) WHERE { GRAPH ?g { ?s ?p ?o } }' | tail -n 1 | tr -d '"\r'
}
rows=()
row() { rows+=("$(printf '%-50s %8s %10s %9.2f %11.0f' "$1" "$2" "$3" "$4" "$(echo "$3 / $4" | bc -l)")"); }

mkdir "$work/out"
ln -s "$(realpath "$outdir/objects")" "$work/out/objects"
num_objects=$(find -L "$work/out/objects" -mindepth 2 -maxdepth 2 -name run.json | wc -l)

# Graph Store, one graph per object.
start "$work/vt-gs"
base=$(store_triples)
t0=$(now)
"$geotex" publish "$work/out" --endpoint "http://127.0.0.1:$http/sparql-graph-crud" --graph-per-object \
    --quiet >"$work/gs.txt"
t1=$(now)
sent=$(awk -F, 'NR > 1 && $3 == "sent" { n += $4 } END { print n + 0 }' "$work/out/publish-report.csv")
row "Graph Store, graph per object (PUT)" "$num_objects" "$sent" "$(echo "$t1 - $t0" | bc -l)"
in_store=$(($(store_triples) - base))
# One graph for the collection, same instance.
t0=$(now)
"$geotex" publish "$work/out" --endpoint "http://127.0.0.1:$http/sparql-graph-crud" \
    --graph urn:geotex:bench:collection --quiet >"$work/gs1.txt"
t1=$(now)
sent1=$(awk -F, 'NR > 1 && $3 == "sent" { n += $4 } END { print n + 0 }' "$work/out/publish-report.csv")
row "Graph Store, one graph (PUT, then POST)" "$num_objects" "$sent1" "$(echo "$t1 - $t0" | bc -l)"
stop

# N-Quads, then the bulk loader into a new instance.
t0=$(now)
"$geotex" publish "$work/out" --nquads "$work/all.nq" --quiet >"$work/nq.txt"
t1=$(now)
quads=$(wc -l <"$work/all.nq" | tr -d ' ')
row "geotex publish --nquads (file only)" "$num_objects" "$quads" "$(echo "$t1 - $t0" | bc -l)"
start "$work/vt-bulk"
base=$(store_triples)
t0=$(now)
"$virtuoso" bulkload "$current" "$work/all.nq"
t1=$(now)
row "bulk loader (ld_dir, rdf_loader_run, checkpoint)" "$num_objects" "$quads" "$(echo "$t1 - $t0" | bc -l)"
bulk_in_store=$(($(store_triples) - base))
stop

echo "store_load: $num_objects objects of $outdir; load average $(cut -d' ' -f1-3 /proc/loadavg); Virtuoso $(virtuoso-t -? 2>&1 | sed -n 's/.*Version \([0-9.]*\).*/\1/p' | head -1); $(nproc) cores; $(date -u +%Y-%m-%d)"
printf '%-50s %8s %10s %9s %11s\n' "way" "objects" "triples" "seconds" "triples/s"
printf '%s\n' "${rows[@]}"
echo "new triples in the store: $in_store after the Graph Store (graph per object), $bulk_in_store after the bulk load"
