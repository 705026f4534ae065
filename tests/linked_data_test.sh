#!/usr/bin/env bash
# Linked data a museum can merge (ontology/README.md: "IRIs", "The bridge", "Units"): runs of
# one mesh at two scales, with two dictionary versions, and with a base, merged into one
# graph, conform to ontology/shapes.ttl with an independent SHACL validator; the mesh
# represents the museum's object and one query spans the museum's record and geotex's output;
# lengths in the mesh unit agree with the unit-side values; the options are checked.
#   tests/linked_data_test.sh GEOTEX SOURCE_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
js="$src/tests/js"
shapes="$src/ontology/shapes.ttl"
py=/usr/bin/python3

"$geotex" synth --level 5 -o m.ply --quiet >/dev/null || fail synth
annotate() { "$geotex" annotate m.ply --threads 2 --quiet "$@" >/dev/null; }

# --- two runs, two dictionary versions, a base: one graph ---------------------------------
annotate --scale 0.04 -o s4.ttl || fail "annotate at 4%"
annotate --scale 0.06 -o s6.ttl --jsonld s6.jsonld || fail "annotate at 6%"
# A copy of the default dictionary at version 1.1 with one interval narrowed.
"$py" - "$src/dictionaries/default.yaml" d11.yaml <<'PY' || fail "make the 1.1 dictionary"
import re, sys
text = open(sys.argv[1], encoding="utf-8").read()
text, n = re.subn(r'(?m)^(\s*version:\s*)"[^"\n]*"', r'\1"1.1"', text, count=1)
# one interval narrowed: the same concept, another rule
text, m = re.subn(r'interval: \[0\.05, 0\.15\]', 'interval: [0.05, 0.14]', text, count=1)
assert n == 1 and m == 1, (n, m)
open(sys.argv[2], "w", encoding="utf-8").write(text)
PY
annotate --scale 0.04 --dictionary d11.yaml -o d11.ttl || fail "annotate with dictionary 1.1"
annotate --scale 0.04 --base https://museum.example.org/scan/42/ -o based.ttl || fail "annotate with --base"
annotate --scale 0.04 -o s4-again.ttl
cmp -s s4.ttl s4-again.ttl || fail "the same run gives other bytes"

# --scale auto records how the scale was chosen (docs/scales.md): every scale of the series,
# and the chosen one, whose scale is the parameter set's.
annotate --scale auto -o auto.ttl --json auto.json || fail "annotate --scale auto"
"$py" - auto.ttl auto.json <<'PY' || fail "the scale choice of --scale auto (see above)"
import json, sys, rdflib
from rdflib.namespace import RDF
GTX = rdflib.Namespace("https://w3id.org/geotex/ns#")
g = rdflib.Graph(); g.parse(sys.argv[1], format="turtle")
report = json.load(open(sys.argv[2]))
params = list(g.subjects(RDF.type, GTX.ParameterSet))
assert len(params) == 1, params
choice = g.value(params[0], GTX.scaleChoice)
assert choice is not None and (choice, RDF.type, GTX.ScaleChoice) in g
candidates = sorted(g.objects(choice, GTX.candidate), key=lambda c: float(g.value(c, GTX.candidateScale)))
chosen = g.value(choice, GTX.chosenCandidate)
assert chosen in candidates, chosen
scale = float(g.value(params[0], GTX.scale))
assert float(g.value(chosen, GTX.candidateScale)) == scale == report["parameters"]["scale"], scale
assert report["scale_choice"]["chosen"] == scale
series = report["scale_choice"]["scales"]
assert [float(g.value(c, GTX.candidateScale)) for c in candidates] == [s["scale"] for s in series]
for c, s in zip(candidates, series):
    assert g.value(c, GTX.scaleSkipped).toPython() == s["skipped"]
    if not s["skipped"]:
        assert int(g.value(c, GTX.texelsFound)) == s["texels"]
        assert int(g.value(c, GTX.persistentTexels)) == s["persistent"]
assert g.value(choice, GTX.stableScaleFound).toPython() == report["scale_choice"]["stable"]
assert not g.value(chosen, GTX.scaleSkipped).toPython()
PY

# --levels: every stable scale a level, each texel at its level and on the coarser texel it
# lies on (tests/levels_test.sh checks the links against a ground truth).
annotate --scale auto --levels -o levels.ttl --json levels.json || fail "annotate --scale auto --levels"
"$py" - levels.ttl levels.json <<'PY' || fail "the levels of --levels (see above)"
import json, sys, rdflib
from rdflib.namespace import RDF
GTX = rdflib.Namespace("https://w3id.org/geotex/ns#")
g = rdflib.Graph(); g.parse(sys.argv[1], format="turtle")
levels = json.load(open(sys.argv[2]))["levels"]
nodes = sorted(g.subjects(RDF.type, GTX.DetailLevel), key=lambda n: int(g.value(n, GTX.levelIndex)))
assert len(nodes) == len(levels) >= 1, (nodes, levels)
assert [g.value(n, GTX.mainLevel).toPython() for n in nodes] == [l["main"] for l in levels]
for n, l in zip(nodes, levels):
    texels = set(g.subjects(GTX.atLevel, n))
    assert len(texels) == l["texel_count"] == int(g.value(n, GTX.levelTexelCount)), (n, len(texels))
