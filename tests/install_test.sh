#!/usr/bin/env bash
# Installed use, as the README describes it: `cmake --install` of this build into a fresh
# prefix, then examples/ configured and built as a project of its own with find_package(geotex)
# and the targets geotex::pipeline and geotex::ontology, and both examples run: one annotates
# a synthetic sphere, whose Turtle and JSON report must be the bytes of `geotex annotate` for
# the same mesh, scale and dictionary; the other prints a dictionary's SKOS, which must be the same Turtle as
# `geotex dict skos` writes.
#   tests/install_test.sh GEOTEX SOURCE_DIR BUILD_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
build=$(realpath "$3")

cmake --install "$build" --prefix "$work/prefix" >install.txt 2>&1 || { cat install.txt; fail "cmake --install"; finish install; }
[ -f prefix/lib/cmake/geotex/geotexTargets.cmake ] || [ -n "$(find prefix -name geotexTargets.cmake)" ] || fail "no geotexTargets.cmake installed"
for h in geometry/segmentation.hpp annotation/dictionary.hpp ontology/rdf_writer.hpp pipeline/annotate.hpp pipeline/report_json.hpp pipeline/read_text_file.hpp; do
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
  "$geotex" synth --level 5 --engraved 0.5 -o s.ply --quiet >/dev/null
  # The installed dictionary, given to both: the library and the command read the same bytes.
  dict=$(find prefix -path '*geotex/dictionaries/default.yaml' | head -1)
  [ -n "$dict" ] || fail "dictionaries/default.yaml not installed"
  examples-build/example_library s.ply 0.05 "$dict" lib.json >lib.ttl 2>err.txt || fail "example_library: $(cat err.txt)"
  "$geotex" annotate s.ply --scale 0.05 --dictionary "$dict" -o cmd.ttl --json cmd.json --quiet >/dev/null 2>&1 || fail "geotex annotate"
  cmp -s lib.ttl cmd.ttl || fail "example_library: not the Turtle of geotex annotate ($(wc -c <lib.ttl) and $(wc -c <cmd.ttl) bytes)"
  cmp -s lib.json cmd.json || fail "example_library: not the JSON report of geotex annotate --json ($(wc -c <lib.json) and $(wc -c <cmd.json) bytes)"
  grep -q '"annotation"' lib.json || fail "example_library: no annotation in its JSON report"
  grep -q 'oa:Annotation' lib.ttl || fail "example_library: no annotation in its Turtle"
fi
if [ -x examples-build/example_dictionary_skos ]; then
  examples-build/example_dictionary_skos "$src/dictionaries/default.yaml" >lib.ttl 2>err.txt || fail "example_dictionary_skos: $(cat err.txt)"
  "$geotex" dict skos "$src/dictionaries/default.yaml" -o cmd.ttl --quiet >/dev/null 2>&1 || fail "geotex dict skos"
  cmp -s lib.ttl cmd.ttl || fail "example_dictionary_skos: not the Turtle of geotex dict skos ($(wc -c <lib.ttl) and $(wc -c <cmd.ttl) bytes)"
fi
finish install
