#!/usr/bin/env bash
# `geotex dict fit` on a real batch output: marks that hold move nothing; a texture marked with
# the neighbouring concept of its word gets it after the fit, checked by annotating the batch
# again with the new dictionary (the batch's own words, not the fit's); the new dictionary is
# clean and a new version; contradictory marks are listed with exit 5; bad rows and a PATH
# that is no batch are one-line errors that write nothing.
#   tests/dict_fit_test.sh GEOTEX SOURCE_DIR
set -u
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
export SOURCE_DATE_EPOCH=1767225600  # 2026-01-01

mkdir meshes
for s in 1 2 3; do
  "$geotex" synth -o meshes/s$s.ply --level 4 --layout-seed $s --engraved 0.3 >/dev/null 2>&1 || fail "synth $s"
done
cp "$src/dictionaries/default.yaml" dict.yaml
"$geotex" batch meshes -o out --scale 0.08 --orientation both --dictionary dict.yaml --quiet >/dev/null || fail "batch"

# 1. Every word of every texture marked yes: nothing to move, the dictionary comes out as it was.
/usr/bin/python3 - out >same.csv <<'PY'
import json, os, sys
print("object,texture,concept,answer")
for o in sorted(os.listdir(os.path.join(sys.argv[1], "objects"))):
    r = json.load(open(os.path.join(sys.argv[1], "objects", o, "report.json")))
    for t in r["annotation"]["textures"]:
        for c in t["concepts"]:
            print(f"{o},{t['texture']},{c['concept']},yes")
PY
[ "$(wc -l <same.csv)" -gt 3 ] || fail "too few words in the batch to test"
"$geotex" dict fit same.csv --from out --dictionary dict.yaml -o same.yaml --quiet >same.txt
[ $? -eq 0 ] || fail "marks that hold: exit status not 0"
cmp -s dict.yaml same.yaml || fail "marks that hold changed the dictionary"
[ -s same.txt ] && { cat same.txt; fail "marks that hold printed moves or problems"; }

# 2. One texture marked with the concept next to its word (same feature, shared bound).
/usr/bin/python3 - out dict.yaml >move.txt <<'PY'
import json, os, sys, yaml
d = yaml.safe_load(open(sys.argv[2]))
def bound(x):
    return float(x)
neighbours = {}
for feature, concepts in d["features"].items():
    cs = sorted(concepts, key=lambda c: bound(c["interval"][0]))
    for a, b in zip(cs, cs[1:]):
        if bound(a["interval"][1]) == bound(b["interval"][0]):
            neighbours[a["id"]] = (b["id"], "up")
            neighbours[b["id"]] = (a["id"], "down")
for o in sorted(os.listdir(os.path.join(sys.argv[1], "objects"))):
    r = json.load(open(os.path.join(sys.argv[1], "objects", o, "report.json")))
    for t in r["annotation"]["textures"]:
        for c in t["concepts"]:
            if c["concept"] in neighbours:
                n, _ = neighbours[c["concept"]]
                print(o, t["texture"], c["concept"], n, c["feature"], repr(c["value"]))
                sys.exit(0)
PY
read -r obj tex word other feature value <move.txt || fail "no word with a neighbouring concept"
printf '%s,%s,%s,yes\n%s,%s,%s,no\n' "$obj" "$tex" "$other" "$obj" "$tex" "$word" >move.csv
"$geotex" dict fit move.csv --from out --dictionary dict.yaml -o moved.yaml --quiet >moved.txt
status=$?
[ $status -eq 0 ] || [ $status -eq 5 ] || fail "fit: exit status $status"
grep -q "^moved: " moved.txt || { cat moved.txt; fail "no bound moved"; }
grep -q "unsatisfied" moved.txt && { cat moved.txt; fail "a satisfiable mark listed unsatisfied"; }
"$geotex" dict check moved.yaml >check.txt || { cat check.txt; fail "the fitted dictionary is not clean"; }
grep -q '^  version: "2.1"$' moved.yaml || fail "version not bumped to 2.1"
grep -q '^  modified: 2026-01-01 ' moved.yaml || fail "modified not set to SOURCE_DATE_EPOCH's day"
# only version, modified and the two intervals of the shared bound changed
[ "$(diff dict.yaml moved.yaml | grep -c '^>')" -eq 4 ] || { diff dict.yaml moved.yaml; fail "other lines changed"; }
# the value now lies in the other concept's interval
/usr/bin/python3 - moved.yaml "$feature" "$other" "$value" <<'PY' || fail "the value is not in the new interval"
import sys, yaml
d = yaml.safe_load(open(sys.argv[1]))
v = float(sys.argv[4])
c = [c for c in d["features"][sys.argv[2]] if c["id"] == sys.argv[3]][0]
lo, hi = (float(x) for x in c["interval"])
sys.exit(0 if lo <= v < hi else 1)
PY
# independent check: the batch itself, run again with the new dictionary (its geometry cached)
if [ $status -eq 0 ]; then
  "$geotex" batch meshes -o out --scale 0.08 --orientation both --dictionary moved.yaml --quiet >/dev/null || fail "batch with moved.yaml"
  /usr/bin/python3 - "out/objects/$obj/report.json" "$tex" "$other" "$word" <<'PY' || fail "the batch does not give the marked word"