links = sum(c is not None for l in levels for c in l["part_of"])
assert len(list(g.triples((None, GTX.partOf, None)))) == links, links
PY
for f in s4 s6 d11 based auto levels; do
  node "$js/validate.mjs" "$f.ttl" "$shapes" >"$f.shacl" 2>&1 || { fail "$f.ttl does not conform"; head -20 "$f.shacl"; }
done
node "$js/validate.mjs" s4.ttl "$shapes" s6.ttl d11.ttl based.ttl auto.ttl >union.shacl 2>&1 ||
  { fail "the union of four runs does not conform to shapes.ttl"; head -30 union.shacl; }

# Only the mesh (and geotex's release, the dictionary's concepts) are shared between runs.
"$py" - s4.ttl s6.ttl d11.ttl <<'PY' || fail "runs share nodes (see above)"
import sys
import rdflib
G = rdflib.Namespace("https://w3id.org/geotex/ns#")
graphs = [rdflib.Graph().parse(f, format="turtle") for f in sys.argv[1:]]
run_nodes = []
for g in graphs:
    run = next(g.subjects(rdflib.RDF.type, G.TextureAnalysis))
    prefix = str(run)[: -len("run")]
    assert prefix.startswith("ni:///sha-256;") and prefix.endswith("#"), prefix
    run_nodes.append({str(s) for s in g.subjects() if str(s).startswith(prefix)})
    meshes = set(g.subjects(rdflib.RDF.type, G.Mesh))
    assert len(meshes) == 1 and str(next(iter(meshes))).startswith("ni:///sha-256;"), meshes
ok = True
for i in range(len(run_nodes)):
    for j in range(i + 1, len(run_nodes)):
        common = run_nodes[i] & run_nodes[j]
        if common:
            print("runs", i, j, "share", sorted(common)[:3]); ok = False
meshes = [set(g.subjects(rdflib.RDF.type, G.Mesh)) for g in graphs]
if not meshes[0] == meshes[1] == meshes[2]:
    print("the mesh has several IRIs:", meshes); ok = False
sys.exit(0 if ok else 1)
PY

# --- the bridge: the museum's record and geotex's output, one query ------------------------
object=https://museum.example.org/object/1923-45
annotate --scale 0.06 -o bridged.ttl --object "$object" --mesh-unit cm --creator https://museum.example.org/staff/7 \
  || fail "annotate --object"
node "$js/validate.mjs" bridged.ttl "$shapes" >bridged.shacl 2>&1 || { fail "bridged.ttl does not conform"; head -20 bridged.shacl; }
"$geotex" query "$src/ontology/examples/catalogue-concepts.rq" "$src/ontology/examples/linked-art-object.ttl" bridged.ttl \
  --format csv >catalogue.csv || fail "catalogue-concepts.rq"
"$py" - catalogue.csv bridged.ttl <<'PY' || fail "the query across both graphs (see above)"
import csv, sys
import rdflib
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
g = rdflib.Graph().parse(sys.argv[2], format="turtle")
OA = rdflib.Namespace("http://www.w3.org/ns/oa#")
G = rdflib.Namespace("https://w3id.org/geotex/ns#")
expected = {str(c) for a in g.subjects(G.describes, None) for c in g.objects(a, OA.hasBody)}
got = {r["concept"] for r in rows}
print(len(rows), "rows;", sorted(got)[:3])
ok = rows and got == expected and all(r["accession"] == "1923.45" and r["title"] == "Amphora with stamped roundels" for r in rows)
sys.exit(0 if ok else 1)
PY

# --- units: centimetres, read back --------------------------------------------------------
"$py" - bridged.ttl <<'PY' || fail "quantities in the mesh unit (see above)"
import sys
import rdflib
g = rdflib.Graph().parse(sys.argv[1], format="turtle")
G = rdflib.Namespace("https://w3id.org/geotex/ns#")
Q = rdflib.Namespace("http://qudt.org/schema/qudt/")
U = rdflib.Namespace("http://qudt.org/vocab/unit/")
side = 1 / float(next(g.objects(None, G.unitScale)))
power = {G.contour_perimeter: (G.contourPerimeter, 1, U.CentiM), G.area_rel: (G.areaRel, 2, U.CentiM2),
         G.bounding_sphere_radius_rel: (G.boundingSphereRadiusRel, 1, U.CentiM)}
