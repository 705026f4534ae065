#!/usr/bin/env bash
# The geotex command as a user runs it: a small end-to-end run, byte-identical outputs for
# any thread count, outputs to a device. Bad input, options and outputs: tests/corpus_test.sh.
set -u
geotex=$(realpath "$1")
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# --- a small run end to end ------------------------------------------------------------------
"$geotex" synth -o s.ply --level 6 --quiet >/dev/null || fail "synth"
[ -s s.ply ] && [ -s s.truth.json ] || fail "synth outputs"
# Levels 0 to 11 (84 million faces): anything else is a usage error before any work.
for level in 12 -1 nan 7.5 ''; do
  rc=0; "$geotex" synth -o badlevel.ply --level "$level" -q >badlevel.out 2>badlevel.err || rc=$?
  [ "$rc" = 1 ] || fail "synth --level '$level': exit $rc, expected 1"
  [ "$(wc -l <badlevel.err)" = 1 ] && grep -q -- "--level" badlevel.err ||
    fail "synth --level '$level': error $(cat badlevel.err)"
  [ ! -e badlevel.ply ] || fail "synth --level '$level' wrote a mesh"
done
"$geotex" synth -o badlevel.ply --level 12 -q 2>&1 | grep -q "not in range 0 to 11" ||
  fail "synth --level 12: the message gives the range"
"$geotex" segment s.ply --scale 0.04 -o seg1.ply --json seg1.json --threads 1 --quiet >/dev/null || fail "segment 1 thread"
"$geotex" segment s.ply --scale 0.04 -o seg2.ply --json seg2.json --threads 2 --quiet >/dev/null || fail "segment 2 threads"
cmp -s seg1.ply seg2.ply || fail "segmentation PLY differs between 1 and 2 threads"
cmp -s seg1.json seg2.json || fail "JSON report differs between 1 and 2 threads"
head -c 400 seg1.ply | grep -q "property int texel" || fail "segmentation PLY lacks the texel property"
head -c 500 seg1.ply | grep -q "property uchar red" || fail "segmentation PLY lacks colours"
"$geotex" evaluate seg1.ply s.truth.json --json score.json --quiet >eval.txt || fail "evaluate"
grep -q '"matched": 88' score.json || fail "evaluate: expected 88 matched shapes: $(cat eval.txt)"
# The same sphere as unindexed triangles (--soup): 3 vertices for each of its 81,920 faces, of
# which the repair merges all but the sphere's 40,962 back, and the same 88 shapes found.
"$geotex" synth -o soup.ply --level 6 --soup --quiet >/dev/null || fail "synth --soup"
head -c 300 soup.ply | grep -aq "element vertex 245760" || fail "synth --soup: not 3 vertices a face"
rc=0; "$geotex" synth -o badsoup.ply --level 2 --soup=maybe -q >badsoup.out 2>badsoup.err || rc=$?
[ "$rc" = 1 ] && [ "$(wc -l <badsoup.err)" = 1 ] && grep -q -- "--soup" badsoup.err && [ ! -e badsoup.ply ] ||
  fail "synth --soup=maybe: exit $rc, $(cat badsoup.err)"
"$geotex" segment soup.ply --scale 0.04 -o soupseg.ply --json soupseg.json --quiet >/dev/null ||
  fail "segment the soup"
grep -q '"duplicate_vertices_merged": 204798' soupseg.json || fail "the soup's vertices not merged back"
"$geotex" evaluate soupseg.ply s.truth.json --json soupscore.json --quiet >/dev/null &&
  grep -q '"matched": 88' soupscore.json || fail "the soup's segmentation: not 88 matched shapes"
# 88 texels and 80 landmarks: the 4 textures of sphere-1's 4 kinds, the same bytes on any thread
# count. (Groups of 16 to 37 texels need most of them: 50 to 70 landmarks give 3 textures.)
for j in 1 2; do
  "$geotex" segment s.ply --scale 0.04 --cluster-landmarks 80 -o lm$j.ply --json lm$j.json \
    --threads $j >lm$j.out 2>lm$j.err || fail "segment --cluster-landmarks 80 -j $j"
