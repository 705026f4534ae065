#!/usr/bin/env bash
# Several levels at once (issue 20, docs/scales.md "Several levels"): the paper's two-level
# sphere (8 bumps carrying 48 strokes, 8 of them on a bump's top; its generator writes one
# ground truth per level) in one run of `--scale auto --levels`. The strokes are the fine
# level, the bumps the coarse one, and the strokes linked to a bump are those the ground truth
# puts on it; in the report, the PLY and the RDF (SPARQL over it, SHACL against shapes.ttl).
#   tests/levels_test.sh GEOTEX SOURCE_DIR GEOTEX_TWO_LEVEL
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
two_level=$(realpath "$3")
PY=/usr/bin/python3

"$two_level" 7 smooth tl.ply strokes.json bumps.json >/dev/null || fail "two-level sphere"
"$geotex" segment tl.ply --scale auto --levels --ascii -o seg.ply --json seg.json -q -j 2 \
  >seg.out || fail "segment --scale auto --levels"
"$geotex" annotate tl.ply --scale auto --levels -o tl.ttl --json ann.json -q -j 2 >ann.out ||
  fail "annotate --scale auto --levels"
grep -q '^level 0, scale 1.66% (main):$' ann.out && grep -q '^level 1, scale 5.84%:$' ann.out ||
  { cat ann.out; fail "annotate --levels: no line per level on stdout"; }
"$geotex" scales tl.ply -q >scales.out || fail "scales of the two-level sphere"
grep -q '^levels: 1.66%, 5.84% (--scale auto --levels' scales.out ||
  { cat scales.out; fail "scales: no hint of the two levels"; }

"$PY" - <<'PYEOF' || fail "the levels against the ground truth (see above)"
import json
from collections import Counter
strokes, bumps = json.load(open('strokes.json')), json.load(open('bumps.json'))
seg = json.load(open('seg.json'))
levels = seg['levels']
assert [l['level'] for l in levels] == [0, 1], levels
fine, coarse = levels
assert fine['main'] and not coarse['main'], (fine['main'], coarse['main'])
assert fine['scale'] == seg['parameters']['scale'] < coarse['scale'], (fine['scale'], coarse['scale'])
assert fine['texel_count'] == len(seg['texels']) == 48, fine['texel_count']
assert coarse['texel_count'] == len(coarse['texels']) == 8, coarse['texel_count']
# Each texel's shape in its level's ground truth: the shape holding most of its faces.
def shape_of(faces, face_shape):
    shape, n = Counter(face_shape[f] for f in faces).most_common(1)[0]
    assert shape >= 0 and n > len(faces) / 2, (shape, n, len(faces))
    return shape
stroke_of = [shape_of(t['faces'], strokes['face_shape']) for t in seg['texels']]
bump_of = [shape_of(t['faces'], bumps['face_shape']) for t in coarse['texels']]
assert sorted(stroke_of) == list(range(48)) and sorted(bump_of) == list(range(8))
# The ground truth's links: a stroke lies on a bump when most of its faces are the bump's.
size = Counter(s for s in strokes['face_shape'] if s >= 0)
shared = Counter((s, b) for s, b in zip(strokes['face_shape'], bumps['face_shape']) if s >= 0 and b >= 0)
truth = {s: b for (s, b), n in shared.items() if n > size[s] / 2}
assert len(truth) == 8, truth
found = {stroke_of[i]: bump_of[c] for i, c in enumerate(fine['part_of']) if c is not None}
assert found == truth, (found, truth)
assert coarse['part_of'] == [None] * 8   # the coarsest level lies on nothing
# The annotation report has the same levels, and words for the bumps' textures.
ann = json.load(open('ann.json'))
assert [l['part_of'] for l in ann['levels']] == [l['part_of'] for l in levels]
words = ann['levels'][1]['annotation']
assert len(words) == coarse['texture_count'] and all(t['concepts'] for t in words), words
PYEOF