checked = 0
for texel in g.subjects(rdflib.RDF.type, G.Texel):
    quantities = list(g.objects(texel, G.quantity))
    assert len(quantities) == 3, (texel, quantities)
    for q in quantities:
        prop, p, unit = power[next(g.objects(q, G.ofFeature))]
        value = float(next(g.objects(texel, prop)))
        number = float(next(g.objects(q, Q.numericValue)))
        assert abs(number - value * side ** p) <= 1e-12 * abs(number) + 1e-300, (texel, q, number, value)
        assert next(g.objects(q, Q.unit)) == unit
        checked += 1
print(checked, "quantities")
sys.exit(0 if checked > 0 else 1)
PY

# --- JSON-LD: generator, creator, created only with --timestamp ---------------------------
annotate --scale 0.06 -o t.ttl --jsonld t.jsonld --creator https://museum.example.org/staff/7 --timestamp 2026-12-01T10:00:00Z \
  || fail "annotate --timestamp"
"$py" - s6.jsonld t.jsonld <<'PY' || fail "JSON-LD provenance (see above)"
import json, sys
plain, stamped = (json.load(open(f)) for f in sys.argv[1:])
a, b = plain["items"][0], stamped["items"][0]
assert a["generator"]["type"] == "Software" and a["generator"]["id"].startswith("https://w3id.org/geotex/release/"), a["generator"]
assert "creator" not in a and "created" not in a
assert b["creator"] == "https://museum.example.org/staff/7" and b["created"] == "2026-12-01T10:00:00Z", b
assert all("generator" in item for item in stamped["items"])
PY
node "$js/jsonld_roundtrip.mjs" t.jsonld t.ttl >roundtrip.txt 2>&1 || { fail "JSON-LD with provenance does not match the Turtle"; cat roundtrip.txt; }

# --- bad options: usage errors naming the option, no output --------------------------------
bad() {
  local option=$1 value=$2
  rm -f bad.ttl
  "$geotex" annotate m.ply --scale 0.06 -o bad.ttl "$option" "$value" >bad.out 2>bad.err
  local rc=$?
  [ $rc -eq 1 ] || fail "$option '$value': exit $rc, not 1"
  grep -q -- "$option" bad.err || fail "$option '$value': the message does not name the option: $(cat bad.err)"
  [ "$(wc -l <bad.err)" -eq 1 ] || fail "$option '$value': not one line: $(cat bad.err)"
  [ ! -e bad.ttl ] || fail "$option '$value': an output was written"
}
for option in --object --creator; do
  for value in museum/object/42 "https://museum.example.org/a b" 'https://museum.example.org/"x"' \
               'https://museum.example.org/<x>' "https://museum.example.org/a'b>"; do
    bad "$option" "$value"
  done
done
bad --base "https://museum.example.org/no end/"
bad --base "relative/"
for value in km MM inch " mm"; do bad --mesh-unit "$value"; done

# --- batch: a manifest with object and unit columns, and the templates ---------------------
mkdir -p coll
cp m.ply coll/a.ply && "$geotex" synth --level 4 -o coll/b.ply --quiet >/dev/null
printf 'mesh,id,object,mesh_unit\na.ply,a,https://museum.example.org/object/A,mm\nb.ply,b,,\n' >coll/manifest.csv
"$geotex" batch coll/manifest.csv -o out --scale 0.06 --object-template 'https://museum.example.org/object/{id}' \
  --creator https://museum.example.org/staff/7 --mesh-unit in -q >batch.txt 2>&1 || { fail "batch with objects"; cat batch.txt; }
grep -q 'crm:P138_represents <https://museum.example.org/object/A>' out/objects/a/annotation.ttl || fail "manifest object of a"
grep -q 'crm:P138_represents <https://museum.example.org/object/b>' out/objects/b/annotation.ttl || fail "template object of b"
grep -q 'gtx:meshUnit unit:MilliM' out/objects/a/annotation.ttl || fail "manifest unit of a"
grep -q 'gtx:meshUnit unit:IN' out/objects/b/annotation.ttl || fail "--mesh-unit of b"
grep -q 'dcterms:creator <https://museum.example.org/staff/7>' out/objects/b/annotation.ttl || fail "--creator in batch"
printf 'mesh,id,object,mesh_unit\na.ply,a,not an iri,mm\nb.ply,b,,furlong\n' >coll/bad.csv
"$geotex" batch coll/bad.csv -o badout --scale 0.06 -q >badbatch.txt 2>&1
[ $? -eq 3 ] || fail "batch with bad cells: exit not 3"
grep -q "column 'object'" badout/summary.csv || fail "bad object cell not reported: $(cat badout/summary.csv)"
grep -q "column 'mesh_unit'" badout/summary.csv || fail "bad unit cell not reported"
"$geotex" batch coll/manifest.csv -o o2 --object-template 'https://museum.example.org/object/' -q >/dev/null 2>t.err
[ $? -eq 1 ] && grep -q -- "--object-template" t.err || fail "--object-template without {id}: $(cat t.err)"

finish "linked data"