done
grep -q "88 texels in 4 textures" lm1.out || fail "--cluster-landmarks 80: $(cat lm1.out)"
grep -q "clustering: 88 points are more than max_points (80)" lm1.err ||
  fail "--cluster-landmarks 80: no note of the landmarks: $(cat lm1.err)"
cmp -s lm1.ply lm2.ply && cmp -s lm1.json lm2.json ||
  fail "--cluster-landmarks: outputs differ between 1 and 2 threads"
grep -q '"cluster_landmarks": 80' lm1.json || fail "--cluster-landmarks: not in the report"
for bad in 1 -1 x; do
  rc=0; "$geotex" segment s.ply --scale 0.04 --cluster-landmarks "$bad" -o badlm.ply \
    >/dev/null 2>badlm.err || rc=$?
  [ "$rc" = 1 ] && [ "$(wc -l <badlm.err)" = 1 ] && grep -q -- "--cluster-landmarks" badlm.err ||
    fail "--cluster-landmarks '$bad': exit $rc, $(cat badlm.err)"
  [ ! -e badlm.ply ] || fail "--cluster-landmarks '$bad' wrote a mesh"
done
"$geotex" segment s.ply --radius 0.08 -o seg3.ply --quiet >/dev/null || fail "segment --radius"
"$geotex" segment s.ply --scale 0.04 --orientation both -o seg4.ply --ascii --quiet >/dev/null || fail "segment both"
head -c 3 seg4.ply | grep -q ply || fail "ASCII output"

"$geotex" --help >/dev/null || fail "--help"
"$geotex" segment --help | grep -q -- "--scale" || fail "segment --help"

# --- nothing salient: a warning, exit 0, valid empty outputs ----------------------------------
"$geotex" synth -o plain.ply --level 5 --big-discs 0 --small-discs 0 --squares 0 --rectangles 0 --quiet >/dev/null
"$geotex" segment plain.ply --scale 0.04 -o plain.seg.ply --json plain.json --quiet >/dev/null 2>warn.txt || fail "perfect sphere: non-zero exit"
grep -q "geotex: warning: .*no salient" warn.txt || fail "perfect sphere: no warning ($(cat warn.txt))"
grep -q '"texels": \[\]' plain.json || fail "perfect sphere: JSON should list zero texels"

# --- outputs that are not regular files --------------------------------------------------
"$geotex" segment s.ply --scale 0.04 -o /dev/null --quiet >/dev/null || fail "-o /dev/null"
[ -c /dev/null ] || fail "/dev/null is no longer a device"

# --- an output never names an input: exit 1 before any work, naming both, the input intact ----
# expect_refused CODE PATTERN FILE cmd...: exit CODE, one error line matching PATTERN, FILE unchanged
expect_refused() {
  local code=$1 pattern=$2 file=$3; shift 3
  local before rc=0
  before=$(sha256sum "$file")
  "$@" >refused.out 2>refused.err || rc=$?
  [ "$rc" = "$code" ] || fail "'$*': exit $rc, expected $code ($(cat refused.err))"
  [ "$(wc -l <refused.err)" = 1 ] && grep -q -- "$pattern" refused.err || fail "'$*': error $(cat refused.err)"
  [ "$(sha256sum "$file")" = "$before" ] || fail "'$*': $file was changed"
}

# --- --tiles: the same segmentation made a tile at a time (docs/tiles.md) ------------------------
"$geotex" segment s.ply --scale 0.04 --orientation both -o tiles4.ply --ascii --tiles 4 --quiet >/dev/null || fail "segment --tiles 4"
cmp -s tiles4.ply seg4.ply || fail "--tiles 4: not the whole mesh's segmentation"
"$geotex" segment s.ply --scale 0.04 -o tiles9.ply --tiles 9 --quiet >/dev/null || fail "segment --tiles 9"
cmp -s tiles9.ply seg1.ply || fail "--tiles 9: not the whole mesh's segmentation"
for tiles in -1 10001 2.5 x nan ""; do
  expect_refused 1 "tiles" s.ply "$geotex" segment s.ply --scale 0.04 -o badtiles.ply --tiles "$tiles" -q
  [ ! -e badtiles.ply ] || fail "--tiles '$tiles' wrote a segmentation"
