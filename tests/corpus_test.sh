#!/usr/bin/env bash
# Hostile input: a corpus of malformed meshes (PLY ASCII and binary, OBJ, OFF, STL),
# dictionaries, ground truths and command lines, generated here by tests/corpus_make.py.
# Every case must end with the right exit code and exactly one stderr line
# `geotex: error: ...` that names the file or the option and the problem, leave no output
# and no temporary file behind, not crash, and stay within bounded memory (headers that
# declare 10^12 elements must not be believed).
#   tests/corpus_test.sh GEOTEX
set -u
geotex=$(realpath "$1")
# Without it every case would fail on its own, 440 times; scripts/setup-deps.sh test installs it.
[ -x /usr/bin/time ] || { echo "FAIL: /usr/bin/time (GNU time, Debian package 'time') is missing: run scripts/setup-deps.sh test"; exit 1; }
here=$(dirname "$(realpath "$0")")
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work"
failures=0
cases=0
max_rss_kb=$((200 * 1024))
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Runs a command with stdout and stderr in out.txt and err.txt; sets `got` to its exit status
# (128+N for signal N) and `rss` to its peak resident memory in kB. GNU time rather than a
# Python wrapper, and bash builtins rather than commands where they do the same: the corpus
# runs 440 cases, and a Python start (0.1-0.2 s) or a dozen forks a case cost more than the
# cases themselves.
measured() {
  /usr/bin/time -q -f '%M' -o rss.txt "$@" >out.txt 2>err.txt
  got=$?
  rss=unmeasured
  read -r rss <rss.txt
}

# Whether the last `measured` command stayed under max_rss_kb (false when time gave no number).
within_memory() { [[ $rss =~ ^[0-9]+$ ]] && [ "$rss" -lt "$max_rss_kb" ]; }

# Sets `listing` to every file and directory under the work directory but the outputs of
# `measured`, one a line.
snapshot() {
  local f
  listing=
  shopt -s globstar dotglob nullglob
  for f in **; do
    case "${f##*/}" in out.txt | err.txt | rss.txt) ;; *) listing+="$f"$'\n' ;; esac
  done
  shopt -u globstar dotglob nullglob
}

sanitizer_report='Sanitizer|runtime error:|==[0-9]+==ERROR'

# expect_error CODE NAME PROBLEM -- command...
# CODE: exit code; NAME: the file or option the message must name (fixed string); PROBLEM:
# an extended regular expression the message must match.
expect_error() {
  local code=$1 name=$2 problem=$3
  shift 4
  cases=$((cases + 1))
  local before got rss line err= newlines listing
  snapshot
  before=$listing
  measured "$@"
  snapshot
  local what="$* [exit $got]"
  IFS= read -r -d '' err <err.txt
  newlines=${err//[!$'\n']/}
  line=${err%%$'\n'*}
  [ "$got" -lt 128 ] || fail "$what: killed by signal $((got - 128)): ${err:0:300}"
  [ "$got" -eq "$code" ] || fail "$what: expected exit $code: ${err:0:300}"
  ! [[ $err =~ $sanitizer_report ]] || fail "$what: sanitizer report: ${err:0:300}"
  [ "${#newlines}" -eq 1 ] && [ "$line"$'\n' = "$err" ] || fail "$what: expected one stderr line, got: ${err:0:600}"
  case "$line" in "geotex: error: "*) ;; *) fail "$what: not 'geotex: error: ...': $line" ;; esac
  [[ $line == *"$name"* ]] || fail "$what: message does not name '$name': $line"
  grep -q -E -- "$problem" <<<"$line" || fail "$what: message does not say /$problem/: $line"
  within_memory || fail "$what: peak memory $rss kB"
  [ "$before" = "$listing" ] || fail "$what: files changed: $(diff <(echo "$before") <(echo "$listing") | grep '^[<>]' | tr '\n' ' ')"
}

