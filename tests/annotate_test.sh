#!/usr/bin/env bash
# The semantic layer as a user runs it: annotate the paper's synthetic sphere-1, check the
# paper's Figure 12 outcome through the example SPARQL queries, check the RDF with
# independent parsers and a SHACL validator, determinism, and hostile names.
#   tests/annotate_test.sh GEOTEX SOURCE_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
q="$src/ontology/queries"

# --- sphere-1 at level 7, the paper's mesh -------------------------------------------------
"$geotex" synth -o sphere-1.ply --quiet >/dev/null || fail synth
"$geotex" annotate sphere-1.ply --scale 0.04 -o s1.ttl --json s1.json --jsonld s1.jsonld --threads 2 --quiet >annotate.txt || fail "annotate"
"$geotex" annotate sphere-1.ply --scale 0.04 -o s1-one-thread.ttl --threads 1 --quiet >/dev/null || fail "annotate, 1 thread"
cmp -s s1.ttl s1-one-thread.ttl || fail "Turtle differs between 1 and 2 threads"
"$geotex" annotate sphere-1.ply --scale 0.04 -o s1-again.ttl --jsonld s1-again.jsonld --quiet >/dev/null
cmp -s s1.ttl s1-again.ttl || fail "Turtle differs between two runs"
cmp -s s1.jsonld s1-again.jsonld || fail "JSON-LD differs between two runs"

# Figure 12: the labels come from the example query; which texture holds which shapes
# comes from the report and the ground truth.
"$geotex" query "$q/texture-labels.rq" s1.ttl --format csv >labels.csv || fail "texture-labels.rq"
/usr/bin/python3 - s1.json sphere-1.truth.json labels.csv <<'PY' || fail "Figure 12 outcome (see above)"
import collections, csv, json, sys
report, truth, labels = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), list(csv.DictReader(open(sys.argv[3])))
kinds = [s["kind"] for s in truth["shapes"]]
face_shape = truth["face_shape"]
texture_kinds = collections.defaultdict(collections.Counter)
for t in report["texels"]:
    shape = collections.Counter(face_shape[f] for f in t["faces"] if face_shape[f] >= 0).most_common(1)[0][0]
    texture_kinds[t["texture"]][kinds[shape]] += 1
by_texture = {row["texture"].rstrip(">").rsplit("/", 1)[1]: row["labels"] for row in labels}
expected = {"big_disc": "circular shape", "small_disc": "circular shape", "rectangle": "one dominant axis",
            "square": "close to circular shape"}
ok = True
for texture, counter in sorted(texture_kinds.items()):
    kind = counter.most_common(1)[0][0]
    names = [x.strip() for x in by_texture.get(str(texture), "").split(",")]
    good = expected[kind] in names
    ok = ok and good
    print(f"texture {texture}: {dict(counter)} -> {names} {'ok' if good else 'MISSING ' + expected[kind]}")
sys.exit(0 if ok and len(texture_kinds) == 4 else 1)
PY

# The other documented queries run and answer.
for query in texels-per-texture features-by-significance textures-with-concept; do
  "$geotex" query "$q/$query.rq" s1.ttl --format csv >"$query.csv" || fail "$query.rq"
  [ "$(wc -l <"$query.csv")" -gt 1 ] || fail "$query.rq: no rows"
done
"$geotex" query "$q/texture-labels.rq" s1.ttl --format json | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["results"]["bindings"]' \
  || fail "JSON results"

# Honest assertions (issue 15), read back by rdflib from the Turtle alone: an annotation of a
# texture targets that texture, never its texels; every body of a texel's annotation holds
# for the texel's own value (the SHACL rule of the concept's interval in the dictionary
# version the run used: its shortcut property and bounds) and its relief allows the texel's
# orientation.
/usr/bin/python3 - s1.ttl <<'PY' || fail "honest assertions (see above)"
import sys, rdflib
from rdflib.namespace import RDF
OA, SH = rdflib.Namespace("http://www.w3.org/ns/oa#"), rdflib.Namespace("http://www.w3.org/ns/shacl#")
GTX, PROV = rdflib.Namespace("https://w3id.org/geotex/ns#"), rdflib.Namespace("http://www.w3.org/ns/prov#")
g = rdflib.Graph(); g.parse(sys.argv[1], format="turtle")
texels = set(g.subjects(RDF.type, GTX.Texel))
bad, bodies, texel_annotations = [], 0, 0
for a, target in g.subject_objects(OA.hasTarget):
    described = set(g.objects(a, GTX.describes))
    if target in texels:
        if described or (a, RDF.type, GTX.TexelAnnotation) not in g:
            bad.append(f"{a} asserts texture concepts of the texel {target}")
        texel_annotations += 1
        run = g.value(a, PROV.wasGeneratedBy)
        versions = [v for v in g.objects(run, PROV.used) if (v, RDF.type, GTX.DictionaryVersion) in g]
        if len(versions) != 1:
            bad.append(f"{run} used {len(versions)} dictionary versions")
            continue
        for body in g.objects(a, OA.hasBody):
            bodies += 1
            intervals = [i for i in g.objects(body, GTX.hasInterval) if (i, GTX.inVersion, versions[0]) in g]
            if len(intervals) != 1 or g.value(intervals[0], GTX.ofConcept) != body:
                bad.append(f"{body}: {len(intervals)} intervals in {versions[0]}")
                continue
            rule = g.value(intervals[0], GTX.rule)
            value = g.value(target, g.value(rule, SH.path)).toPython()
            lower, upper = g.value(rule, SH.minInclusive), g.value(rule, SH.maxExclusive)
            if (lower is not None and value < lower.toPython()) or (upper is not None and not value < upper.toPython()):
                bad.append(f"{body} of {target}: its value {value} is outside [{lower}, {upper})")
            relief = g.value(intervals[0], GTX.appliesTo)
            if relief is not None and relief != g.value(target, GTX.orientation):
                bad.append(f"{body} of {target}: a concept of the other relief")
    elif described != {target}:
        bad.append(f"{a} targets {target} but describes {described}")
