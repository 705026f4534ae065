#!/usr/bin/env bash
# The geotex command as a user runs it: a small end-to-end run, byte-identical outputs for
# any thread count, outputs to a device. Bad input, options and outputs: tests/corpus_test.sh.
set -u
geotex=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# --- a small run end to end ------------------------------------------------------------------
"$geotex" synth -o s.ply --level 6 --quiet >/dev/null || fail "synth"
[ -s s.ply ] && [ -s s.truth.json ] || fail "synth outputs"
"$geotex" segment s.ply --scale 0.04 -o seg1.ply --json seg1.json --threads 1 --quiet >/dev/null || fail "segment 1 thread"
"$geotex" segment s.ply --scale 0.04 -o seg2.ply --json seg2.json --threads 2 --quiet >/dev/null || fail "segment 2 threads"
cmp -s seg1.ply seg2.ply || fail "segmentation PLY differs between 1 and 2 threads"
cmp -s seg1.json seg2.json || fail "JSON report differs between 1 and 2 threads"
head -c 400 seg1.ply | grep -q "property int texel" || fail "segmentation PLY lacks the texel property"
head -c 500 seg1.ply | grep -q "property uchar red" || fail "segmentation PLY lacks colours"
"$geotex" evaluate seg1.ply s.truth.json --json score.json --quiet >eval.txt || fail "evaluate"
grep -q '"matched": 88' score.json || fail "evaluate: expected 88 matched shapes: $(cat eval.txt)"
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

# --- a radius too small for the mesh: a note, not an error --------------------------------------
"$geotex" synth -o coarse.ply --level 4 --quiet >/dev/null
"$geotex" segment coarse.ply --scale 0.04 -o coarse.seg.ply 2>&1 >/dev/null | grep -q "three mean edge lengths" || fail "coarse mesh: no note about the radius"

[ "$failures" -eq 0 ] && echo "cli tests passed" || { echo "$failures cli test(s) failed"; exit 1; }