# expect_check_error NAME PROBLEM FILE: `geotex dict check FILE` lists each problem as
# FILE:line:column: what, then ends with one `geotex: error:` line; exit 2.
expect_check_error() {
  local name=$1 problem=$2 file=$3
  cases=$((cases + 1))
  local got rss
  measured "$geotex" dict check "$file"
  local what="dict check $file [exit $got]"
  [ "$got" -eq 2 ] || fail "$what: expected exit 2: $(head -c 300 err.txt)"
  ! grep -q -E "$sanitizer_report" err.txt || fail "$what: sanitizer report"
  [ "$(grep -c '^geotex: error: ' err.txt)" -eq 1 ] && [ "$(tail -n 1 err.txt | grep -c "^geotex: error: $name: ")" -eq 1 ] ||
    fail "$what: expected one final 'geotex: error: $name: ...' line: $(cat err.txt)"
  [ "$(grep -v -c -e '^geotex: error: ' -e "^$name:[0-9]*:[0-9]*: " err.txt)" -eq 0 ] ||
    fail "$what: lines not of the form '$name:line:column: what': $(cat err.txt)"
  grep -q -E -- "$problem" err.txt || fail "$what: no problem matching /$problem/: $(cat err.txt)"
  within_memory || fail "$what: peak memory $rss kB"
}

/usr/bin/python3 "$here/corpus_make.py" || { echo "FAIL: corpus generation"; exit 1; }
"$geotex" synth -o s.ply --level 4 --quiet >/dev/null || fail "synth"
head -c 2000 s.ply >ply_binary_synth_truncated.ply
mkdir adir
printf 'solid\n' >mesh.xyz
mesh=(--scale 0.1 -o out.ply --quiet)

# The corpus is made by breaking valid files: the unbroken ones must read.
for good in good_ascii.ply good_binary_le.ply good_binary_be.ply good.obj good.off good_ascii.stl good_binary.stl good_bom.obj good_bom.off; do
  "$geotex" segment "$good" --scale 0.1 -o good.seg.ply --quiet >/dev/null 2>err.txt && [ -s good.seg.ply ] ||
    fail "the unbroken $good does not read: $(cat err.txt)"
  rm -f good.seg.ply
done
"$geotex" dict check dict_good.yaml >/dev/null 2>err.txt || fail "the unbroken dict_good.yaml: $(cat err.txt)"
# ... without facets it loads with one warning; the faceted one, which the facet cases break, is clean
[ "$(grep -c '^dict_good.yaml:1:1: warning: no facets' err.txt)" -eq 1 ] && [ "$(wc -l <err.txt)" -eq 1 ] || fail "dict_good.yaml: expected one 'no facets' warning: $(cat err.txt)"
"$geotex" dict check dict_facets_good.yaml >/dev/null 2>err.txt && [ ! -s err.txt ] || fail "the unbroken dict_facets_good.yaml: $(cat err.txt)"
"$geotex" evaluate seg.ply truth_good.json --quiet >/dev/null 2>err.txt || fail "the unbroken seg.ply and truth_good.json: $(cat err.txt)"

