#!/bin/bash
# geotex segment --tiles on sphere-1 level 8 (1.3 million faces), issue 21's test: 4 and 9
# tiles give the whole mesh's segmentation, byte for byte (texels, textures, colours).
# Release only (about 30 s): the sanitizer half of make test skips it.
set -u
geotex=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$geotex" synth -o s8.ply --level 8 --quiet >/dev/null || fail "synth --level 8"
"$geotex" segment s8.ply --scale 0.04 -o whole.ply --json whole.json --quiet >summary.txt || fail "segment whole"
grep -q "88 texels in 4 textures" summary.txt || fail "whole: not sphere-1's 88 texels in 4 textures: $(head -1 summary.txt)"
for tiles in 4 9; do
  "$geotex" segment s8.ply --scale 0.04 -o "tiles$tiles.ply" --tiles "$tiles" --quiet >/dev/null || fail "segment --tiles $tiles"
  cmp -s whole.ply "tiles$tiles.ply" || fail "--tiles $tiles: not the whole mesh's segmentation"
done

[ "$failures" -eq 0 ] && echo "tiles tests passed" || { echo "$failures tiles test(s) failed"; exit 1; }
