#!/usr/bin/env bash
# The queries of ontology/queries/ on a small collection, run as a user would with
# `geotex query` over all the files: four synthetic objects (icosphere level 4) annotated with
# distinct --base IRIs, two of them with older copies of the default dictionary.
# 1. The rows of the cross-object queries against rows computed here from the JSON reports of
#    the runs (chosen concepts, feature values, dictionary version), not from the RDF.
# 2. Every shipped query, and parameter variants, gives the same rows in rdflib and Oxigraph
#    (tests/query_engines.py) as in `geotex query`.
#   tests/collection_queries_test.sh GEOTEX SOURCE_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
q="$src/ontology/queries"

# --- the collection -----------------------------------------------------------------------
# The dictionary as it was before its last two releases: the same concepts, versions 0.9 and
# 0.8 (the scheme's IRI does not change with the version); 0.8 also had a narrower "small
# perimeter" (issue 16: a concept whose interval changed keeps its IRI).
for version in 0.9 0.8; do
  sed "s/^  version: \"[^\"]*\"\$/  version: \"$version\"/" "$src/dictionaries/default.yaml" >"default-$version.yaml"
  [ "$(grep -c "^  version: \"$version\"\$" "default-$version.yaml")" -eq 1 ] \
    || fail "default-$version.yaml: the version line of default.yaml has changed"
done
sed -i '/- id: small-perimeter$/,/interval:/ s/interval: \[0\.07, 0\.4\]/interval: [0.07, 0.3]/' default-0.8.yaml
grep -q 'interval: \[0.07, 0.3\]' default-0.8.yaml || fail "default-0.8.yaml: the small-perimeter interval of default.yaml has changed"
for version in 0.9 0.8; do
  "$geotex" dict check "default-$version.yaml" >/dev/null || fail "default-$version.yaml is not a clean dictionary"
done
namespace=$(sed -n 's/^  namespace: "\(.*\)"$/\1/p' "$src/dictionaries/default.yaml")
[ -n "$namespace" ] || fail "no namespace in default.yaml"

# object, synth options, annotate options. The amphora has raised and engraved discs, so two
# textures with --orientation both; the others one texture each; the cup and the vase use
# the older dictionaries.
objects=(
  "amphora|--layout-seed 1 --big-discs 12 --small-discs 0 --squares 0 --rectangles 0 --engraved 0.5|--orientation both"
  "bowl|--layout-seed 5 --big-discs 6 --small-discs 0 --squares 0 --rectangles 0|"
  "cup|--layout-seed 3 --big-discs 3 --small-discs 0 --squares 4 --rectangles 3|--dictionary default-0.8.yaml"
  "vase|--layout-seed 1 --big-discs 5 --small-discs 0 --squares 0 --rectangles 5|--dictionary default-0.9.yaml"
)
files=()
for entry in "${objects[@]}"; do
  IFS='|' read -r name synth_options annotate_options <<<"$entry"
  # shellcheck disable=SC2086 # the option strings are word lists
  "$geotex" synth -o "$name.ply" --level 4 $synth_options --quiet >/dev/null || fail "synth $name"
  # shellcheck disable=SC2086
  "$geotex" annotate "$name.ply" --scale 0.05 $annotate_options --base "https://collection.example.org/object/$name/" \
    -o "$name.ttl" --json "$name.json" --quiet >/dev/null || fail "annotate $name"
  files+=("$name.ttl")
done

# Runs one query over the whole collection as CSV; $2 (optional) is a sed script that edits
# the query's parameter line first.
run_query() {
  local query="$q/$1.rq"
  if [ -n "${2:-}" ]; then
    sed "$2" "$query" >edited.rq
    cmp -s edited.rq "$query" && fail "$1: the edit '$2' changed nothing"
    query=edited.rq
  fi
  "$geotex" query "$query" "${files[@]}" --format csv >"$3" || fail "$1 did not run"
}

# Compares the CSV of a query with the rows that check.py computes from the reports.
compare() {
  /usr/bin/python3 "$work/check.py" "$@" || fail "$1 ($2): rows differ (see above)"
}
cat >check.py <<'PY'
import csv, json, sys

query, what, result, namespace = sys.argv[1:5]
names = ["amphora", "bowl", "cup", "vase"]
reports = {n: json.load(open(n + ".json", encoding="utf-8")) for n in names}
mesh = {n: "https://collection.example.org/object/%s/mesh" % n for n in names}
rows = list(csv.reader(open(result, newline="", encoding="utf-8")))
header, rows = rows[0], rows[1:]