# --- PLY --------------------------------------------------------------------------------------
expect_error 2 ply_ascii_fewer_vertices.ply 'face 0 of 4: polygon with 1 vertices' -- "$geotex" segment ply_ascii_fewer_vertices.ply "${mesh[@]}"
expect_error 2 ply_ascii_more_vertices.ply 'face 0 of 4: expected an integer' -- "$geotex" segment ply_ascii_more_vertices.ply "${mesh[@]}"
expect_error 2 ply_ascii_fewer_faces.ply 'face 3 of 4: end of file' -- "$geotex" segment ply_ascii_fewer_faces.ply "${mesh[@]}"
expect_error 2 ply_ascii_more_faces.ply ":18:1: '3' after the last declared element" -- "$geotex" segment ply_ascii_more_faces.ply "${mesh[@]}"
expect_error 2 ply_binary_le_fewer_faces.ply 'face 3 of 4: truncated' -- "$geotex" segment ply_binary_le_fewer_faces.ply "${mesh[@]}"
expect_error 2 ply_binary_be_fewer_vertices.ply 'truncated' -- "$geotex" segment ply_binary_be_fewer_vertices.ply "${mesh[@]}"
expect_error 2 ply_binary_le_more_faces.ply '13 bytes after the last declared element' -- "$geotex" segment ply_binary_le_more_faces.ply "${mesh[@]}"
expect_error 2 ply_binary_le_more_vertices.ply 'face 0 of 4' -- "$geotex" segment ply_binary_le_more_vertices.ply "${mesh[@]}"
expect_error 2 ply_header_only.ply "4 'vertex' elements.*only 0 bytes" -- "$geotex" segment ply_header_only.ply "${mesh[@]}"
expect_error 2 ply_binary_header_only.ply 'vertex 0 of 4: truncated' -- "$geotex" segment ply_binary_header_only.ply "${mesh[@]}"
expect_error 2 ply_mid_header.ply "'end_header' is missing" -- "$geotex" segment ply_mid_header.ply "${mesh[@]}"
expect_error 2 ply_no_end_header.ply "is 'end_header' missing" -- "$geotex" segment ply_no_end_header.ply "${mesh[@]}"
expect_error 2 ply_binary_be_mid_body.ply 'face 2 of 4: truncated at byte 243' -- "$geotex" segment ply_binary_be_mid_body.ply "${mesh[@]}"
expect_error 2 ply_binary_synth_truncated.ply 'truncated at byte 2000' -- "$geotex" segment ply_binary_synth_truncated.ply "${mesh[@]}"
expect_error 2 ply_float_indices.ply 'item type float, which is not an integer type' -- "$geotex" segment ply_float_indices.ply "${mesh[@]}"
expect_error 2 ply_unknown_type.ply ":4:10: unknown property type 'flaot'" -- "$geotex" segment ply_unknown_type.ply "${mesh[@]}"
expect_error 2 ply_missing_z.ply "no 'z' property" -- "$geotex" segment ply_missing_z.ply "${mesh[@]}"
expect_error 2 ply_vertex_list.ply "vertex property 'z' is a list" -- "$geotex" segment ply_vertex_list.ply "${mesh[@]}"
expect_error 2 ply_bad_format.ply "unknown PLY format 'binary_middle_endian'" -- "$geotex" segment ply_bad_format.ply "${mesh[@]}"
expect_error 2 ply_index_out_of_range.ply ':17:7: face 3 of 4: vertex index 4 out of range' -- "$geotex" segment ply_index_out_of_range.ply "${mesh[@]}"
expect_error 2 ply_negative_index.ply 'negative vertex index -2' -- "$geotex" segment ply_negative_index.ply "${mesh[@]}"
expect_error 2 ply_binary_le_index_out_of_range.ply 'vertex index 7 out of range' -- "$geotex" segment ply_binary_le_index_out_of_range.ply "${mesh[@]}"
expect_error 2 ply_binary_be_negative_index.ply 'negative vertex index -1' -- "$geotex" segment ply_binary_be_negative_index.ply "${mesh[@]}"
expect_error 2 ply_binary_uint_index_wraps.ply 'vertex index 4294967295 out of range' -- "$geotex" segment ply_binary_uint_index_wraps.ply "${mesh[@]}"
expect_error 2 ply_two_corner_face.ply 'polygon with 2 vertices' -- "$geotex" segment ply_two_corner_face.ply "${mesh[@]}"
expect_error 2 ply_nan.ply ':11:5: vertex 1 of 4: non-finite coordinate y = nan' -- "$geotex" segment ply_nan.ply "${mesh[@]}"
expect_error 2 ply_inf.ply 'non-finite coordinate z = -inf' -- "$geotex" segment ply_inf.ply "${mesh[@]}"
expect_error 2 ply_binary_le_nan.ply 'vertex 2 of 4 \(byte 197\): non-finite coordinate y = nan' -- "$geotex" segment ply_binary_le_nan.ply "${mesh[@]}"
expect_error 2 ply_binary_be_inf.ply 'non-finite coordinate x = inf' -- "$geotex" segment ply_binary_be_inf.ply "${mesh[@]}"
# Headers that lie about their size: refused from the header, nothing allocated.
expect_error 2 ply_ascii_huge_faces.ply "1000000000000 'face' elements" -- "$geotex" segment ply_ascii_huge_faces.ply "${mesh[@]}"
expect_error 2 ply_binary_le_huge_faces.ply "1000000000000 'face' elements" -- "$geotex" segment ply_binary_le_huge_faces.ply "${mesh[@]}"
expect_error 2 ply_binary_be_huge_vertices.ply "1000000000000 'vertex' elements" -- "$geotex" segment ply_binary_be_huge_vertices.ply "${mesh[@]}"
expect_error 2 ply_count_overflow.ply 'element count .* is too large' -- "$geotex" segment ply_count_overflow.ply "${mesh[@]}"
expect_error 2 ply_ascii_garbage_body.ply "vertex 0 of 4: expected a number for 'x'" -- "$geotex" segment ply_ascii_garbage_body.ply "${mesh[@]}"
expect_error 2 ply_binary_garbage_body.ply 'vertex 0 of 4' -- "$geotex" segment ply_binary_garbage_body.ply "${mesh[@]}"
expect_error 2 ply_bad_magic.ply "not a PLY file" -- "$geotex" segment ply_bad_magic.ply "${mesh[@]}"
expect_error 2 ply_empty.ply "not a PLY file" -- "$geotex" segment ply_empty.ply "${mesh[@]}"
expect_error 2 ply_zero_faces.ply 'the file has no faces' -- "$geotex" segment ply_zero_faces.ply "${mesh[@]}"
expect_error 2 ply_zero_vertices.ply 'the file has no faces' -- "$geotex" segment ply_zero_vertices.ply "${mesh[@]}"
expect_error 2 ply_all_degenerate.ply 'all 4 triangles .* are degenerate' -- "$geotex" segment ply_all_degenerate.ply "${mesh[@]}"
# The same reader behind annotate and render: no RDF, no picture.
expect_error 2 ply_binary_le_huge_faces.ply 'truncated' -- "$geotex" annotate ply_binary_le_huge_faces.ply --scale 0.1 -o out.ttl --quiet
expect_error 2 ply_negative_index.ply 'negative vertex index' -- "$geotex" render ply_negative_index.ply -o out.png --quiet

