#!/usr/bin/env bash
# Two versions of a dictionary in one store (issue 16): `geotex dict skos` of default.yaml and
# of a copy with version "2.1" and one interval narrowed, merged as a store would merge them,
# read by three parsers and checked against ontology/shapes.ttl (tests/rdf_peer_check.sh),
# then the SKOS of the union by rdflib; and a label changed under the same concept id, which
# the shapes must refuse (dictionaries/README.md, "Versions").
#   tests/dictionary_versions_test.sh GEOTEX SOURCE_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"

# default.yaml as it is, and 2.1: "small perimeter" narrowed from [0.07, 0.4) to [0.07, 0.3).
cp "$src/dictionaries/default.yaml" v20.yaml
sed -e 's/^  version: "2.0"$/  version: "2.1"/' \
    -e '/- id: small-perimeter$/,/interval:/ s/interval: \[0\.07, 0\.4\]/interval: \[0.07, 0.3\]/' v20.yaml >v21.yaml
[ "$(diff v20.yaml v21.yaml | grep -c '^>')" -eq 2 ] || fail "v21.yaml: default.yaml's version or small-perimeter line has changed"
for v in v20 v21; do
  "$geotex" dict check "$v.yaml" >/dev/null || fail "$v.yaml is not clean"
  "$geotex" dict skos "$v.yaml" -o "$v.nt" --format ntriples --quiet || fail "dict skos $v.yaml"
done
# N-Triples is Turtle: the union is the two files one after the other.
cat v20.nt v21.nt >union.nt
"$src/tests/rdf_peer_check.sh" union.nt "$src/ontology/shapes.ttl" >peer.txt 2>&1 || { cat peer.txt; fail "the union of 2.0 and 2.1 does not conform"; }

# The SKOS of the union, read by rdflib: one concept IRI with an interval per version, each
# with one upper bound; one prefLabel per language for every concept; the facets as top
# concepts, broader than every concept.
/usr/bin/python3 - union.nt <<'PY' || fail "SKOS of the union (see above)"
import collections, sys, rdflib
from rdflib.namespace import RDF, SKOS
GTX = rdflib.Namespace("https://w3id.org/geotex/ns#")
DCTERMS = rdflib.Namespace("http://purl.org/dc/terms/")
N = "https://w3id.org/geotex/dictionary/default/"
g = rdflib.Graph(); g.parse(sys.argv[1], format="nt")
bad = []
scheme = rdflib.URIRef(N + "scheme")
versions = set(g.objects(scheme, DCTERMS.hasVersion))
if versions != {rdflib.URIRef(N + "scheme/version/2.0"), rdflib.URIRef(N + "scheme/version/2.1")}:
    bad.append(f"versions {sorted(versions)}")
concepts = set(g.subjects(GTX.onFeature, None))
if len(concepts) != 75:
    bad.append(f"{len(concepts)} concepts, not 75: the IRIs differ between versions")
small = rdflib.URIRef(N + "small-perimeter")
uppers = {str(g.value(i, GTX.inVersion)).rsplit("/", 1)[1]: [str(u) for u in g.objects(i, GTX.upperBound)]
          for i in g.objects(small, GTX.hasInterval)}
if uppers != {"2.0": ["0.4"], "2.1": ["0.3"]}:
    bad.append(f"small-perimeter upper bounds by version {uppers}")
for c in concepts:
    intervals = set(g.objects(c, GTX.hasInterval))
    if len(intervals) != 2:
        bad.append(f"{c}: {len(intervals)} intervals")
    for i in intervals:
        for p in (GTX.lowerBound, GTX.upperBound, GTX.rule):
            if len(set(g.objects(i, p))) > 1:
                bad.append(f"{i}: several {p}")
labels = collections.Counter((s, o.language) for s, o in g.subject_objects(SKOS.prefLabel))
bad += [f"{s} has {n} prefLabels in {lang}" for (s, lang), n in labels.items() if n > 1]
top = set(g.objects(scheme, SKOS.hasTopConcept))
if len(top) != 7 or any((t, RDF.type, GTX.Facet) not in g for t in top):
    bad.append(f"{len(top)} top concepts, not the 7 facets")
