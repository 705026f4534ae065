#!/usr/bin/env bash
# Installed use, as the README describes it: `cmake --install` of this build into a fresh
# prefix, then examples/ configured and built as a project of its own with find_package(geotex)
# and the targets geotex::geometry and geotex::ontology, and both examples run: one segments
# a synthetic sphere, the other prints a dictionary's SKOS, which must be the same Turtle as
# `geotex dict skos` writes.
#   tests/install_test.sh GEOTEX SOURCE_DIR BUILD_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
build=$(realpath "$3")

cmake --install "$build" --prefix "$work/prefix" >install.txt 2>&1 || { cat install.txt; fail "cmake --install"; finish install; }
[ -f prefix/lib/cmake/geotex/geotexTargets.cmake ] || [ -n "$(find prefix -name geotexTargets.cmake)" ] || fail "no geotexTargets.cmake installed"
for h in geometry/segmentation.hpp annotation/dictionary.hpp ontology/rdf_writer.hpp; do
  [ -f "prefix/include/geotex/$h" ] || fail "header $h not installed"
done
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if cmake -S "$src/examples" -B examples-build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
     -DCMAKE_PREFIX_PATH="$work/prefix" >configure.txt 2>&1; then
  cmake --build examples-build >build.txt 2>&1 || { tail -30 build.txt; fail "examples do not build against the installed geotex"; }
else
  tail -30 configure.txt; fail "examples do not configure against the installed geotex"
fi

[ -x examples-build/example_library ] && [ -x examples-build/example_dictionary_skos ] || fail "the examples were not built"
if [ -x examples-build/example_library ]; then
  "$geotex" synth --level 5 -o s.ply --quiet >/dev/null
  examples-build/example_library s.ply 0.05 >lib.txt 2>&1 || fail "example_library: $(cat lib.txt)"
  # The same segmentation as the command's: the texel count of its summary line.
  expected=$("$geotex" segment s.ply --scale 0.05 -o seg.ply --json seg.json --quiet >/dev/null &&
             /usr/bin/python3 -c 'import json,sys; print(len(json.load(open("seg.json"))["texels"]))')
  grep -q "^$expected texels, " lib.txt || fail "example_library: expected $expected texels: $(head -1 lib.txt)"
fi
if [ -x examples-build/example_dictionary_skos ]; then
  examples-build/example_dictionary_skos "$src/dictionaries/default.yaml" >lib.ttl 2>err.txt || fail "example_dictionary_skos: $(cat err.txt)"
  "$geotex" dict skos "$src/dictionaries/default.yaml" -o cmd.ttl --quiet >/dev/null 2>&1 || fail "geotex dict skos"
  cmp -s lib.ttl cmd.ttl || fail "example_dictionary_skos: not the Turtle of geotex dict skos ($(wc -c <lib.ttl) and $(wc -c <cmd.ttl) bytes)"
fi
finish install