# --- OBJ, OFF, STL ------------------------------------------------------------------------------
expect_error 2 obj_short_vertex.obj ":1:5: vertex 0: expected 3 coordinates after 'v', found 2" -- "$geotex" segment obj_short_vertex.obj "${mesh[@]}"
expect_error 2 obj_bad_number.obj "expected a number, got '1.0.0'" -- "$geotex" segment obj_bad_number.obj "${mesh[@]}"
expect_error 2 obj_index_zero.obj 'vertex index 0 is invalid' -- "$geotex" segment obj_index_zero.obj "${mesh[@]}"
expect_error 2 obj_index_beyond.obj ':6:7: face 1: vertex index 5 out of range' -- "$geotex" segment obj_index_beyond.obj "${mesh[@]}"
expect_error 2 obj_relative_out_of_range.obj 'relative vertex index -5 refers before the first vertex' -- "$geotex" segment obj_relative_out_of_range.obj "${mesh[@]}"
expect_error 2 obj_nan.obj "non-finite coordinate 'NaN'" -- "$geotex" segment obj_nan.obj "${mesh[@]}"
expect_error 2 obj_unknown_statement.obj "unknown OBJ statement 'vx'" -- "$geotex" segment obj_unknown_statement.obj "${mesh[@]}"
expect_error 2 obj_no_faces.obj 'the file has no faces' -- "$geotex" segment obj_no_faces.obj "${mesh[@]}"
expect_error 2 obj_empty.obj 'the file has no vertices' -- "$geotex" segment obj_empty.obj "${mesh[@]}"
expect_error 2 off_fewer_vertices.off 'end of file after 2 of 3 vertices' -- "$geotex" segment off_fewer_vertices.off "${mesh[@]}"
expect_error 2 off_fewer_faces.off 'end of file after 2 of 4 faces' -- "$geotex" segment off_fewer_faces.off "${mesh[@]}"
expect_error 2 off_more_faces.off ":11:1: '3' after the last declared face" -- "$geotex" segment off_more_faces.off "${mesh[@]}"
expect_error 2 off_truncated.off 'end of file after 3 of 4 faces' -- "$geotex" segment off_truncated.off "${mesh[@]}"
expect_error 2 off_missing_header.off 'expected the keyword OFF' -- "$geotex" segment off_missing_header.off "${mesh[@]}"
expect_error 2 off_negative_count.off "vertex count must be a non-negative integer" -- "$geotex" segment off_negative_count.off "${mesh[@]}"
expect_error 2 off_index_out_of_range.off ':10:7: face 3: vertex index 9 out of range' -- "$geotex" segment off_index_out_of_range.off "${mesh[@]}"
expect_error 2 off_huge_counts.off 'declares 2147483647 vertices and 2147483647 faces' -- "$geotex" segment off_huge_counts.off "${mesh[@]}"
expect_error 2 off_count_too_large.off "face count must be a non-negative integer below 2\^31" -- "$geotex" segment off_count_too_large.off "${mesh[@]}"
expect_error 2 off_empty.off 'end of file in the OFF header' -- "$geotex" segment off_empty.off "${mesh[@]}"
expect_error 2 stl_ascii_truncated.stl "facet 3: expected 3 coordinates after 'vertex'" -- "$geotex" segment stl_ascii_truncated.stl "${mesh[@]}"
expect_error 2 stl_ascii_two_corners.stl 'facet 0: 2 vertices' -- "$geotex" segment stl_ascii_two_corners.stl "${mesh[@]}"
expect_error 2 stl_binary_count_mismatch.stl 'declares 100 triangles, which need 5084 bytes, but the file has 284' -- "$geotex" segment stl_binary_count_mismatch.stl "${mesh[@]}"
expect_error 2 stl_binary_huge_count.stl 'declares 4294967295 triangles' -- "$geotex" segment stl_binary_huge_count.stl "${mesh[@]}"
expect_error 2 stl_binary_nan.stl 'triangle 3 of 4 \(byte 246\): non-finite' -- "$geotex" segment stl_binary_nan.stl "${mesh[@]}"
expect_error 2 stl_no_facets.stl 'the file has no faces' -- "$geotex" segment stl_no_facets.stl "${mesh[@]}"
expect_error 2 stl_short.stl 'too short \(40 bytes\)' -- "$geotex" segment stl_short.stl "${mesh[@]}"
expect_error 2 nosuch.ply 'No such file' -- "$geotex" segment nosuch.ply "${mesh[@]}"
expect_error 2 mesh.xyz "unknown mesh extension '.xyz'" -- "$geotex" segment mesh.xyz "${mesh[@]}"
mkdir dir.ply
expect_error 2 dir.ply 'is a directory' -- "$geotex" segment dir.ply "${mesh[@]}"
# A pipe would block the open, a device never end (issue 17): refused before opening.
mkfifo fifo.ply; ln -s /dev/zero zero.obj
expect_error 2 fifo.ply 'it is a pipe \(FIFO\), not a regular file' -- timeout 60 "$geotex" segment fifo.ply "${mesh[@]}"
expect_error 2 fifo.ply 'it is a pipe \(FIFO\), not a regular file' -- timeout 60 "$geotex" annotate fifo.ply --scale 0.1 -o fifo.ttl
expect_error 2 zero.obj 'it is a device, not a regular file' -- timeout 60 "$geotex" segment zero.obj "${mesh[@]}"