print(f"honest: {texel_annotations} texel annotations, {bodies} bodies checked, {len(bad)} problems")
for b in bad[:10]: print("  " + b)
sys.exit(1 if bad or bodies == 0 else 0)
PY

# Independent parsers and SHACL.
"$src/tests/rdf_peer_check.sh" s1.ttl "$src/ontology/shapes.ttl" >peer.txt 2>&1 || { cat peer.txt; fail "peer check of s1.ttl"; }
"$geotex" annotate sphere-1.ply --scale 0.04 -o s1.nt --format ntriples --quiet >/dev/null || fail "N-Triples"
[ "$(rapper -q -i ntriples -c s1.nt 2>&1 | grep -o '[0-9]*' | tail -1)" = "$(rapper -q -i turtle -c s1.ttl 2>&1 | grep -o '[0-9]*' | tail -1)" ] \
  || fail "N-Triples and Turtle differ in triple count"
"$geotex" annotate sphere-1.ply --scale 0.04 -o s1.rdf --format rdfxml --quiet >/dev/null || fail "RDF/XML"
rapper -q -i rdfxml -c s1.rdf >/dev/null 2>&1 || fail "RDF/XML does not parse"

# JSON-LD: read back by the jsonld package (offline, the W3C context from a fixture) and
# compared with the Turtle of the same run by N3.js (tests/js/jsonld_roundtrip.mjs).
jsonld_check() {
  node "$src/tests/js/jsonld_roundtrip.mjs" "$1" "$2" >jsonld-check.txt 2>&1 || { cat jsonld-check.txt; fail "JSON-LD round trip of $1"; }
}
[ -d "$src/tests/js/node_modules/jsonld" ] || fail "npm package jsonld missing: run  npm ci --prefix $src/tests/js"
jsonld_check s1.jsonld s1.ttl
"$geotex" annotate sphere-1.ply --scale 0.04 -o same.ttl --jsonld same.ttl --quiet >/dev/null 2>err.txt
[ $? -eq 1 ] && grep -q -- "--jsonld" err.txt || fail "--jsonld naming the --output file should be a usage error: $(cat err.txt)"

# --- several objects ----------------------------------------------------------------------
"$geotex" synth -o other.ply --level 6 --layout-seed 7 --squares 0 --rectangles 0 --quiet >/dev/null
"$geotex" annotate other.ply --scale 0.04 --base 'https://collection.example.org/object/7/model/' -o other.ttl \
  --jsonld other.jsonld --quiet >/dev/null || fail "annotate with --base"
jsonld_check other.jsonld other.ttl
# Both objects have circular discs, and both are called so: a texture's words do not depend on
# the object's other details (sphere-1 also has squares and rectangles, `other` only discs).
# Only sphere-1 has rectangles, so only it carries "one dominant axis" (the query edited).
"$geotex" query "$q/objects-with-concept.rq" s1.ttl other.ttl --format csv >objects.csv || fail "objects-with-concept.rq"
[ "$(tail -n +2 objects.csv | cut -d, -f1 | tr '\n' ' ')" = "other.ply sphere-1.ply " ] || fail "objects-with-concept: $(cat objects.csv)"
sed 's/("circular-shape")/("one-dominant-axis")/' "$q/objects-with-concept.rq" >one-axis.rq
"$geotex" query one-axis.rq s1.ttl other.ttl --format csv >objects2.csv || fail "objects-with-concept, edited"
[ "$(tail -n +2 objects2.csv | cut -d, -f1 | tr '\n' ' ')" = "sphere-1.ply " ] || fail "objects-with-concept, edited: $(cat objects2.csv)"

