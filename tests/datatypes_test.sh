#!/usr/bin/env bash
# The lexical spaces of geotex's own datatypes (gtx:faceRanges, gtx:point3) checked by an XML
# Schema validator (xmllint): the xsd:pattern facets of ontology/geotex.ttl, read with rdflib,
# become an XML Schema; known good and bad lexical forms, and every such literal of a real
# run, are validated against it. XML Schema patterns are anchored by definition and know no
# ^ or $: a pattern written with them matches nothing, which this test would show.
#   tests/datatypes_test.sh GEOTEX SOURCE_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
command -v xmllint >/dev/null || { echo "FAIL: xmllint missing (Debian package libxml2-utils)"; exit 1; }

"$geotex" synth -o small.ply --level 5 --quiet >/dev/null || { echo "FAIL: synth"; exit 1; }
"$geotex" annotate small.ply --scale 0.05 -o small.ttl --quiet >/dev/null || { echo "FAIL: annotate"; exit 1; }

/usr/bin/python3 - "$src/ontology/geotex.ttl" small.ttl <<'PY'
import html, subprocess, sys
import rdflib
from rdflib.namespace import OWL, RDF, XSD
from rdflib.collection import Collection

GTX = rdflib.Namespace("https://w3id.org/geotex/ns#")
vocab = rdflib.Graph().parse(sys.argv[1], format="turtle")
run = rdflib.Graph().parse(sys.argv[2], format="turtle")
failures = []

def pattern_of(datatype):
    """The xsd:pattern of the restriction that owl:equivalentClass gives `datatype`."""
    for restricted in vocab.objects(datatype, OWL.equivalentClass):
        for facets in vocab.objects(restricted, OWL.withRestrictions):
            for facet in Collection(vocab, facets):
                for p in vocab.objects(facet, XSD.pattern):
                    return str(p)
    raise SystemExit("FAIL: no xsd:pattern for %s in geotex.ttl" % datatype)

def valid(pattern, text):
    """Whether xmllint accepts `text` against an XML Schema string restricted by `pattern`."""
    with open("t.xsd", "w") as f:
        f.write('<xs:schema xmlns:xs="http://www.w3.org/2001/XMLSchema">'
                '<xs:element name="v"><xs:simpleType><xs:restriction base="xs:string">'
                '<xs:pattern value="%s"/></xs:restriction></xs:simpleType></xs:element></xs:schema>'
                % html.escape(pattern, quote=True))
    with open("v.xml", "w") as f:
        f.write("<v>%s</v>" % html.escape(text, quote=False))
    return subprocess.run(["xmllint", "--noout", "--schema", "t.xsd", "v.xml"],
                          capture_output=True).returncode == 0

cases = {
    GTX.faceRanges: (["0", "7", "812-840 902", "0-3 5 9-12 100"],
                     ["", " 3", "3 ", "01", "3--5", "3-", "a", "1,2", "3  5", "-3"]),
    GTX.point3: (["1.25E-1 -3.0E-2 4.4E-1", "0 0 0", "1. .5 -2e3", "+1 -1 1E+2"],
                 ["", "1 2", "1 2 3 4", "1,2,3", "1  2 3", "NaN 0 0", "1 2 3 ", "e1 2 3"]),
}
for datatype, (good, bad) in cases.items():
    pattern = pattern_of(datatype)
    for text in good:
        if not valid(pattern, text):
            failures.append("%s: '%s' refused" % (datatype, text))
    for text in bad:
        if valid(pattern, text):
            failures.append("%s: '%s' accepted" % (datatype, text))
    # every literal of this datatype in a real run
    seen = 0
    for o in run.objects():
        if isinstance(o, rdflib.Literal) and o.datatype == datatype:
            seen += 1
            if not valid(pattern, str(o)):
                failures.append("%s: the run's '%s' refused" % (datatype, o))
    if seen == 0:
        failures.append("%s: no literal of it in the run" % datatype)
    print("%s: %d good, %d bad forms and %d literals of a run checked" % (datatype, len(good), len(bad), seen))
for f in failures:
    print("FAIL: " + f)
sys.exit(1 if failures else 0)
PY
