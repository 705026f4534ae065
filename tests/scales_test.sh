#!/usr/bin/env bash
# geotex scales (issue 20, docs/scales.md) as a user runs it: a sphere with known shapes gives
# a plateau whose best scale finds them all; a sphere without detail has no stable scale and
# exits 0; the JSON and the SVG plot are well formed; scales too fine for the sampling are
# skipped with a note; bad options and files are one-line errors with their exit codes.
#   tests/scales_test.sh GEOTEX
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
G=$geotex
PY=/usr/bin/python3

# 20 well separated shapes on a 81,920-face sphere.
"$G" synth -q --level 6 --big-discs 6 --small-discs 6 --squares 4 --rectangles 4 -o shapes.ply >/dev/null
"$G" scales shapes.ply --from 0.01 --to 0.12 --steps 5 --json shapes.json --plot shapes.svg \
  >shapes.out 2>shapes.err
grep -q 'scales 1% to 1.86% skipped: r is below 3 mean edge lengths' shapes.err || { cat shapes.err >&2; fail "no note for a skipped scale"; }
grep -q '^best: --scale ' shapes.out || { cat shapes.out >&2; fail "no best scale printed"; }
"$PY" - <<'PYEOF' || fail "shapes.json"
import json
j = json.load(open('shapes.json'))
truth = json.load(open('shapes.truth.json'))
shapes = len(truth['shapes'])
assert shapes == 20, shapes
scales = j['scales']
assert len(scales) == 5 and scales[0]['scale'] == 0.01 and scales[-1]['scale'] == 0.12, scales
assert scales[0]['skipped'] is True            # 1% is below 3 mean edge lengths here
best = [s for s in scales if s['scale'] == j['best']]
assert len(best) == 1 and best[0]['stable'], j['best']
# At the best scale every shape is one texel, and every one persists.
assert best[0]['texels'] == shapes and best[0]['persistent'] == shapes, best[0]
assert j['plateaus'] and any(p['recommended'] == j['best'] for p in j['plateaus'])
PYEOF
"$PY" - <<'PYEOF' || fail "shapes.svg"
import json, xml.etree.ElementTree as ET
computed = [s for s in json.load(open('shapes.json'))['scales'] if not s['skipped']]
root = ET.parse('shapes.svg').getroot()
ns = '{http://www.w3.org/2000/svg}'
assert root.tag == ns + 'svg'
lines = {p.get('class'): p.get('points') for p in root.iter(ns + 'polyline')}
assert set(lines) == {'texels', 'persistent', 'stability'}, lines.keys()
assert len(lines['texels'].split()) == len(computed) >= 2, lines['texels']
assert any(l.get('class') == 'best' for l in root.iter(ns + 'line'))
assert any(r.get('class') == 'plateau' for r in root.iter(ns + 'rect'))
PYEOF

# A perfect sphere: no detail at any scale, "no stable scale", exit 0, best null.
"$G" synth -q --level 5 --big-discs 0 --small-discs 0 --squares 0 --rectangles 0 -o plain.ply >/dev/null
"$G" scales plain.ply --from 0.06 --steps 3 --json plain.json -q >plain.out || fail "plain sphere: non-zero exit"
grep -q '^no stable scale$' plain.out || { cat plain.out >&2; fail "plain sphere: no 'no stable scale'"; }
"$PY" -c "import json; j = json.load(open('plain.json')); assert j['best'] is None and j['plateaus'] == [], j" \
  || fail "plain.json"

# --scale auto takes the best scale of the same series, and the report says so.
"$G" segment shapes.ply --scale auto -o auto.ply --json auto.json 2>auto.err >/dev/null \
  || { cat auto.err >&2; fail "segment --scale auto"; }