def textures(n):
    return reports[n]["annotation"]["textures"]

if query == "objects-sharing-concept":
    # Concept id -> English label (the runs used --lang en), per object.
    concepts = {n: {c["concept"]: c["label"] for t in textures(n) for c in t["concepts"]} for n in names}
    expected = []
    for a in names:
        for b in names:
            if mesh[a] < mesh[b]:
                for cid in sorted(set(concepts[a]) & set(concepts[b])):
                    expected.append([a + ".ply", b + ".ply", namespace + cid, concepts[a][cid], mesh[a], mesh[b]])
    expected.sort()
    ok = header == ["object1", "object2", "concept", "label", "mesh1", "mesh2"] and rows == expected
    ok = ok and len(expected) > 0
elif query == "feature-distribution":
    feature = what
    expected = []
    for n in names:
        values = [f["value"] for t in textures(n) for f in t["features"] if f["feature"] == feature]
        expected.append([n + ".ply", mesh[n], len(values), min(values), sum(values) / len(values), max(values)])
    ok = header == ["object", "mesh", "textures", "min", "mean", "max"] and len(rows) == len(expected)
    for got, exp in zip(rows, expected):
        # min and max are values of the data: the same doubles (the report writes 17
        # significant digits, the RDF the shortest exact form). The mean is summed in
        # another order: a few ulps.
        ok = ok and got[:2] == exp[:2] and int(got[2]) == exp[2]
        ok = ok and float(got[3]) == exp[3] and float(got[5]) == exp[5]
        ok = ok and abs(float(got[4]) - exp[4]) <= 1e-14 * max(abs(exp[4]), 1e-300)
    ok = ok and any(e[2] > 1 for e in expected)
else:  # old-dictionary-version
    version = {n: reports[n]["annotation"]["dictionary"]["version"] for n in names}
    reference = what if what != "newest" else max(version.values())
    expected = [[n + ".ply", mesh[n], namespace + "scheme", version[n], reference]
                for n in names if version[n] != reference]
    ok = header == ["object", "mesh", "scheme", "version", "reference"] and rows == expected
    ok = ok and len(expected) > 0

if not ok:
    print("%s (%s): got" % (query, what))
    for r in [header] + rows:
        print("  ", r)
    print("expected")
    for r in expected:
        print("  ", r)
sys.exit(0 if ok else 1)
PY

# --- the collection as one graph ------------------------------------------------------------
# What a store holds: the runs of three versions of one dictionary, each version's intervals
# on their own nodes, so the union conforms to the shapes (issue 16).
for f in "${files[@]}"; do rapper -q -i turtle -o ntriples "$f" || fail "rapper $f"; done >collection.nt
"$src/tests/rdf_peer_check.sh" collection.nt "$src/ontology/shapes.ttl" >peer.txt 2>&1 || { cat peer.txt; fail "the collection does not conform to the shapes"; }
/usr/bin/python3 - collection.nt "$namespace" <<'PY' || fail "versions in the collection (see above)"
import sys, rdflib
GTX = rdflib.Namespace("https://w3id.org/geotex/ns#")
g = rdflib.Graph(); g.parse(sys.argv[1], format="nt")
concept = rdflib.URIRef(sys.argv[2] + "small-perimeter")
uppers = sorted(str(g.value(i, GTX.upperBound)) for i in g.objects(concept, GTX.hasInterval))
versions = sorted(str(v) for v in g.subjects(rdflib.RDF.type, GTX.DictionaryVersion))
print("small-perimeter upper bounds:", uppers, "versions:", versions)
sys.exit(0 if uppers == ["0.3", "0.4", "0.4"] and len(versions) == 3 else 1)
PY

# --- the queries ----------------------------------------------------------------------------
run_query objects-sharing-concept "" sharing.csv
compare objects-sharing-concept en sharing.csv "$namespace"

run_query feature-distribution "" distribution.csv
compare feature-distribution contour_sphericity distribution.csv "$namespace"
run_query feature-distribution 's/(gtx:contour_sphericity) }   # <- the feature/(gtx:area) }   # <- the feature/' area.csv
compare feature-distribution area area.csv "$namespace"

run_query old-dictionary-version "" old.csv
compare old-dictionary-version newest old.csv "$namespace"
run_query old-dictionary-version 's/BIND("" AS ?given)/BIND("0.9" AS ?given)/' given.csv
compare old-dictionary-version 0.9 given.csv "$namespace"

