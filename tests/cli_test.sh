#!/usr/bin/env bash
# The geotex command as a user runs it: a small end-to-end run, byte-identical outputs for
# any thread count, and every bad input answered by one line, the right exit code and no
# output file.
set -u
geotex=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_error CODE FILE-IN-MESSAGE -- command...: exit code, one stderr line naming the
# file, and no new file in the directory.
expect_error() {
  local code=$1 name=$2; shift 3
  local before after
  before=$(ls -A | sort)
  "$@" >out.txt 2>err.txt
  local got=$?
  after=$(ls -A | grep -v -e '^out.txt$' -e '^err.txt$' | sort)
  before=$(printf '%s\n' "$before" | grep -v -e '^out.txt$' -e '^err.txt$' | sort)
  [ "$got" -eq "$code" ] || fail "$*: exit $got, expected $code ($(cat err.txt))"
  [ "$(wc -l <err.txt)" -eq 1 ] || fail "$*: expected one stderr line, got: $(cat err.txt)"
  grep -q "^geotex: error: .*$name" err.txt || fail "$*: message does not name '$name': $(cat err.txt)"
  [ "$before" = "$after" ] || fail "$*: left files behind: $(comm -13 <(echo "$before") <(echo "$after") | tr '\n' ' ')"
}

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

# --- bad input and options --------------------------------------------------------------------
expect_error 2 nosuch.ply -- "$geotex" segment nosuch.ply --scale 0.04 -o x.ply
printf 'solid\n' > mesh.xyz
expect_error 2 mesh.xyz -- "$geotex" segment mesh.xyz --scale 0.04 -o x.ply
head -c 2000 s.ply > truncated.ply
expect_error 2 truncated.ply -- "$geotex" segment truncated.ply --scale 0.04 -o x.ply
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n' > nan.ply
expect_error 2 nan.ply -- "$geotex" segment nan.ply --scale 0.04 -o x.ply
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n' > empty.ply
expect_error 2 empty.ply -- "$geotex" segment empty.ply --scale 0.04 -o x.ply
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n' > short.off
expect_error 2 short.off -- "$geotex" segment short.off --scale 0.04 -o x.ply
for bad in 0 1 -0.1 1.5; do
  expect_error 1 scale -- "$geotex" segment s.ply --scale "$bad" -o x.ply
done
expect_error 1 scale -- "$geotex" segment s.ply -o x.ply
expect_error 1 radius -- "$geotex" segment s.ply --radius -2 -o x.ply
expect_error 1 orientation -- "$geotex" segment s.ply --scale 0.04 --orientation sideways -o x.ply
expect_error 4 no/such/dir/x.ply -- "$geotex" segment s.ply --scale 0.04 -o no/such/dir/x.ply --quiet
"$geotex" segment s.ply --scale 0.04 -o /dev/null --quiet >/dev/null || fail "-o /dev/null"
[ -c /dev/null ] || fail "/dev/null is no longer a device"
mkdir adir
expect_error 4 adir -- "$geotex" segment s.ply --scale 0.04 -o adir --quiet
expect_error 2 nosuch.json -- "$geotex" evaluate seg1.ply nosuch.json --quiet
"$geotex" synth -o coarse.ply --level 4 --quiet >/dev/null
expect_error 2 coarse.truth.json -- "$geotex" evaluate seg1.ply coarse.truth.json --quiet
"$geotex" segment coarse.ply --scale 0.04 -o coarse.seg.ply 2>&1 >/dev/null | grep -q "three mean edge lengths" || fail "coarse mesh: no note about the radius"

[ "$failures" -eq 0 ] && echo "cli tests passed" || { echo "$failures cli test(s) failed"; exit 1; }
