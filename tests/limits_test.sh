#!/usr/bin/env bash
# The limits of doubles and of memory (issue 17, findings 8 and 9):
# - the same mesh in any unit from x1e-300 to x1e300 gives the same texels, textures and
#   words (--scale promises independence from units); a mesh whose size no double holds
#   is refused with exit 2 and a message that says so;
# - under any address-space limit (ulimit -v) a run ends with exit 0 or 3 and one error
#   line naming the mesh: never an abort or a signal.
#   tests/limits_test.sh GEOTEX
set -u
# shellcheck source=tests/test_lib.sh
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"

# scaled SRC DST K: the ASCII PLY SRC with every coordinate multiplied by K (as doubles).
scaled() {
  /usr/bin/python3 - "$@" <<'PY'
import sys
src, dst, k = sys.argv[1], sys.argv[2], float(sys.argv[3])
lines = open(src).read().split("\n")
i = lines.index("end_header") + 1
nv = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
header = [l.replace("property float", "property double") for l in lines[:i]]
body = [" ".join(repr(float(x) * k) for x in l.split()) for l in lines[i:i + nv]]
open(dst, "w").write("\n".join(header + body + lines[i + nv:]))
PY
}
# face_labels PLY: the texel and texture of every face of an ASCII segmentation PLY.
face_labels() {
  /usr/bin/python3 - "$1" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
i = lines.index("end_header") + 1
nv = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
nf = int(next(l for l in lines if l.startswith("element face")).split()[2])
for l in lines[i + nv:i + nv + nf]:
    w = l.split()
    print(w[1 + int(w[0])], w[2 + int(w[0])])  # texel, texture after the index list
PY
}

# --- finding 9: extreme coordinates ---------------------------------------------------------
"$geotex" synth --level 5 --ascii -o m.ply --quiet >/dev/null || fail synth
for k in 1 1e-300 1e-100 1e100 1e300; do
  scaled m.ply "m$k.ply" "$k"
  "$geotex" segment "m$k.ply" --scale 0.05 --ascii -o "seg$k.ply" --quiet >"seg$k.txt" 2>err.txt ||
    fail "x$k: segment exit $?: $(cat err.txt)"
  [ ! -s err.txt ] || fail "x$k: stderr: $(cat err.txt)"
  face_labels "seg$k.ply" >"labels$k.txt"
  "$geotex" annotate "m$k.ply" --scale 0.05 -o "ann$k.ttl" --quiet >"ann$k.txt" 2>err.txt ||
    fail "x$k: annotate exit $?: $(cat err.txt)"
done
# The unscaled mesh has texels (else the comparison proves nothing).
grep -q '^m1.ply: [1-9][0-9]* texels in [1-9]' seg1.txt || fail "x1: no texels: $(cat seg1.txt)"
for k in 1e-300 1e-100 1e100 1e300; do
  # Same counts (the summary without the file name and the radius), same face labels, same words.
  diff <(sed 's/^[^:]*: //; s/(radius [^ ]* /(radius /' seg1.txt) <(sed 's/^[^:]*: //; s/(radius [^ ]* /(radius /' "seg$k.txt") >/dev/null ||
    fail "x$k: other texels or textures: $(head -n 1 "seg$k.txt") vs $(head -n 1 seg1.txt)"
  cmp -s labels1.txt "labels$k.txt" || fail "x$k: other face labels ($(diff labels1.txt "labels$k.txt" | grep -c '^>') faces differ)"
  diff <(grep '^  texture' ann1.txt) <(grep '^  texture' "ann$k.txt") >/dev/null || fail "x$k: other words: $(grep '^  texture' "ann$k.txt")"
done
# The radius is reported in the file's unit.
grep -q 'radius 1.01643e+299 mesh units' seg1e300.txt || fail "x1e300: radius not in mesh units: $(head -n 1 seg1e300.txt)"
# Sizes no double holds: refused as input (exit 2), one line that says why, no output.
scaled m.ply m-denormal.ply 1e-310
scaled m.ply m-huge.ply 1.7e308
for case in "m-denormal.ply|below the smallest normal double" "m-huge.ply|beyond the largest double"; do
  file=${case%%|*}
  "$geotex" segment "$file" --scale 0.05 -o out.ply --quiet >/dev/null 2>err.txt
  code=$?
  [ "$code" -eq 2 ] && [ "$(wc -l <err.txt)" -eq 1 ] && grep -q "^geotex: error: $file: .*${case#*|}" err.txt && [ ! -e out.ply ] ||
    fail "$file: expected exit 2 and one line '${case#*|}', got exit $code: $(cat err.txt)"
  # The mesh job of a tiled run, whose reader gives the positions to a scratch file: the same,
  # and the directory it made for them goes again.
  "$geotex" segment "$file" --scale 0.05 --tiles 4 --tile-dir "parts-$file" --pass mesh --quiet >/dev/null 2>err.txt
  code=$?
  [ "$code" -eq 2 ] && [ "$(wc -l <err.txt)" -eq 1 ] && grep -q "^geotex: error: $file: .*${case#*|}" err.txt && [ ! -e "parts-$file" ] ||
    fail "$file, --pass mesh: expected exit 2 and one line '${case#*|}', got exit $code: $(cat err.txt)"