# --- dictionaries: annotate --dictionary and dict check -------------------------------------------
dictionary_cases=(
  "dict_wrong_type.yaml|:13:18: .*lower bound 'low' is not a number"
  "dict_interval_scalar.yaml|:13:.*interval"
  "dict_overlap.yaml|:13:17: .*overlaps \[0, 0.1\) of 'circular'"
  "dict_unknown_key.yaml|:14:7: .*unknown key 'lables'.*did you mean 'labels'"
  "dict_unknown_feature.yaml|:8:3: .*unknown feature 'contour_sphericty'"
  "dict_lower_above_upper.yaml|:13:17: .*the lower bound must be below the upper bound"
  "dict_invalid_utf8.yaml|:14:22: .*invalid UTF-8"
  "dict_latin1.yaml|:14:32: .*invalid UTF-8 .*0xE9"
  "dict_syntax_error.yaml|:14:13: .*YAML syntax error"
  "dict_empty.yaml|:1:1: .*empty dictionary"
  "dict_duplicate_label.yaml|:18:20: .*label 'circular' in 'en' is also the label of concept 'circular' at line 15, column 20"
  "dict_feature_in_no_facet.yaml|:12:3: .*'contour_sphericity' has concepts but is in no facet"
  "dict_feature_in_two_facets.yaml|:13:16: .*'contour_sphericity' is in two facets"
  "dict_facet_unknown_feature.yaml|:10:36: .*unknown feature 'contour_sphericty' in facet 'outline'; did you mean 'contour_sphericity'"
  "dict_facet_no_features.yaml|:10:15: .*facet 'outline' has no features"
  "dict_facet_label_missing.yaml|:9:13: .*facet 'outline': labels: no text in 'en'"
  "dict_facet_unknown_key.yaml|:9:5: .*unknown key 'lables' in a facet.*did you mean 'labels'"
  "dict_unknown_relief.yaml|:19:15: .*unknown relief 'convex'"
  "dict_bound_digits.yaml|:10:21: .*upper bound '0\.10*1' has 55 significant digits; a bound has at most 15"
  "dict_control_key.yaml|:8:3: .*unknown feature 'contour[\\]x1b\[2J[\\]x07[\\]x0asphericity'"
)
for entry in "${dictionary_cases[@]}"; do
  file=${entry%%|*}
  problem=${entry#*|}
  expect_error 2 "$file" "$problem" -- "$geotex" annotate s.ply --scale 0.1 --dictionary "$file" -o out.ttl --quiet
  expect_check_error "$file" "$problem" "$file"
done
# Control characters of user text never reach the terminal raw (only tab and newline ending
# the lines are allowed in the output).
for cmd in "dict check dict_control_key.yaml" "annotate s.ply --scale 0.1 --dictionary dict_control_key.yaml -o out.ttl"; do
  # shellcheck disable=SC2086
  "$geotex" $cmd >/dev/null 2>err.txt
  ! LC_ALL=C grep -q -P '[\x00-\x08\x0b-\x1f\x7f]' err.txt || fail "$cmd: control characters on stderr: $(od -c err.txt | head -5)"
done
expect_error 2 nosuch.yaml 'cannot open \(No such file or directory\)' -- "$geotex" annotate s.ply --scale 0.1 --dictionary nosuch.yaml -o out.ttl
expect_error 2 nosuch.yaml 'cannot open \(No such file or directory\)' -- "$geotex" dict check nosuch.yaml
expect_error 2 adir 'is a directory' -- "$geotex" annotate s.ply --scale 0.1 --dictionary adir -o out.ttl
expect_error 2 adir 'is a directory' -- "$geotex" dict check adir
expect_error 2 dict_overlap.yaml 'overlaps' -- "$geotex" dict skos dict_overlap.yaml -o out.ttl --quiet

# --- ground truths for evaluate ---------------------------------------------------------------
expect_error 2 truth_face_count.json 'has 2 faces but seg.ply has 4' -- "$geotex" evaluate seg.ply truth_face_count.json --json out.json --quiet
expect_error 2 truth_shape_range.json 'face 1 has shape 7' -- "$geotex" evaluate seg.ply truth_shape_range.json --json out.json --quiet
expect_error 2 truth_syntax.json 'not valid JSON' -- "$geotex" evaluate seg.ply truth_syntax.json --quiet
expect_error 2 truth_wrong_type.json 'malformed ground truth' -- "$geotex" evaluate seg.ply truth_wrong_type.json --quiet
expect_error 2 nosuch.json 'cannot open' -- "$geotex" evaluate seg.ply nosuch.json --quiet
expect_error 2 adir 'is a directory' -- "$geotex" evaluate seg.ply adir --quiet
expect_error 2 seg_no_texel.ply "no face property 'texel'" -- "$geotex" evaluate seg_no_texel.ply truth_good.json --quiet

# --- command-line options (without --quiet: nothing else may reach stderr first) ---------------
seg=("$geotex" segment s.ply)
ann=("$geotex" annotate s.ply --scale 0.1)
expect_error 1 --frobnicate 'not expected' -- "${seg[@]}" --scale 0.1 -o out.ply --frobnicate
expect_error 1 --output 'is required' -- "${seg[@]}" --scale 0.1
expect_error 1 mesh 'is required' -- "$geotex" segment --scale 0.1 -o out.ply
expect_error 1 subcommand 'required' -- "$geotex" frobnicate
expect_error 1 --scale 'give exactly one of --scale .* or --radius' -- "${seg[@]}" -o out.ply
expect_error 1 --scale 'give exactly one of --scale .* or --radius' -- "${seg[@]}" --scale 0.1 --radius 1 -o out.ply
for bad in 0 1 -0.1 1.5 ''; do
  expect_error 1 --scale "must be in \(0, 1\)" -- "${seg[@]}" --scale "$bad" -o out.ply
done
expect_error 1 --scale "'abc' is neither a number nor auto" -- "${seg[@]}" --scale abc -o out.ply
expect_error 1 --scale "'0.1x' is neither a number nor auto" -- "${seg[@]}" --scale 0.1x -o out.ply
expect_error 1 --scale "exactly one of --scale" -- "${seg[@]}" --scale auto --radius 1 -o out.ply
for bad in 0 -2; do
  expect_error 1 --radius 'must be positive and finite' -- "${seg[@]}" --radius "$bad" -o out.ply
done
expect_error 1 --orientation 'sideways' -- "${seg[@]}" --scale 0.1 --orientation sideways -o out.ply
expect_error 1 --orientation '2 not in' -- "${seg[@]}" --scale 0.1 --orientation 2 -o out.ply   # the enum's number is no name
expect_error 1 --smoothing '0 not in' -- "${seg[@]}" --scale 0.1 --smoothing 0 -o out.ply
expect_error 1 --smoothing 'median' -- "${seg[@]}" --scale 0.1 --smoothing median -o out.ply
expect_error 1 --min-faces 'not in range' -- "${seg[@]}" --scale 0.1 --min-faces 0 -o out.ply
for bad in 0 -1 abc; do
  expect_error 1 --threads 'not in range' -- "${seg[@]}" --scale 0.1 -o out.ply --threads "$bad"
done
expect_error 1 --format 'turtel not in' -- "${ann[@]}" --format turtel -o out.ttl
expect_error 1 --lang "'e n' is not a language tag" -- "${ann[@]}" --lang 'e n' -o out.ttl
expect_error 1 --lang "'' is not a language tag" -- "${ann[@]}" --lang '' -o out.ttl
expect_error 1 --lang "is not a language tag" -- "${ann[@]}" --lang 'en_US' -o out.ttl
expect_error 1 --base 'not absolute' -- "${ann[@]}" --base 'no-scheme/' -o out.ttl
expect_error 1 --base "base IRI" -- "${ann[@]}" --base 'https://example.org/a b/' -o out.ttl
expect_error 1 --base "base IRI" -- "${ann[@]}" --base 'https://example.org/no-end' -o out.ttl
expect_error 1 --concepts 'not in range' -- "${ann[@]}" --concepts 21 -o out.ttl
expect_error 1 --concepts 'not in range' -- "${ann[@]}" --concepts -1 -o out.ttl
expect_error 1 --min-agreement '0 not in .0, 1.' -- "${ann[@]}" --min-agreement 0 -o out.ttl
expect_error 1 --max-significance 'not a number' -- "${ann[@]}" --max-significance half -o out.ttl
expect_error 1 --resamples 'not in range' -- "${ann[@]}" --resamples -5 -o out.ttl
for bad in yesterday 2026-01-01T00:00:00+25:00 9999-99-99T99:99:99Z 2026-02-30T12:00:00Z 2023-02-29T12:00:00Z \
  2026-01-01T24:00:00Z 2026-01-01T00:00:00-14:30 2026-01-01T00:00:00+05:60 2026-01-01T00:00:00. 12026-01-01T00:00:00Z; do
  expect_error 1 --timestamp 'not an xsd:dateTime' -- "${ann[@]}" --timestamp "$bad" -o out.ttl
done
for good in 2024-02-29T23:59:59Z 2026-01-01T00:00:00+14:00 2026-01-01T00:00:00-14:00 2026-06-30T12:30:00.25 2000-02-29T00:00:00+05:30; do
  cases=$((cases + 1))
  "${ann[@]}" --timestamp "$good" -o good.ttl --quiet >/dev/null 2>err.txt && grep -q -F "\"$good\"^^" good.ttl ||
    fail "--timestamp $good refused or not written: $(cat err.txt)"
  rm -f good.ttl
done
# A newline (or an escape) in an option value stays on the error's one line, escaped.
expect_error 1 --lang 'a\\x0ab\\x1b\[31m' -- "${ann[@]}" --lang $'a\nb\e[31m' -o out.ttl
expect_error 1 'not expected' 'x\\x0ay' -- "${seg[@]}" --scale 0.1 -o out.ply $'x\ny'
expect_error 1 --output 'empty file name' -- "${seg[@]}" --scale 0.1 -o ''
expect_error 1 './out.ply' '--output and --json name the same file' -- "${seg[@]}" --scale 0.1 -o out.ply --json ./out.ply
expect_error 1 'out.ply' '--output and --truth name the same file' -- "$geotex" synth -o out.ply --truth out.ply
# Outputs that cannot be written: refused before any work, no file anywhere.
expect_error 4 no/such/dir/out.ply 'No such file or directory' -- "${seg[@]}" --scale 0.1 -o no/such/dir/out.ply
expect_error 4 no/such/dir/out.json 'No such file or directory' -- "${seg[@]}" --scale 0.1 -o out.ply --json no/such/dir/out.json
expect_error 4 no/out.ttl 'No such file or directory' -- "${ann[@]}" -o out.ttl --segmentation no/out.ttl
expect_error 4 s.ply/out.ply 'is not a directory' -- "${seg[@]}" --scale 0.1 -o s.ply/out.ply
expect_error 4 adir 'is a directory' -- "${seg[@]}" --scale 0.1 -o adir
expect_error 4 adir/ 'is a directory' -- "${ann[@]}" -o adir/
expect_error 4 adir 'is a directory' -- "$geotex" dict skos dict_good.yaml -o adir
expect_error 4 no/x.png 'No such file or directory' -- "$geotex" render s.ply -o no/x.png
if [ "$(id -u)" -ne 0 ]; then
  mkdir locked && chmod 555 locked
  expect_error 4 locked/out.ply 'Permission denied' -- "${seg[@]}" --scale 0.1 -o locked/out.ply
  expect_error 4 locked/out.ttl 'Permission denied' -- "${ann[@]}" -o locked/out.ttl
else
  echo "note: running as root, which can write anywhere: the unwritable-directory cases are skipped"
fi

# Every floating option of every subcommand (found in the --help texts, where CLI11 names their
# type FLOAT) refuses NaN and infinities at parse time: exit 1 naming the option, before any
# work (the inputs exist, so only the option can stop the run).
subcommands() { "$geotex" "$@" --help | sed -n '/^Subcommands:/,/^$/p' | sed -n 's/^  \([a-z]\+\) .*/\1/p'; }
float_options() {
  "$geotex" "$@" --help | sed -n 's/^ *\(-[a-z],\)\?\(--[a-z0-9-]\+\) FLOAT.*/\2/p'
}
num_float_options=0
for sub in $(subcommands); do
  for path in "$sub" $(subcommands "$sub" | sed "s/^/$sub /"); do
    # shellcheck disable=SC2086
    for option in $(float_options $path); do
      num_float_options=$((num_float_options + 1))
      for bad in nan -nan NaN inf -inf Infinity 1e999; do
        # shellcheck disable=SC2086
        expect_error 1 "$option" "not a finite number: '$bad'" -- "$geotex" $path "$option=$bad"
      done
    done
  done
done
# The options of issue 17 among them, so that the enumeration cannot silently find nothing.
[ "$num_float_options" -ge 28 ] || fail "only $num_float_options floating options found in the --help texts"
for bad in nan inf; do
  expect_error 1 --min-depth "not a finite number" -- "${seg[@]}" --scale 0.1 -o out.ply --min-depth "$bad"
  expect_error 1 --merge-overlap "not a finite number" -- "${ann[@]}" -o out.ttl --merge-overlap "$bad"
  expect_error 1 --curvature-scale "not a finite number" -- "${seg[@]}" --scale 0.1 -o out.ply --curvature-scale "$bad"
  expect_error 1 --scale "not a finite number" -- "${seg[@]}" --scale "$bad" -o out.ply
  expect_error 1 --radius "not a finite number" -- "${seg[@]}" --radius "$bad" -o out.ply
  expect_error 1 --timeout "not a finite number" -- "$geotex" publish adir --nquads out.nq --timeout "$bad"
done

[ "$cases" -ge 40 ] || fail "only $cases cases"
[ "$failures" -eq 0 ] && echo "corpus tests passed ($cases cases)" || { echo "$failures of $cases corpus case(s) failed"; exit 1; }
