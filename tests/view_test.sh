#!/usr/bin/env bash
# geotex view over HTTP with curl (view/README.md): the routes over a small batch output, the
# GTXM mesh checked against the report's face lists, the Host, Origin and token checks, path
# traversal (encoded slashes and dots, a link out of PATH), corrupt objects among good ones,
# a port in use, a PATH that is no batch output, and SIGINT ending the server with exit 0.
# Usage: tests/view_test.sh path/to/geotex path/to/source
set -euo pipefail
G=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
PY=/usr/bin/python3
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }
check() { local what=$1; shift; "$@" || fail "$what"; }
# expect CODE PATTERN cmd...: exit code CODE and one 'geotex: error:' line matching PATTERN
expect() {
  local code=$1 pattern=$2; shift 2
  local rc=0
  "$@" >out.txt 2>err.txt || rc=$?
  [ "$rc" = "$code" ] || { cat err.txt >&2; fail "'$*' exited $rc, expected $code"; }
  [ "$(grep -c '^geotex: error:' err.txt)" = 1 ] || { cat err.txt >&2; fail "'$*': not exactly one error line"; }
  grep -q -- "$pattern" err.txt || { cat err.txt >&2; fail "'$*': error does not say '$pattern'"; }
}

# start NAME ARGS...: runs geotex view in the background; sets PORT, BASE and SERVER (its pid).
start() {
  local name=$1; shift
  "$G" view "$@" >"$name.out" 2>"$name.err" &
  SERVER=$!
  pids+=("$SERVER")
  for _ in $(seq 1 200); do
    if grep -q '^geotex view: http://' "$name.out" 2>/dev/null; then break; fi
    kill -0 "$SERVER" 2>/dev/null || { cat "$name.err" >&2; fail "$name: the server ended at start"; }
    sleep 0.05
  done
  PORT=$(sed -n 's|^geotex view: http://127\.0\.0\.1:\([0-9]*\)/.*|\1|p' "$name.out")
  TOKEN=$(sed -n 's|^geotex view: http://.*?token=\([0-9a-f]*\)$|\1|p' "$name.out")
  [ -n "$PORT" ] || { cat "$name.out" "$name.err" >&2; fail "$name: no URL printed"; }
  BASE=http://127.0.0.1:$PORT
}
# status URL [curl options]: the HTTP status; the body goes to body.txt
status() { local url=$1; shift; curl -s -o body.txt -w '%{http_code}' "$@" "$url"; }
# want CODE URL [curl options]
want() {
  local code=$1 url=$2; shift 2
  local got
  got=$(status "$url" "$@")
  [ "$got" = "$code" ] || { cat body.txt >&2; fail "$url $*: HTTP $got, expected $code"; }
}
# py WHAT: runs the Python check read from stdin, failing with WHAT
py() { "$PY" - || fail "$1"; }

# ---- a batch output of four small objects ------------------------------------------------
mkdir meshes
for i in 1 2 3 4; do
  "$G" synth -q --level 4 --layout-seed "$i" --big-discs 6 --small-discs 0 --squares 6 --rectangles 0 \
    -o "meshes/obj-$i.ply" >/dev/null