done

# --- finding 8: out of memory -----------------------------------------------------------------
# Not under AddressSanitizer: its shadow memory needs terabytes of address space (no
# `ulimit -v` leaves room for it), and LeakSanitizer cannot run under strace (ptrace). The
# sanitizer half of `make test` checks the coordinates above; the Release half all of it.
if ldd "$geotex" 2>/dev/null | grep -q libasan; then
  echo "note: a sanitizer build: the memory limits and the thread count are checked by the Release build"
  finish limits
fi
# The smallest address space in which the binary starts at all (below it the dynamic loader
# fails, before geotex runs), then limits from there up, 8 MB apart, until the run succeeds.
base=0
for kb in $(seq 8000 4000 400000); do
  if (ulimit -v "$kb" && "$geotex" --version) >/dev/null 2>&1; then base=$kb; break; fi
done
[ "$base" -gt 0 ] || fail "geotex --version does not start under 400 MB"
# memory_ladder NAME OUTPUT -- command...: every rung ends with exit 0 (and the output) or
# exit 3 with one line saying "out of memory" that names m1.ply; the ladder must see both.
# Only a run that fails before its command line is parsed (the lowest rungs) knows no file
# yet and says just "out of memory".
memory_ladder() {
  local name=$1 output=$2
  shift 3
  local kb code saw_error=0 saw_success=0 saw_named=0 last_error=0 step
  # rung KB: one run under KB kB; 0 when it succeeded, 1 when it failed as it should.
  rung() {
    local limit=$1
    shift
    rm -f "$output"
    (ulimit -v "$limit" && exec "$@") >/dev/null 2>err.txt
    code=$?
    if [ "$code" -eq 0 ]; then
      [ -s "$output" ] || fail "$name under $limit kB: exit 0 without $output"
      return 0
    fi
    saw_error=1
    [ "$code" -eq 3 ] && [ "$(wc -l <err.txt)" -eq 1 ] && grep -q -E '^geotex: error: (m1\.ply: )?out of memory' err.txt ||
      fail "$name under $limit kB: exit $code (expected 0 or 3 with one 'geotex: error: m1.ply: out of memory' line): $(head -c 300 err.txt)"
    ! grep -q '^geotex: error: m1\.ply: out of memory' err.txt || saw_named=1
    [ ! -e "$output" ] || fail "$name under $limit kB: exit $code but $output exists"
    return 1
  }
  for kb in $(seq "$base" 8000 $((base + 800000))); do
    if rung "$kb" "$@"; then saw_success=1; break; fi
    last_error=$kb
  done
  # The runs that fail once the mesh is named lie between the last failure and the first
  # success; how wide that band is depends on the binary's size and its allocations, so when
  # 8 MB steps jump over it, walk it 1 MB at a time.
  if [ "$saw_success" -eq 1 ] && [ "$saw_named" -eq 0 ] && [ "$last_error" -gt 0 ]; then
    for step in $(seq $((last_error + 1000)) 1000 $((kb - 1000))); do
      rung "$step" "$@" && break
    done
  fi
  [ "$saw_error" -eq 1 ] || fail "$name: even the smallest limit ($base kB) was enough: the ladder tested nothing"
  [ "$saw_named" -eq 1 ] || fail "$name: no out-of-memory error named the mesh"
  [ "$saw_success" -eq 1 ] || fail "$name: no limit up to $((base + 800000)) kB was enough"
  # No temporary output left by any rung.
  [ -z "$(find . -name '.*.tmp.*')" ] || fail "$name: temporary files left: $(find . -name '.*.tmp.*')"
}
# With -j1 no thread is started at all (so none can fail to start).
# (strace may be missing, or not allowed to trace in a container: the check is then skipped.)
if command -v strace >/dev/null && strace -f -o /dev/null true 2>/dev/null; then
  printf 'ASK { ?s ?p ?o }\n' >ask.rq
  for cmd in "segment m1.ply --scale 0.05 -o one.ply" "annotate m1.ply --scale 0.05 -o one.ttl --json one.json" \
             "query ask.rq one.ttl two.ttl"; do
    [ -e one.ttl ] && cp one.ttl two.ttl
    # shellcheck disable=SC2086
    strace -f -e trace=clone,clone3 -o clones.txt "$geotex" $cmd -j1 --quiet >/dev/null 2>err.txt || fail "$cmd -j1: $(cat err.txt)"
    [ "$(grep -c 'clone' clones.txt)" -eq 0 ] || fail "$cmd -j1 started threads: $(grep clone clones.txt | head -3)"
  done
else
  echo "note: strace missing or not allowed: the no-thread check of -j1 is skipped"
fi
memory_ladder "segment -j1" seg.ply -- "$geotex" segment m1.ply --scale 0.05 -o seg.ply -j1 --quiet
memory_ladder "segment" seg.ply -- "$geotex" segment m1.ply --scale 0.05 -o seg.ply --quiet
memory_ladder "annotate -j2" ann.ttl -- "$geotex" annotate m1.ply --scale 0.05 -o ann.ttl --json ann.json -j2 --quiet

finish limits