# The PLY: one more face property per level, the same texels as the report.
"$PY" - <<'PYEOF' || fail "the levels in the segmentation PLY (see above)"
import json
seg = json.load(open('seg.json'))
with open('seg.ply') as f:
    header = []
    for line in f:
        header.append(line.strip())
        if line.startswith('end_header'):
            break
    props = [h.split()[-1] for h in header[header.index(next(h for h in header if h.startswith('element face'))):] if h.startswith('property')]
    assert props[-2:] == ['level_0_texel', 'level_1_texel'], props
    nv = int(next(h for h in header if h.startswith('element vertex')).split()[-1])
    for _ in range(nv):
        next(f)
    rows = [list(map(int, line.split())) for line in f]
texel = {(0, f): t['id'] for t in seg['texels'] for f in t['faces']}
texel.update({(1, f): t['id'] for t in seg['levels'][1]['texels'] for f in t['faces']})
for face, row in enumerate(rows):
    assert row[4] == row[-2] == texel.get((0, face), -1), (face, row)
    assert row[-1] == texel.get((1, face), -1), (face, row)
PYEOF

# The RDF: which strokes lie on which bump, asked in SPARQL; the labels of both levels.
"$PY" - <<'PYEOF' || fail "the levels in the RDF (see above)"
import json, rdflib
g = rdflib.Graph(); g.parse('tl.ttl', format='turtle')
ann = json.load(open('ann.json'))
rows = list(g.query('''
PREFIX gtx: <https://w3id.org/geotex/ns#>
SELECT ?stroke ?bump ?label WHERE {
  ?stroke gtx:partOf ?bump ; gtx:atLevel [ gtx:levelIndex 0 ; gtx:mainLevel true ] .
  ?bump gtx:atLevel [ gtx:levelIndex 1 ; gtx:levelScale ?s ] ; gtx:inTexture ?t .
  ?t rdfs:label ?label .
}'''))
assert len(rows) == 8, rows
assert len({r.bump for r in rows}) == 8, rows
# Each link is the report's: stroke i (the run's texel/i) on bump j (level/1/texel/j).
expected = {(i, c) for i, c in enumerate(ann['levels'][0]['part_of']) if c is not None}
got = {(int(str(r.stroke).rsplit('/', 1)[1]), int(str(r.bump).rsplit('/', 1)[1])) for r in rows}
assert got == expected, (got, expected)
assert all('/level/1/texel/' in str(r.bump) or '#level/1/texel/' in str(r.bump) for r in rows)
levels = list(g.query('''
PREFIX gtx: <https://w3id.org/geotex/ns#>
SELECT ?level ?count WHERE { ?level a gtx:DetailLevel ; gtx:levelTexelCount ?count ;
  gtx:levelCandidate ?c . ?c gtx:texelsFound ?count } ORDER BY ?count'''))
assert [int(r[1]) for r in levels] == [8, 48], levels
PYEOF
# The documented query of ontology/queries/ gives the same 8 links with geotex's own engine.
"$geotex" query "$src/ontology/queries/texels-on-coarser.rq" tl.ttl --format csv >on.csv 2>on.err ||
  { cat on.err; fail "texels-on-coarser.rq"; }
[ "$(tail -n +2 on.csv | wc -l)" = 8 ] || { cat on.csv; fail "texels-on-coarser.rq: not 8 rows"; }
grep -q '#level/1/texel/' on.csv || fail "texels-on-coarser.rq: no coarse texel of level 1"
node "$src/tests/js/validate.mjs" tl.ttl "$src/ontology/shapes.ttl" >tl.shacl 2>&1 ||
  { fail "tl.ttl does not conform to shapes.ttl"; head -20 tl.shacl; }

# --levels needs the series of --scale auto.
expect_error 1 "levels needs --scale auto" "$geotex" segment tl.ply --scale 0.04 --levels -o x.ply
expect_error 1 "levels needs --scale auto" "$geotex" annotate tl.ply --radius 0.1 --levels -o x.ttl
[ ! -e x.ply ] && [ ! -e x.ttl ] || fail "a refused run wrote an output"
finish levels