# --- every shipped query in two other SPARQL 1.1 engines ----------------------------------
# texture-labels.rq: `labels` is a GROUP_CONCAT, whose order SPARQL leaves open.
[ -d "$src/tests/js/node_modules/oxigraph" ] || fail "npm package oxigraph missing: run  npm ci --prefix $src/tests/js"
command -v node >/dev/null || fail "node not found: apt-get install -y nodejs npm"
engines() {  # QUERY.rq ...: each in both engines; fails unless every comparison agrees
  local args=() f
  for f in "$@"; do args+=(--query "$f"); done
  /usr/bin/python3 "$src/tests/query_engines.py" --unordered "texture-labels.rq:labels:, " \
    "${args[@]}" "$geotex" "${files[@]}" >engines.txt 2>&1 || { cat engines.txt; fail "engines: $*"; }
  [ "$(grep -c ', the same$' engines.txt)" -eq $((2 * $#)) ] || { cat engines.txt; fail "engines: not all compared: $*"; }
}
engines "$q"/*.rq
# Parameter variants, edited as a user would.
variant() {  # NAME SED-SCRIPT
  sed "$2" "$q/$1.rq" >"$1.rq"
  cmp -s "$1.rq" "$q/$1.rq" && fail "$1: the edit '$2' changed nothing"
  engines "$1.rq"
}
variant objects-with-concept 's/VALUES (?id) { ("circular-shape") }/VALUES (?id) { ("thick-shape") ("large-area") }/'
variant textures-with-concept 's/VALUES (?id) { ("circular-shape") }/VALUES (?id) { ("no-such-concept") }/'
variant texture-labels 's/= "en")/= "fr")/'
variant features-by-significance 's/= "en")/= "fr")/'
variant objects-sharing-concept 's/= "en")/= "fr")/'
variant feature-distribution 's/(gtx:contour_sphericity) }   # <- the feature/(gtx:area) (gtx:depth_mean) }   # <- the feature/'
variant old-dictionary-version 's/BIND("" AS ?given)/BIND("0.9" AS ?given)/'

# --- hostile queries and data (issue 17) ----------------------------------------------------
# refused EXPECTED-EXIT WORDS OUTFILE -- ARGS...: `geotex query ARGS` exits EXPECTED-EXIT with
# one line on stderr holding WORDS and nothing on stdout.
refused() {
  local code=$1 words=$2 name=$3 status
  shift 4
  timeout 60 "$geotex" query "$@" >"$name.out" 2>"$name.err"
  status=$?
  [ "$status" -eq "$code" ] || fail "$name: exit $status, expected $code ($(cat "$name.err"))"
  [ "$(wc -l <"$name.err")" -eq 1 ] || fail "$name: not one line on stderr: $(cat "$name.err")"
  grep -qF -- "$words" "$name.err" || fail "$name: no '$words' in: $(cat "$name.err")"
  [ ! -s "$name.out" ] || fail "$name: wrote a partial result"
}
# SERVICE reaches no file and no host: refused before Rasqal runs, at the keyword's place. A
# local listener that accepts and never answers records any connection (Rasqal would hang on it).
printf 'SELECT * WHERE {\n  ?s ?p ?o .\n  # SERVICE <file:///etc/hostname> in a comment\n  SERVICE <file:///etc/passwd> { ?a ?b ?c }\n}\n' >service-file.rq
refused 2 "service-file.rq:4:3: SERVICE is refused" service-file -- service-file.rq "${files[0]}"
/usr/bin/python3 - >listener.port <<'PY' &
import socket, sys, time
s = socket.socket(); s.bind(("127.0.0.1", 0)); s.listen(5)
print(s.getsockname()[1], flush=True); sys.stdout.close()
s.settimeout(60)
try:
    conn, _ = s.accept()
    open("listener.connected", "w").write("yes")
    time.sleep(60)
except socket.timeout:
    pass
PY
listener=$!
for _ in $(seq 50); do [ -s listener.port ] && break; sleep 0.1; done
port=$(cat listener.port)
printf 'PREFIX ex: <http://ex.org/>\nSELECT * WHERE { ?s ?p ?o . service silent <http://127.0.0.1:%s/sparql> { ?a ?b ?c } }\n' "$port" >service-http.rq
refused 2 "service-http.rq:2:29: SERVICE is refused" service-http -- service-http.rq "${files[0]}"
sleep 0.5
[ ! -e listener.connected ] || fail "service-http: geotex connected to the SERVICE host"
kill "$listener" 2>/dev/null; wait "$listener" 2>/dev/null
# Neither FROM nor a string or IRI that merely says SERVICE.
printf 'SELECT ?s FROM <file:///etc/passwd> WHERE { ?s ?p ?o }\n' >from.rq
refused 2 "FROM and FROM NAMED are not supported" from -- from.rq "${files[0]}"
printf 'SELECT (COUNT(*) AS ?n) WHERE { ?s ?p ?o FILTER(?o != "SERVICE <http://x/>" && ?s != <http://x/SERVICE>) }\n' >not-service.rq
"$geotex" query not-service.rq "${files[0]}" --format csv >not-service.csv || fail "not-service.rq refused"

# --timeout: the issue's four-way cross join over 200 triples (1.6e9 rows) ends at the limit.
/usr/bin/python3 -c '
for i in range(200): print("<http://ex.org/s%d> <http://ex.org/p%d> \"v%d\" ." % (i, i % 7, i))' >d200.nt
printf 'SELECT (COUNT(*) AS ?n) WHERE { ?a ?p ?o . ?b ?p2 ?o2 . ?c ?p3 ?o3 . ?d ?p4 ?o4 }\n' >cross.rq
refused 3 "cross.rq: the query ran out of time" cross -- cross.rq d200.nt --timeout 1
refused 3 "--timeout" cross-json -- cross.rq d200.nt --timeout 0.5 --format json
# A loop inside Rasqal that never asks geotex's store (a product of VALUES blocks, 1.6e9 rows):
# the watchdog ends it 5 s past the limit, with the same error.
/usr/bin/python3 -c '
v = " ".join("(%d)" % i for i in range(200))
print("SELECT (COUNT(*) AS ?n) WHERE { " + " ".join("VALUES (?%s) {%s}" % (x, v) for x in "abcd") + " }")' >values.rq
refused 3 "values.rq: the query ran out of time" values -- values.rq d200.nt --timeout 1
for bad in nan -1 inf -inf; do
  refused 1 "--timeout must be a number of seconds" "timeout$bad" -- cross.rq d200.nt --timeout "$bad"
done
printf 'SELECT (COUNT(*) AS ?n) WHERE { ?a ?p ?o . ?b ?p2 ?o2 }\n' >pairs.rq
"$geotex" query pairs.rq d200.nt --timeout 60 --format csv >pairs.csv || fail "pairs.rq with --timeout 60"
[ "$(tail -n 1 pairs.csv | tr -d '\r')" = 40000 ] || fail "pairs.rq: $(cat pairs.csv), expected 40000"

# A query file with a UTF-8 byte order mark; a literal holding U+0000 (finding 11).
printf '\357\273\277SELECT (COUNT(*) AS ?n) WHERE { ?s ?p ?o }\n' >bom.rq
"$geotex" query bom.rq d200.nt --format csv >bom.csv 2>bom.err || fail "bom.rq: $(cat bom.err)"
[ "$(tail -n 1 bom.csv | tr -d '\r')" = 200 ] || fail "bom.rq: $(cat bom.csv)"
printf '<http://ex.org/a> <http://ex.org/p> "a\\u0000b" .\n<http://ex.org/b> <http://ex.org/p> "c\\\\u0000d" .\n' >nul.nt
printf 'SELECT ?o WHERE { ?s ?p ?o } ORDER BY ?s\n' >nul.rq
"$geotex" query nul.rq nul.nt --format json >nul.json || fail "nul.rq json"
/usr/bin/python3 -c '
import json, sys
values = [b["o"]["value"] for b in json.load(open("nul.json"))["results"]["bindings"]]
assert values == ["a\0b", "c\\u0000d"], values' || fail "nul.rq: JSON values $(cat nul.json)"
"$geotex" query nul.rq nul.nt --format csv >nul.csv || fail "nul.rq csv"
[ "$(sed -n 2p nul.csv | tr -d '\r')" = 'a\u0000b' ] || fail "nul.rq: CSV $(cat -A nul.csv)"
"$geotex" query nul.rq nul.nt >nul.txt || fail "nul.rq table"
grep -qxF 'a\u0000b' nul.txt || fail "nul.rq: table $(cat -A nul.txt)"

finish "collection query"