done
rm meshes/*.truth.json
cp "$SRC/dictionaries/default.yaml" dict.yaml
"$G" batch meshes -o out --scale 0.1 --dictionary dict.yaml -q \
  --base-template 'https://example.org/object/{id}/' >/dev/null
# obj-2: a report that is no JSON; obj-3: a segmentation that is no PLY; obj-4: a link to a
# copy of its outputs outside PATH, which must never be followed.
printf '{"texels": [' > out/objects/obj-2/report.json
printf 'ply\nformat ascii 1.0\nelement vertex 99\n' > out/objects/obj-3/segmentation.ply
# obj-3's stamp is made to record its broken PLY, so that the server, not the stamp check of
# loading, meets the bad bytes.
"$PY" - out/objects/obj-3 <<'PYEOF'
import hashlib, json, os, sys
d = sys.argv[1]
s = json.load(open(os.path.join(d, 'run.json')))
s['outputs']['segmentation.ply'] = hashlib.sha256(open(os.path.join(d, 'segmentation.ply'), 'rb').read()).hexdigest()
json.dump(s, open(os.path.join(d, 'run.json'), 'w'), indent=2)
PYEOF
mv out/objects/obj-4 outside
ln -s "$work/outside" out/objects/obj-4
echo 'SECRET-OUTSIDE-PATH' > outside/secret.txt
cp dict.yaml dict.before

start main out --port 0 --dictionary dict.yaml

# ---- the routes --------------------------------------------------------------------------
want 200 "$BASE/api/session"
py session <<'PYEOF'
import json
s = json.load(open('body.txt'))
assert s['path'] == 'out', s
assert s['dictionary']['file'] == 'dict.yaml' and s['dictionary']['editable'] is True, s
assert 'depth_mean' in s['features'] and len(s['features']) == len(set(s['features']))
PYEOF
# The meshes made at start: once the preparation ends, obj-1's mesh is held (its PLY is not
# read again: moved away, the mesh still comes), the broken obj-3 and the objects listed with
# an error are not.
for _ in $(seq 1 600); do
  want 200 "$BASE/api/session"
  grep -q '"preparing":false' body.txt && break
  sleep 0.1
done
py "meshes made at start" <<'PYEOF'
import json
s = json.load(open('body.txt'))
assert s['preparing'] is False, s
assert s['meshes_ready'] == ['obj-1'], s['meshes_ready']
PYEOF
mv out/objects/obj-1/segmentation.ply held.ply
want 200 "$BASE/api/objects/obj-1/mesh"
check "a held mesh is a GTXM" sh -c 'head -c 4 body.txt | grep -q GTXM'
want 200 "$BASE/api/objects/obj-1/thumbnail.png"
mv held.ply out/objects/obj-1/segmentation.ply

want 200 "$BASE/api/objects"
py "objects list" <<'PYEOF'
import csv, json
objects = {o['id']: o for o in json.load(open('body.txt'))}
assert sorted(objects) == ['obj-1', 'obj-2', 'obj-3', 'obj-4'], objects.keys()
rows = {r['id']: r for r in csv.DictReader(open('out/summary.csv'))}
o = objects['obj-1']
assert o['error'] is None and o['status'] == 'ok' and o['reannotate'] is True, o
assert o['texels'] == int(rows['obj-1']['texels']) and o['textures'] == int(rows['obj-1']['textures'])
report = json.load(open('out/objects/obj-1/report.json'))
words = sorted({c['concept'] for t in report['annotation']['textures'] for c in t['concepts']})
assert o['concepts'] == words, (o['concepts'], words)
assert 'report.json' in objects['obj-2']['error'], objects['obj-2']
assert objects['obj-4']['error'] and 'link' in objects['obj-4']['error'], objects['obj-4']
assert objects['obj-3']['error'] is None  # its mesh is read when asked for
PYEOF
check "no secret in the list" sh -c '! grep -q SECRET body.txt'

want 200 "$BASE/api/objects/obj-1"
py object <<'PYEOF'
import json
o = json.load(open('body.txt'))
r = json.load(open('out/objects/obj-1/report.json'))
assert o['faces'] == r['mesh']['faces'] and o['vertices'] == r['mesh']['vertices']
assert [t['id'] for t in o['textures']] == [t['id'] for t in r['textures']]
assert [t['colour'] for t in o['textures']] == [t['colour'] for t in r['textures']]
assert len(o['texels']) == len(r['texels'])
for x, y in zip(o['texels'], r['texels']):
    assert x['texture'] == y['texture']
    for k, v in y['features'].items():
        assert x['features'][k] == v, (k, x['features'][k], v)
PYEOF

# The mesh: the faces of each texel in the report carry that texel, the others -1; each texel
# has its texture and depth_mean; no vertex is shared by faces of two texels, and the vertices
# after the file's are copies of them.
want 200 "$BASE/api/objects/obj-1/mesh" -D headers.txt
check "mesh is octet-stream" grep -qi '^Content-Type: application/octet-stream' headers.txt
py "GTXM mesh" <<'PYEOF'
import json, math, struct
b = open('body.txt', 'rb').read()
r = json.load(open('out/objects/obj-1/report.json'))
assert b[:4] == b'GTXM'
version, nv, nf, nt = struct.unpack_from('<IIII', b, 4)
assert version == 2 and nf == r['mesh']['faces'] and nt == len(r['texels']), (version, nf, nt)
assert nv >= r['mesh']['vertices'], (nv, r['mesh']['vertices'])
assert len(b) == 20 + 12 * nv + 16 * nf + 8 * nt, len(b)
o = 20
pos = struct.unpack_from('<%df' % (3 * nv), b, o); o += 12 * nv
idx = struct.unpack_from('<%dI' % (3 * nf), b, o); o += 12 * nf
texel = struct.unpack_from('<%di' % nf, b, o); o += 4 * nf
texture = struct.unpack_from('<%di' % nt, b, o); o += 4 * nt
depth = struct.unpack_from('<%df' % nt, b, o)
assert max(idx) < nv
expected = [-1] * nf
for t in r['texels']:
    for f in t['faces']:
        expected[f] = t['id']
assert list(texel) == expected
assert any(t >= 0 for t in texel)
owner = {}
for f in range(nf):
    for v in idx[3 * f:3 * f + 3]:
        assert owner.setdefault(v, texel[f]) == texel[f], (v, owner[v], texel[f])
for t in r['texels']:
    d = t['features']['depth_mean']
    assert texture[t['id']] == t['texture']
    assert abs(depth[t['id']] - d) <= 1e-6 * max(1, abs(d)), (depth[t['id']], d)
# The file's vertices come first; every later vertex is a copy of one of them.
nv0 = r['mesh']['vertices']
first = {tuple(pos[3 * v:3 * v + 3]) for v in range(nv0)}
assert all(tuple(pos[3 * v:3 * v + 3]) in first for v in range(nv0, nv))
PYEOF
want 200 "$BASE/api/objects/obj-1/thumbnail.png"
py thumbnail <<'PYEOF'
import struct
b = open('body.txt', 'rb').read()
assert b[:8] == b'\x89PNG\r\n\x1a\n' and b[12:16] == b'IHDR'
assert struct.unpack('>II', b[16:24]) == (192, 192)
PYEOF
want 200 "$BASE/api/features"
py features <<'PYEOF'
import json
f = json.load(open('body.txt'))
n = sum(len(json.load(open('out/objects/%s/report.json' % o))['texels']) for o in ('obj-1', 'obj-3'))
assert len(f['depth_mean']['texels']) == n, (len(f['depth_mean']['texels']), n)
PYEOF
want 200 "$BASE/api/dictionary"
py dictionary <<'PYEOF'
import json
d = json.load(open('body.txt'))
assert d['text'] == open('dict.yaml').read() and d['problems'] == [] and len(d['concepts']) > 0
PYEOF

# Assets: three.js byte for byte, never compressed even when the client asks for it.
want 200 "$BASE/assets/three.min.js" -D headers.txt -H 'Accept-Encoding: br, gzip'
check "three.min.js unchanged" cmp -s body.txt /usr/share/javascript/three/three.min.js
check "three.min.js is JavaScript" grep -qi '^Content-Type: text/javascript' headers.txt
check "no compression" sh -c '! grep -qi "^Content-Encoding" headers.txt'
want 200 "$BASE/assets/OrbitControls.js"
check "OrbitControls.js unchanged" cmp -s body.txt /usr/share/javascript/three/examples/js/controls/OrbitControls.js
want 404 "$BASE/assets/nothing.js"
if [ -f "$SRC/view/web/index.html" ]; then
  want 200 "$BASE/" -D headers.txt
  check "index is HTML" grep -qi '^Content-Type: text/html' headers.txt
  check "token filled in" grep -Eq '<meta name="geotex-token" content="[0-9a-f]{32}">' body.txt
else
  want 404 "$BASE/"
fi

# Bad objects: each answers its error, the others work.
want 404 "$BASE/api/objects/obj-2/mesh"
want 422 "$BASE/api/objects/obj-3/mesh"
check "corrupt PLY named" grep -q 'obj-3/segmentation.ply' body.txt
want 422 "$BASE/api/objects/obj-3/thumbnail.png"
want 200 "$BASE/api/objects/obj-2"
check "obj-2 error" grep -q '"error":"[^"]*objects/obj-2/report.json' body.txt
want 404 "$BASE/api/objects/obj-4/mesh"
check "nothing from outside" sh -c '! grep -q -e SECRET -e GTXM body.txt'
want 200 "$BASE/api/objects/obj-4"
check "obj-4 shows its error only" sh -c '! grep -q texels body.txt'
want 200 "$BASE/api/objects/obj-1/mesh"

# ---- the request checks ------------------------------------------------------------------
want 403 "$BASE/api/session" -H "Host: evil.example:$PORT"
want 403 "$BASE/api/session" -H "Host: 127.0.0.1:$((PORT + 1))"
want 200 "$BASE/api/session" -H "Host: localhost:$PORT"
want 200 "$BASE/api/session" -H "Host: [::1]:$PORT"
want 403 "$BASE/api/session" -H 'Origin: http://evil.example'
want 403 "$BASE/api/session" -H 'Origin: null'
want 403 "$BASE/api/objects/obj-1/mesh" -H "Origin: http://localhost:$((PORT + 1))"
want 200 "$BASE/api/session" -H "Origin: http://127.0.0.1:$PORT"
curl -s -D headers.txt -o /dev/null -H "Origin: http://127.0.0.1:$PORT" "$BASE/api/session"
check "no CORS header" sh -c '! grep -qi "^Access-Control" headers.txt'
want 403 "$BASE/api/preview" -X POST -H 'Content-Type: application/json' -d '{"edits": []}'
want 403 "$BASE/api/save" -X POST -H 'X-Geotex-Token: 0123456789abcdef0123456789abcdef' -d '{"edits": []}'
want 403 "$BASE/api/save?token=0123456789abcdef0123456789abcdef" -X POST -d '{"edits": []}'
want 404 "$BASE/nothing"
check "404 in JSON" grep -q '"error"' body.txt

# ---- path traversal ----------------------------------------------------------------------
for path in '/api/objects/..%2F..%2Fetc%2Fpasswd/mesh' '/api/objects/%2e%2e/mesh' \
            '/api/objects/%2E%2E%2F%2E%2E%2Fetc/thumbnail.png' '/api/objects/../../etc/passwd' \
            '/assets/..%2F..%2F..%2Fetc%2Fpasswd' '/api/objects/obj-1%2F..%2F..%2Fsummary.csv' \
            '/api/objects/.%2Fobj-1/mesh' '/assets/%2e%2e%2findex.html' '/api/objects/outside/mesh' \
            '/api/objects/obj-1%00/mesh' '/../../../etc/passwd' '/objects/obj-1/report.json'; do
  code=$(status "$BASE$path" --path-as-is)
  case $code in 400|403|404) ;; *) fail "$path: HTTP $code" ;; esac
  check "$path: nothing leaked" sh -c '! grep -q -e "root:" -e SECRET -e GTXM -e "\"texels\"" body.txt'
done

# ---- start-up errors -----------------------------------------------------------------------
expect 1 "in use" "$G" view out --port "$PORT"
mkdir empty
expect 2 "empty" "$G" view empty --port 0
expect 2 "nothing-here" "$G" view nothing-here --port 0
expect 2 "summary.csv" "$G" view out/objects --port 0
for bad in 70000 -1 nan ''; do
  expect 1 "--port: Value $bad not in range" "$G" view out --port "$bad"
done
expect 1 "--host: an empty address" "$G" view out --host '' --port 0

# ---- SIGINT: a clean stop, exit 0 --------------------------------------------------------
kill -INT "$SERVER"
rc=0; wait "$SERVER" || rc=$?
check "SIGINT exits 0 (got $rc)" test "$rc" = 0
check "nothing on stderr" test ! -s main.err


# ---- dictionary edits: --host prints the token, which every request then needs ---------------
start edit out --port 0 --dictionary dict.yaml --host 127.0.0.1
check "token printed with --host" test "${#TOKEN}" = 32
want 403 "$BASE/api/session"
want 200 "$BASE/api/session?token=$TOKEN"
want 200 "$BASE/api/session" -H "X-Geotex-Token: $TOKEN"
# The page's <script src> cannot send a header: ?token= or the cookie of the first load.
want 403 "$BASE/assets/three.min.js"
want 200 "$BASE/assets/three.min.js?token=$TOKEN"
want 200 "$BASE/assets/three.min.js" -H "Cookie: geotex_token=$TOKEN"
want 403 "$BASE/assets/three.min.js" -H "Cookie: geotex_token=0123456789abcdef0123456789abcdef"
want 403 "$BASE/api/save" -X POST -H "Cookie: geotex_token=$TOKEN" -d '{"edits": []}'
if [ -f "$SRC/view/web/index.html" ]; then
  want 200 "$BASE/?token=$TOKEN" -D headers.txt
  check "cookie set" grep -qi "^Set-Cookie: geotex_token=$TOKEN; Path=/; HttpOnly; SameSite=Strict" headers.txt
  check "the page has the token" grep -q "content=\"$TOKEN\"" body.txt
fi
H=(-H "X-Geotex-Token: $TOKEN" -H 'Content-Type: application/json')
# A bound that is no number: 422 with the place, nothing written.
want 422 "$BASE/api/preview" -X POST "${H[@]}" \
  -d '{"edits": [{"op": "bound", "concept": "intermediate-relief", "side": "upper", "value": "abc"}]}'
py "bad edit has a place" <<'PYEOF'
import json
p = json.load(open('body.txt'))['problems']
assert p and all(x['line'] > 0 and x['column'] > 0 for x in p), p
PYEOF
want 422 "$BASE/api/save" -X POST "${H[@]}" \
  -d '{"edits": [{"op": "bound", "concept": "intermediate-relief", "side": "upper", "value": "abc"}]}'
check "bad save writes nothing" cmp -s dict.yaml dict.before
want 400 "$BASE/api/preview" -X POST "${H[@]}" -d 'not json'
want 400 "$BASE/api/preview" -X POST "${H[@]}" -d '{"edits": [{"op": "move"}]}'
# Moving the bound shared by intermediate-relief and among-strongest-reliefs from 0.8 down to
# 0.31: the textures called intermediate lose that word.
MOVE='{"edits": [{"op": "bound", "concept": "intermediate-relief", "side": "upper", "value": "0.31"}]}'
want 200 "$BASE/api/preview" -X POST "${H[@]}" -d "$MOVE"
py "preview" <<'PYEOF'
import json
p = json.load(open('body.txt'))
c = {x['id']: x for x in p['concepts']}
assert c['intermediate-relief']['upper'] == 0.31 and c['among-strongest-reliefs']['lower'] == 0.31
assert p['changed'], 'no texture changed words'
for ch in p['changed']:
    assert 'intermediate-relief' in ch['before'] and 'intermediate-relief' not in ch['after'], ch
# Every texture that had the word and a depth_mean of 0.31 or more is listed, from the reports.
expected = set()
for o in ('obj-1', 'obj-3'):
    r = json.load(open('out/objects/%s/report.json' % o))
    for t in r['annotation']['textures']:
        words = [w['concept'] for w in t['concepts']]
        v = [f['value'] for f in t['features'] if f['feature'] == 'depth_mean'][0]
        if 'intermediate-relief' in words and v >= 0.31:
            expected.add((o, t['texture']))
assert expected <= {(ch['object'], ch['texture']) for ch in p['changed']}, expected
objs = {o['id']: o for o in p['objects']}
for ch in p['changed']:
    t = [t for t in objs[ch['object']]['textures'] if t['id'] == ch['texture']][0]
    assert [w['id'] for w in t['concepts']] == ch['after'], (t, ch)
PYEOF
check "preview writes nothing" cmp -s dict.yaml dict.before
want 200 "$BASE/api/save" -X POST "${H[@]}" -d "$MOVE"
py "save" <<'PYEOF'
import difflib, hashlib, json
s = json.load(open('body.txt'))
new = open('dict.yaml').read()
assert s['sha256'] == hashlib.sha256(new.encode()).hexdigest(), s
assert s['version'] == '2.1', s
diff = [l for l in difflib.unified_diff(open('dict.before').read().splitlines(), new.splitlines(), n=0, lineterm='')
        if l[:1] in '+-' and l[:3] not in ('---', '+++')]
removed = sorted(l[1:].strip() for l in diff if l[0] == '-')
added = sorted(l[1:].strip() for l in diff if l[0] == '+')
assert removed == sorted(['version: "2.0"', 'modified: 2026-12-01   # the last change of meaning of 2.0 (its shape-index classes)',
                          'interval: [0.3, 0.8]', 'interval: [0.8, .inf]']), removed
assert [a.split(':')[0] for a in added] == sorted(['interval', 'interval', 'modified', 'version']), added
assert 'interval: [0.3, 0.31]' in added and 'interval: [0.31, .inf]' in added and 'version: "2.1"' in added, added
PYEOF
"$G" dict check dict.yaml >/dev/null || fail "the saved dictionary passes geotex dict check"
want 200 "$BASE/api/session" "${H[@]}"
check "session shows the new version" grep -q '"version":"2.1"' body.txt
# Edits now apply to the saved text: no edit, no change.
want 200 "$BASE/api/preview" -X POST "${H[@]}" -d '{"edits": []}'
check "nothing changed after the save" grep -q '"changed":\[\]' body.txt
# Fit: a mark of a concept that does not exist is unsatisfied, with a reason.
want 200 "$BASE/api/fit" -X POST "${H[@]}" \
  -d '{"marks": [{"object": "obj-1", "texture": 0, "concept": "no-such-concept", "yes": true}]}'
py "fit" <<'PYEOF'
import json
f = json.load(open('body.txt'))
assert f['edits'] == [] and len(f['unsatisfied']) == 1 and f['unsatisfied'][0]['reason'], f
PYEOF
want 400 "$BASE/api/fit" -X POST "${H[@]}" -d '{"marks": [{"object": "obj-1"}]}'
# The file edited by hand while the workbench runs: a save would lose that edit, so it is
# refused (409) and the file keeps the hand's text.
printf '# added by hand\n' >>dict.yaml
cp dict.yaml dict.by-hand
want 409 "$BASE/api/save" -X POST "${H[@]}" -d "$MOVE"
check "a save over a hand edit says so" grep -q 'changed on disk' body.txt
check "a save over a hand edit writes nothing" cmp -s dict.yaml dict.by-hand
kill -INT "$SERVER"
rc=0; wait "$SERVER" || rc=$?
check "SIGINT exits 0 (got $rc)" test "$rc" = 0
cp dict.yaml dict.before

# One object's outputs as PATH: its id is the directory's name. Without --dictionary, saving
# is refused.
start single out/objects/obj-1 --port 0 --host 127.0.0.1
H=(-H "X-Geotex-Token: $TOKEN")
want 200 "$BASE/api/objects" "${H[@]}"
check "single object listed" grep -q '"id":"obj-1"' body.txt
want 200 "$BASE/api/objects/obj-1/mesh" "${H[@]}"
want 404 "$BASE/api/objects/obj-2" "${H[@]}"
want 409 "$BASE/api/save" -X POST "${H[@]}" -d "$MOVE"
kill -TERM "$SERVER"
rc=0; wait "$SERVER" || rc=$?
check "SIGTERM exits 0 (got $rc)" test "$rc" = 0

check "the dictionary was not written" cmp -s dict.yaml dict.before
echo "view: all checks passed"