done
expect_refused 1 "--tiles with --scale auto" s.ply "$geotex" segment s.ply --scale auto -o badtiles.ply --tiles 4 -q

cp s.ply in.ply
cp "$src/dictionaries/default.yaml" d.yaml
same="is the same file as the input"
expect_refused 1 "--output 'in.ply' $same MESH 'in.ply'" in.ply "$geotex" segment in.ply --scale 0.05 -o in.ply -q
expect_refused 1 "--json 'in.ply' $same MESH" in.ply "$geotex" segment in.ply --scale 0.05 -o o.ply --json in.ply -q
expect_refused 1 "--geometry-cache 'in.ply' $same MESH" in.ply "$geotex" annotate in.ply --scale 0.05 -o o.ttl --geometry-cache in.ply -q
expect_refused 1 "--output 'in.ply' $same MESH" in.ply "$geotex" render in.ply -o in.ply -q
expect_refused 1 "--json 'seg1.ply' $same SEGMENTATION" seg1.ply "$geotex" evaluate seg1.ply s.truth.json --json seg1.ply -q
ln -s in.ply alias.ply; ln in.ply hard.ply
expect_refused 1 "--output 'alias.ply' $same MESH 'in.ply'" in.ply "$geotex" segment in.ply --scale 0.05 -o alias.ply -q
expect_refused 1 "--segmentation 'hard.ply' $same MESH 'in.ply'" in.ply "$geotex" annotate in.ply --scale 0.05 -o o.ttl --segmentation hard.ply -q
expect_refused 1 "--output 'd.yaml' $same FILE 'd.yaml'" d.yaml "$geotex" dict skos d.yaml -o d.yaml
expect_refused 1 "--json 'd.yaml' $same --dictionary" d.yaml "$geotex" annotate in.ply --scale 0.05 --dictionary d.yaml -o o.ttl --json d.yaml -q
[ ! -e o.ply ] && [ ! -e o.ttl ] || fail "a refused run wrote an output"
# The geometry cache is read and rewritten: naming it is no clash with itself.
"$geotex" annotate in.ply --scale 0.05 -o o.ttl --geometry-cache c.cbor -q >/dev/null || fail "cache written"
"$geotex" annotate in.ply --scale 0.05 -o o.ttl --geometry-cache c.cbor 2>&1 >/dev/null | grep -q "geometry read from c.cbor" ||
  fail "the cache named as its own input and output is read"
rm -f o.ttl

# --- one texture-label rule: a language the dictionary lacks gives its first language everywhere -----
# (the dictionary declares French first, so its first language is not the first in sort order)
sed 's/languages: \[en, fr\]/languages: [fr, en]/' "$src/dictionaries/default.yaml" >fr-first.yaml
"$geotex" annotate s.ply --scale 0.04 --dictionary fr-first.yaml --lang de -o de.ttl --json de.json -q >de.txt 2>/dev/null ||
  fail "annotate --lang de"
/usr/bin/python3 - de.txt de.json de.ttl <<'PY' || fail "--lang de: the console, the JSON report and the RDF do not say the same French labels"
import json, re, sys
console = [l.rstrip("\n").split(": ", 1)[1].split(" (withheld")[0] for l in open(sys.argv[1]) if re.match(r"  texture \d+: ", l)]
report = json.load(open(sys.argv[2]))["annotation"]["textures"]
from_json = [", ".join(c["label"] for c in t["concepts"]) for t in report]
rdf = sorted(re.findall(r'rdfs:label "([^"]*)"@fr', open(sys.argv[3], encoding="utf-8").read()))
assert console and console == from_json, (console, from_json)
assert sorted(l for l in console if l) == [l for l in rdf if l in console], (console, rdf)
assert any("é" in l for l in console), console  # French, not English
PY