import json, sys
r = json.load(open(sys.argv[1]))
t = [t for t in r["annotation"]["textures"] if t["texture"] == int(sys.argv[2])][0]
words = [c["concept"] for c in t["concepts"]]
sys.exit(0 if sys.argv[3] in words and sys.argv[4] not in words else 1)
PY
fi

# 3. Contradictory marks: both listed, exit 5, the dictionary still written (unchanged).
printf '%s,%s,%s,yes\n%s,%s,%s,no\n' "$obj" "$tex" "$word" "$obj" "$tex" "$word" >contra.csv
"$geotex" dict fit contra.csv --from out --dictionary dict.yaml -o contra.yaml --quiet >contra.txt
[ $? -eq 5 ] || fail "contradictory marks: exit status not 5"
[ "$(grep -c 'unsatisfied: .*marked yes and no' contra.txt)" -eq 2 ] || { cat contra.txt; fail "contradictory marks not both listed"; }
grep -q '^contra.csv:1: unsatisfied' contra.txt || fail "the place of the mark is not file:line"
cmp -s dict.yaml contra.yaml || fail "contradictory marks changed the dictionary"

# 4. Errors: one line naming the place, exit 2, nothing written.
printf 'object,texture,concept,answer\n%s,x,%s,yes\n' "$obj" "$word" >bad.csv
"$geotex" dict fit bad.csv --from out -o bad.yaml 2>err.txt
[ $? -eq 2 ] || fail "bad texture: exit status not 2"
grep -q "^geotex: error: bad.csv:2: texture 'x' is not a texture id" err.txt || { cat err.txt; fail "bad texture message"; }
printf '%s,0,%s,maybe\n' "$obj" "$word" >bad2.csv
"$geotex" dict fit bad2.csv --from out -o bad.yaml 2>err.txt
[ $? -eq 2 ] && grep -q "bad2.csv:1: 'maybe' is neither yes nor no" err.txt || fail "bad answer"
printf '%s,0,%s\n' "$obj" "$word" >bad3.csv
"$geotex" dict fit bad3.csv --from out -o bad.yaml 2>err.txt
[ $? -eq 2 ] && grep -q "bad3.csv:1: 3 fields; expected 4" err.txt || fail "bad field count"
"$geotex" dict fit same.csv --from meshes -o bad.yaml 2>err.txt
[ $? -eq 2 ] && grep -q "meshes: neither a geotex batch output (no summary.csv)" err.txt || { cat err.txt; fail "PATH that is no batch"; }
[ "$(wc -l <err.txt)" -eq 1 ] || fail "more than one line for a PATH that is no batch"
[ -e bad.yaml ] && fail "an output was written on error"
# An output that is an input of the fit, or no file at all: a usage error, nothing written.
cp same.csv same.before
cp dict.yaml dict.before
"$geotex" dict fit same.csv --from out -o same.csv 2>err.txt
[ $? -eq 1 ] && grep -q "is the same file as the input EXAMPLES" err.txt || { cat err.txt; fail "-o EXAMPLES"; }
cmp -s same.csv same.before || fail "-o EXAMPLES changed the examples"
"$geotex" dict fit same.csv --from out --dictionary dict.yaml -o dict.yaml 2>err.txt
[ $? -eq 1 ] && grep -q "is the same file as the input --dictionary" err.txt || { cat err.txt; fail "-o the dictionary"; }
cmp -s dict.yaml dict.before || fail "-o the dictionary changed it"
"$geotex" dict fit same.csv --from out -o '' 2>err.txt
[ $? -eq 1 ] && grep -q -- "--output: empty file name" err.txt || { cat err.txt; fail "empty -o"; }

finish dict_fit
