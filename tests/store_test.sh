#!/usr/bin/env bash
# geotex publish into a real triple store: a private Virtuoso (scripts/virtuoso.sh) gets a
# small batch output directory through the Graph Store HTTP Protocol, one graph per object
# and then one graph for the collection; every query of ontology/queries/ must give the same
# rows there as `geotex query` over the same files; reruns send nothing, a changed object
# replaces its graph; the N-Quads of `geotex publish --nquads` through the bulk loader give
# the same graphs and answers.
#   tests/store_test.sh GEOTEX SOURCE_DIR
# Exit 77 (ctest: skipped) when Virtuoso is not installed (scripts/setup-deps.sh test).
set -u
geotex=$(realpath "$1")
src=$(realpath "$2")
virtuoso="$src/scripts/virtuoso.sh"
compare="$src/tests/sparql_compare.py"
command -v virtuoso-t >/dev/null && command -v isql-vt >/dev/null || {
    echo "SKIP: Virtuoso is not installed (scripts/setup-deps.sh test)"; exit 77; }
command -v rapper >/dev/null || { echo "SKIP: rapper (raptor2-utils) is not installed"; exit 77; }

work=$(mktemp -d)
vt="$work/virtuoso"
cleanup() {
    "$virtuoso" stop "$vt" >/dev/null 2>&1
    rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP
cd "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
die() { echo "FAIL: $*"; exit 1; }

read -r port_sql port_http < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
"$virtuoso" start "$vt" "$port_sql" "$port_http" || die "Virtuoso did not start"
ep="http://127.0.0.1:$port_http/sparql-graph-crud"
sparql="http://127.0.0.1:$port_http/sparql"

# --- a batch output directory: three objects, one with a space and an accent in its id ------------
mkdir meshes
"$geotex" synth -q --level 4 --layout-seed 4 -o meshes/vase-1.ply >/dev/null || die "synth"
"$geotex" synth -q --level 3 --layout-seed 9 -o 'meshes/bowl é 3.ply' >/dev/null || die "synth"
"$geotex" synth -q --level 3 --layout-seed 5 -o meshes/vase-2.ply >/dev/null || die "synth"
rm meshes/*.truth.json
"$geotex" batch meshes -o out --scale 0.08 --base-template 'https://example.org/object/{id}/' -q >/dev/null ||
    die "geotex batch"
# id, graph, annotation.ttl of each object, tab-separated.
python3 - out >objects.tsv <<'PY'
import json, os, sys
root = os.path.join(sys.argv[1], "objects")
for i in sorted(os.listdir(root)):
    run = json.load(open(os.path.join(root, i, "run.json"), encoding="utf-8"))
    print(i, run["graph"], os.path.join(root, i, "annotation.ttl"), sep="\t")
PY
[ "$(wc -l <objects.tsv)" -eq 3 ] || die "expected 3 objects: $(cat objects.tsv)"

sparql_value() {  # the single value of a one-cell SELECT
    curl -sf --max-time 30 "$sparql" --data-urlencode "query=$1" -H 'Accept: text/csv' | tail -n 1 | tr -d '"\r'
}
graph_count() { sparql_value "SELECT (COUNT(*) AS ?n) WHERE { GRAPH <$1> { ?s ?p ?o } }"; }
file_count() { cat "$@" | rapper -q -i turtle -o ntriples - urn:x: | LC_ALL=C sort -u | wc -l | tr -d ' '; }

# Every query of ontology/queries/, with per-query normalisation, each justified:
# - texture-labels.rq: `labels` is a GROUP_CONCAT, whose order SPARQL leaves open: the
#   labels are compared as a multiset.
queries=()
for q in "$src"/ontology/queries/*.rq; do queries+=(--query "$q"); done
[ ${#queries[@]} -ge 10 ] || die "ontology/queries/ should hold at least 5 queries"
compare() { python3 "$compare" --sparql "$sparql" --unordered "texture-labels.rq:labels:, " "${queries[@]}" "$@"; }

# Every documented query, for each object in its own graph (the store's default graph is
# that graph) against `geotex query` over its file. Per object, because Virtuoso matches
# the merge of several graphs quad by quad: the dictionary's concept scheme, which every
# object's graph carries, would then match once per graph (rows joined with it repeat); the
# collection is compared below, in one graph.
compare_objects() {
    local phase=$1 id graph ttl
    while IFS=$'\t' read -r id graph ttl; do
        compare --graph "$graph" "$geotex" "$ttl" >cmp.txt 2>&1 || { cat cmp.txt; fail "$phase: queries on '$id'"; }
    done <objects.tsv
}

check_graph_counts() {
    local phase=$1 id graph ttl n
    while IFS=$'\t' read -r id graph ttl; do
        n=$(graph_count "$graph")
        [ "$n" = "$(file_count "$ttl")" ] || fail "$phase: <$graph> holds $n triples, '$id' has $(file_count "$ttl")"
    done <objects.tsv
}

# --- one graph per object through the Graph Store protocol ---------------------------------------
"$geotex" publish out --endpoint "$ep" --graph-per-object --quiet >publish1.txt 2>&1 || { cat publish1.txt; fail "publish"; }
[ "$(grep -c '^sent ' publish1.txt)" -eq 3 ] || fail "publish: 3 objects sent: $(cat publish1.txt)"
check_graph_counts "graph per object"
compare_objects "graph per object"

# --- a rerun sends nothing -------------------------------------------------------------------------
cp out/published.json published1.json
"$geotex" publish out --endpoint "$ep" --graph-per-object --quiet >publish2.txt 2>&1 || fail "rerun"
[ "$(grep -c '^unchanged ' publish2.txt)" -eq 3 ] || fail "rerun: all unchanged: $(cat publish2.txt)"
cmp -s published1.json out/published.json || fail "rerun changed published.json"
grep -q ',unchanged,' out/publish-report.csv && ! grep -q ',sent,' out/publish-report.csv || fail "rerun: report"

# --- the authenticated endpoint (HTTP digest; a new database has dba/dba), in chunks -------------
auth="http://127.0.0.1:$port_http/sparql-graph-crud-auth"
GEOTEX_STORE_PASSWORD=dba "$geotex" publish out --endpoint "$auth" --user dba --graph-per-object \
    --chunk-triples 1000 --quiet >publish-auth.txt 2>&1 || { cat publish-auth.txt; fail "publish with digest authentication"; }
[ "$(grep -c '^sent ' publish-auth.txt)" -eq 3 ] || fail "authenticated: 3 objects sent: $(cat publish-auth.txt)"
[ "$(awk -F, '$3 == "sent" && $6 > 1' out/publish-report.csv | wc -l)" -eq 3 ] || fail "authenticated: chunked: $(cat out/publish-report.csv)"
check_graph_counts "chunked, authenticated"
"$geotex" publish out --endpoint "$auth" --user dba --password wrong --graph-per-object --force --quiet >auth-bad.txt 2>&1
[ $? -eq 3 ] && grep -q "^geotex: error: .*HTTP 401" auth-bad.txt || fail "wrong password: $(cat auth-bad.txt)"

# --- a changed object replaces its graph ----------------------------------------------------------
IFS=$'\t' read -r id1 graph1 ttl1 <objects.tsv
before=$(graph_count "$graph1")
grep -q '"geotex"' "$ttl1" || die "'$id1': no \"geotex\" literal to change"
sed -i 's/"geotex"/"geotex (changed)"/' "$ttl1"
python3 "$src/tests/make_outdir.py" --restamp out "$id1" || die "restamp"
"$geotex" publish out --endpoint "$ep" --graph-per-object --quiet >publish3.txt 2>&1 || fail "publish a changed object"
[ "$(grep -c '^sent ' publish3.txt)" -eq 1 ] && grep -q "^sent .* $id1\$" publish3.txt || fail "changed object: $(cat publish3.txt)"
[ "$(graph_count "$graph1")" = "$before" ] || fail "changed object: <$graph1> holds $(graph_count "$graph1") triples, not $before"
[ "$(sparql_value "SELECT (COUNT(*) AS ?n) WHERE { GRAPH <$graph1> { ?s ?p \"geotex (changed)\" } }")" = 1 ] &&
    [ "$(sparql_value "SELECT (COUNT(*) AS ?n) WHERE { GRAPH <$graph1> { ?s ?p \"geotex\" } }")" = 0 ] ||
    fail "changed object: the graph does not hold the new version alone"

# --- the collection in one graph: the same rows as geotex query over all files --------------------
coll="urn:geotex:test:collection"
"$geotex" publish out --endpoint "$ep" --graph "$coll" --quiet >publish4.txt 2>&1 || { cat publish4.txt; fail "publish --graph"; }
mapfile -t ttls < <(cut -f3 objects.tsv)
[ "$(graph_count "$coll")" = "$(file_count "${ttls[@]}")" ] || fail "--graph: <$coll> holds $(graph_count "$coll") triples"
compare --graph "$coll" "$geotex" "${ttls[@]}" >cmp.txt 2>&1 || { cat cmp.txt; fail "collection: queries"; }
"$geotex" publish out --endpoint "$ep" --graph "$coll" --quiet >publish5.txt 2>&1 || fail "rerun --graph"
[ "$(grep -c '^unchanged ' publish5.txt)" -eq 3 ] || fail "rerun --graph: $(cat publish5.txt)"

# --- the bulk loader: N-Quads of the same objects, after dropping their graphs --------------------
"$geotex" publish out --nquads all.nq --quiet >nquads.txt 2>&1 || { cat nquads.txt; fail "--nquads"; }
while IFS=$'\t' read -r id graph ttl; do
    enc=$(python3 -c 'import sys, urllib.parse; print(urllib.parse.quote(sys.argv[1], safe=""))' "$graph")
    curl -sf --max-time 30 -X DELETE "$ep?graph=$enc" >/dev/null || fail "DELETE <$graph>"
    [ "$(graph_count "$graph")" = 0 ] || fail "<$graph> not empty after DELETE"
done <objects.tsv
"$virtuoso" bulkload "$vt" all.nq >bulk.txt 2>&1 || { cat bulk.txt; fail "bulk load"; }
check_graph_counts "bulk loader"
compare_objects "bulk loader"

[ "$failures" -eq 0 ] && echo "store tests passed" || { echo "$failures store test(s) failed"; exit 1; }