# --- hostile names and IRIs ---------------------------------------------------------------
"$geotex" synth -o small.ply --level 5 --quiet >/dev/null
weird='a "quoted" > name\with é 漢 & <tags>.ply'
cp small.ply "$weird"
"$geotex" annotate "$weird" --scale 0.05 -o weird.ttl --quiet >/dev/null || fail "annotate a strange file name"
"$src/tests/rdf_peer_check.sh" weird.ttl "$src/ontology/shapes.ttl" >peer2.txt 2>&1 || { cat peer2.txt; fail "peer check of weird.ttl"; }
/usr/bin/python3 - weird.ttl "$weird" <<'PY' || fail "file name did not round-trip"
import sys, rdflib
g = rdflib.Graph(); g.parse(sys.argv[1], format="turtle")
names = {str(o) for o in g.objects(None, rdflib.URIRef("http://purl.org/dc/terms/identifier"))}
sys.exit(0 if sys.argv[2] in names else 1)
PY
# Hostile labels through the JSON-LD: every label is compared with the Turtle's.
/usr/bin/python3 - "$src/dictionaries/default.yaml" hostile.yaml <<'PY' || fail "hostile dictionary"
import re, sys
text = open(sys.argv[1], encoding="utf-8").read()
# YAML double quotes: \" is a quote, \\ a backslash; then a line separator, a CJK character
text, n = re.subn(r'labels: \{en: ([^,]*),',
                  lambda m: 'labels: {en: "%s \\"q\\" \\\\ </script> \u2028 \u6f22 @id",' % m.group(1), text)
open(sys.argv[2], "w", encoding="utf-8").write(text)
sys.exit(0 if n > 10 else 1)
PY
"$geotex" annotate small.ply --scale 0.05 --dictionary hostile.yaml -o hostile.ttl --jsonld hostile.jsonld --quiet >/dev/null \
  || fail "annotate with hostile labels"
jsonld_check hostile.jsonld hostile.ttl
/usr/bin/python3 - hostile.jsonld <<'PY' || fail "hostile labels did not reach the JSON-LD bodies"
import json, sys
labels = [b["prefLabel"]["en"] for a in json.load(open(sys.argv[1], encoding="utf-8"))["items"] for b in a.get("body", [])]
sys.exit(0 if labels and all(l.endswith(' "q" \\ </script> \u2028 \u6f22 @id') for l in labels) else 1)
PY
for bad in 'https://example.org/a b/' 'https://example.org/x>/' 'no-scheme/' 'https://example.org/no-end'; do
  "$geotex" annotate small.ply --scale 0.05 --base "$bad" -o bad.ttl --quiet >/dev/null 2>err.txt
  [ $? -eq 1 ] || fail "--base '$bad' should be a usage error"
  [ -e bad.ttl ] && fail "--base '$bad' left a file"
  grep -q "^geotex: error: " err.txt || fail "--base '$bad': $(cat err.txt)"
done
# A base whose scheme is a term of the JSON-LD context ('oa:x' reads as a compact IRI there)
# is refused when writing the JSON-LD, and then no output is left.
"$geotex" annotate small.ply --scale 0.05 --base 'oa:objects/1/' -o oa.ttl --jsonld oa.jsonld --quiet >/dev/null 2>err.txt
[ $? -eq 4 ] && [ ! -e oa.ttl ] && [ ! -e oa.jsonld ] && grep -q "compact IRI" err.txt || fail "--base oa:...: $(cat err.txt)"

# --- dictionaries -------------------------------------------------------------------------
"$geotex" dict check "$src/dictionaries/default.yaml" >/dev/null || fail "default.yaml is not clean"
"$geotex" dict skos "$src/dictionaries/default.yaml" -o scheme.ttl --quiet || fail "dict skos"
"$src/tests/rdf_peer_check.sh" scheme.ttl "$src/ontology/shapes.ttl" >peer3.txt 2>&1 || { cat peer3.txt; fail "peer check of scheme.ttl"; }
cat > broken.yaml <<'YAML'
scheme:
  id: broken
  version: "1"
  namespace: https://example.org/dict/broken#
  titles: {en: Broken}
  languages: [en]
features:
  contour_sphericity:
    - id: a
      interval: [0, 0.1]
      labels: {en: first}
    - id: b
      interval: [0.05, 0.2]
      lables: {en: second}
  no_such_feature:
    - id: a
      interval: [1, 0]
      labels: {en: third}
YAML
"$geotex" dict check broken.yaml >out.txt 2>err.txt
[ $? -eq 2 ] || fail "dict check of a broken dictionary should exit 2"
[ "$(grep -c '^broken.yaml:[0-9]*:[0-9]*: ' err.txt)" -ge 4 ] || fail "dict check should list every problem: $(cat err.txt)"
"$geotex" annotate small.ply --scale 0.05 --dictionary broken.yaml -o x.ttl --quiet >/dev/null 2>err.txt
[ $? -eq 2 ] && [ ! -e x.ttl ] && grep -q "^geotex: error: broken.yaml:[0-9]*:[0-9]*: " err.txt || fail "annotate with a broken dictionary: $(cat err.txt)"

finish annotate