grep -q 'the best stable scale' auto.err || { cat auto.err >&2; fail "--scale auto: no word on its choice"; }
"$G" scales shapes.ply --json default.json -q >/dev/null
"$PY" - <<'PYEOF' || fail "auto.json"
import json
r, series = json.load(open('auto.json')), json.load(open('default.json'))
assert r['parameters']['scale'] == series['best'] == r['scale_choice']['chosen'], (r['parameters'], series['best'])
assert r['scale_choice']['stable'] is True
assert r['scale_choice']['scales'] == series['scales']
assert len(r['texels']) == 20, len(r['texels'])
PYEOF
# A batch with --scale auto --levels: the levels in each object's report and RDF; a rerun with
# the same options finds the object up to date, one without --levels runs it again.
mkdir -p coll && cp shapes.ply coll/
"$G" batch coll -o coll-out --scale auto --levels --jobs 1 -q >/dev/null 2>batch.err || { cat batch.err >&2; fail "batch --scale auto --levels"; }
"$PY" - <<'PYEOF' || fail "batch --levels: the object's report and RDF (see above)"
import glob, json
report = json.load(open(glob.glob('coll-out/objects/*/report.json')[0]))
assert report['levels'] and sum(l['main'] for l in report['levels']) == 1, report.get('levels')
ttl = open(glob.glob('coll-out/objects/*/annotation.ttl')[0]).read()
assert 'gtx:DetailLevel' in ttl and 'gtx:detailLevels true' in ttl
PYEOF
"$G" batch coll -o coll-out --scale auto --levels --jobs 1 >again.out 2>again.err || fail "batch rerun"
grep -q 'up to date' again.out again.err || { cat again.out again.err >&2; fail "batch --levels rerun: the object is not up to date"; }
"$G" batch coll -o coll-out --scale auto --jobs 1 >nolevels.out 2>nolevels.err || fail "batch without --levels"
"$PY" -c "import glob, json; r = json.load(open(glob.glob('coll-out/objects/*/report.json')[0])); assert 'levels' not in r" \
  || fail "batch without --levels kept the levels of the run before"

# No detail anywhere: no stable scale, 0 texels, exit 0.
"$G" segment plain.ply --scale auto -o plain-auto.ply --json plain-auto.json 2>plain-auto.err >/dev/null \
  || { cat plain-auto.err >&2; fail "segment --scale auto on a plain sphere: non-zero exit"; }
grep -q 'no stable scale' plain-auto.err || { cat plain-auto.err >&2; fail "plain sphere: no 'no stable scale'"; }
"$PY" -c "import json; r = json.load(open('plain-auto.json')); assert r['texels'] == [] and r['scale_choice']['stable'] is False" \
  || fail "plain-auto.json"
expect_error 1 'exactly one of --scale' "$G" segment plain.ply --scale auto --radius 0.1 -o x.ply
expect_error 1 "'automatic' is neither a number nor auto" "$G" segment plain.ply --scale automatic -o x.ply
expect_error 1 "'0.04x' is neither a number nor auto" "$G" annotate plain.ply --scale 0.04x -o x.ttl
expect_error 1 "not a finite number: 'nan'" "$G" segment plain.ply --scale nan -o x.ply

# A mesh too coarse for every scale of the series: an input error for --scale auto.
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > tri.ply
expect_error 2 'tri.ply: every scale of the series is below 3 mean edge lengths' "$G" segment tri.ply --scale auto -o tri-seg.ply
[ ! -e tri-seg.ply ] || fail "a refused --scale auto wrote tri-seg.ply"

# Bad options and files.
expect_error 1 'steps' "$G" scales plain.ply --steps 1
expect_error 1 'need 0 < --from < --to < 1' "$G" scales plain.ply --from 0.2 --to 0.1
expect_error 1 'scale' "$G" scales plain.ply --scale 0.1
expect_error 2 'missing.ply' "$G" scales missing.ply
expect_error 1 'plain.ply' "$G" scales plain.ply --json plain.ply
expect_error 1 'plain.ply' "$G" scales plain.ply --plot plain.ply
expect_error 1 'plot.svg' "$G" scales plain.ply --json plot.svg --plot plot.svg
printf 'ply\nformat ascii 1.0\nelement vertex 3\n' > cut.ply
expect_error 2 'cut.ply' "$G" scales cut.ply
[ ! -e never.json ] || fail "a failed run left never.json"
expect_error 2 'cut.ply' "$G" scales cut.ply --json never.json
[ ! -e never.json ] || fail "a failed run wrote never.json"
finish scales