# --- outputs over symbolic links: the link stays a link, its target gets the new content ---------
"$geotex" segment s.ply --scale 0.04 -o target.ply -q --ascii >/dev/null
ln -s target.ply link.ply
"$geotex" segment s.ply --scale 0.04 -o link.ply -q >/dev/null || fail "-o link"
[ -L link.ply ] && [ "$(readlink link.ply)" = target.ply ] || fail "-o link: the link was replaced"
cmp -s target.ply seg1.ply || fail "-o link: the target does not hold the new output"
mkdir sub && ln -s ../dangling.ply sub/dlink.ply
"$geotex" segment s.ply --scale 0.04 -o sub/dlink.ply -q >/dev/null || fail "-o dangling link"
[ -L sub/dlink.ply ] && cmp -s dangling.ply seg1.ply || fail "-o dangling link: its target is not created"
# A link to a device, a FIFO, /dev/stdout: written in place, never renamed over.
ln -s /dev/null null-link
"$geotex" segment s.ply --scale 0.04 -o null-link -q >/dev/null || fail "-o link to /dev/null"
[ -L null-link ] && [ -c /dev/null ] || fail "link to /dev/null replaced"
mkfifo pipe
(cat pipe > from-pipe.ply) & reader=$!
"$geotex" segment s.ply --scale 0.04 -o pipe -q >/dev/null || fail "-o FIFO"
wait "$reader"
[ -p pipe ] && cmp -s from-pipe.ply seg1.ply || fail "-o FIFO: not a FIFO any more, or wrong bytes"
# (the texture summary follows the PLY on stdout)
"$geotex" segment s.ply --scale 0.04 -o /dev/stdout -q 2>/dev/null >stdout.ply
cmp -s -n "$(stat -c %s seg1.ply)" stdout.ply seg1.ply || fail "-o /dev/stdout"
[ -c /dev/stdout ] || [ -L /dev/stdout ] || fail "/dev/stdout is no longer a device or link"

# --- a replaced output keeps its mode; a read-only one is refused unless --replace-read-only -------
"$geotex" segment s.ply --scale 0.04 -o private.ply -q >/dev/null
chmod 600 private.ply
"$geotex" segment s.ply --scale 0.04 -o private.ply --orientation both -q >/dev/null
[ "$(stat -c %a private.ply)" = 600 ] || fail "a 600 output came back $(stat -c %a private.ply)"
umask 077; "$geotex" segment s.ply --scale 0.04 -o new.ply -q >/dev/null; umask 022
[ "$(stat -c %a new.ply)" = 600 ] || fail "a new output ignores the umask ($(stat -c %a new.ply))"
chmod 444 private.ply
expect_refused 4 "private.ply: is read-only.*--replace-read-only" private.ply "$geotex" segment s.ply --scale 0.04 -o private.ply -q
expect_refused 4 "private.ply: is read-only" private.ply "$geotex" synth -o private.ply --level 3 -q
"$geotex" segment s.ply --scale 0.04 -o private.ply --replace-read-only -q >/dev/null || fail "--replace-read-only"
cmp -s private.ply seg1.ply && [ "$(stat -c %a private.ply)" = 444 ] || fail "--replace-read-only: content or mode ($(stat -c %a private.ply))"
# As root (the issue's case), a replaced file also keeps its owner.
if [ "$(id -u)" = 0 ]; then
  chown 65534:65534 private.ply
  "$geotex" segment s.ply --scale 0.04 -o private.ply --orientation both --replace-read-only -q >/dev/null
  [ "$(stat -c %u:%g:%a private.ply)" = 65534:65534:444 ] || fail "root: owner or mode not kept ($(stat -c %u:%g:%a private.ply))"
fi

# --- a radius too small for the mesh: a note, not an error --------------------------------------
"$geotex" synth -o coarse.ply --level 4 --quiet >/dev/null
"$geotex" segment coarse.ply --scale 0.04 -o coarse.seg.ply 2>&1 >/dev/null | grep -q "three mean edge lengths" || fail "coarse mesh: no note about the radius"

[ "$failures" -eq 0 ] && echo "cli tests passed" || { echo "$failures cli test(s) failed"; exit 1; }