for c in concepts:
    broader = set(g.objects(c, SKOS.broader))
    if len(broader) != 1 or not broader <= top or (next(iter(broader)), SKOS.narrower, c) not in g:
        bad.append(f"{c}: broader {broader}")
print(f"union: {len(concepts)} concepts, {len(versions)} versions, {len(top)} top concepts, {len(bad)} problems")
for b in bad[:10]: print("  " + b)
sys.exit(1 if bad else 0)
PY

# The shapes are not vacuous: each of these breaks of the union is reported.
N=https://w3id.org/geotex/dictionary/default/
S=http://www.w3.org/2004/02/skos/core#
G=https://w3id.org/geotex/ns#
breaks=(
  "a facet that is also a collection|<${N}scheme/facet/size> <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> <${S}Collection> ."
  "a second upper bound in one version|<${N}scheme/version/2.1/small-perimeter> <${G}upperBound> \"0.35\"^^<http://www.w3.org/2001/XMLSchema#decimal> ."
  "a bound on the concept itself|<${N}small-perimeter> <${G}upperBound> \"0.4\"^^<http://www.w3.org/2001/XMLSchema#decimal> ."
  "a second version string on one version node|<${N}scheme/version/2.1> <http://www.w3.org/2002/07/owl#versionInfo> \"2.2\" ."
  "a version string on the scheme|<${N}scheme> <http://www.w3.org/2002/07/owl#versionInfo> \"2.1\" ."
)
for entry in "${breaks[@]}"; do
  what=${entry%%|*}
  { cat union.nt; echo "${entry#*|}"; } >broken.nt
  node "$src/tests/js/validate.mjs" broken.nt "$src/ontology/shapes.ttl" >/dev/null 2>&1
  [ $? -eq 1 ] || fail "the shapes should report $what"
done
grep -v "^<${N}small-perimeter> <${S}broader> " union.nt >broken.nt
node "$src/tests/js/validate.mjs" broken.nt "$src/ontology/shapes.ttl" >/dev/null 2>&1
[ $? -eq 1 ] || fail "the shapes should report a concept without its facet"

# A label changed under the same id: the concept would have two English prefLabels in a
# store holding both versions, which SKOS forbids and the shapes report.
sed 's/labels: {en: small perimeter,/labels: {en: smallish perimeter,/' v21.yaml >v21-label.yaml
cmp -s v21.yaml v21-label.yaml && fail "v21-label.yaml: the small-perimeter label of default.yaml has changed"
"$geotex" dict skos v21-label.yaml -o v21-label.nt --format ntriples --quiet || fail "dict skos v21-label.yaml"
cat v20.nt v21-label.nt >relabelled.nt
if "$src/tests/rdf_peer_check.sh" relabelled.nt "$src/ontology/shapes.ttl" >peer2.txt 2>&1; then
  fail "a label changed under one concept id should break the shapes of the union"
fi
grep -q 'small-perimeter> path <http://www.w3.org/2004/02/skos/core#prefLabel>.*UniqueLang' peer2.txt \
  || { cat peer2.txt; fail "the violation should be the two prefLabels of small-perimeter"; }

# The same version published twice with different bytes (a comment edited): one version node
# with two digests, which the shapes allow; the meaning is the same.
{ cat v20.yaml; echo "# a comment added later"; } >v20-comment.yaml
"$geotex" dict skos v20-comment.yaml -o v20-comment.nt --format ntriples --quiet || fail "dict skos v20-comment.yaml"
cat v20.nt v20-comment.nt >same.nt
"$src/tests/rdf_peer_check.sh" same.nt "$src/ontology/shapes.ttl" >peer3.txt 2>&1 || { cat peer3.txt; fail "one version with two digests should conform"; }

finish "dictionary version"
