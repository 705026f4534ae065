#!/usr/bin/env bash
# The workbench of `geotex view` in a real browser (issue 19): a small batch output, the server
# on a free port, tests/js/workbench.mjs driving Debian's Chromium through puppeteer-core (the
# list, an object opened by its link, the texture colours in a screenshot, a click on a face,
# a bound moved and a label renamed, a bad edit, a save, fitting), then Ctrl-C and the saved
# dictionary checked here: `geotex dict check` passes, the version changed, and only the edited
# spans of the YAML changed.
# Usage: tests/workbench_test.sh path/to/geotex SOURCE_DIR
. "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"

# scripts/setup-deps.sh installs both; a missing one is a failure, not a skip.
[ -x /usr/bin/chromium ] || { echo "FAIL: /usr/bin/chromium missing (run scripts/setup-deps.sh)"; exit 1; }
[ -d "$src/tests/js/node_modules/puppeteer-core" ] ||
    { echo "FAIL: tests/js/node_modules/puppeteer-core missing (run scripts/setup-deps.sh)"; exit 1; }

# Four objects with raised and engraved shapes (two textures each, words that differ); the
# fourth's report.json is then damaged: it must be listed with its error, the others work.
mkdir meshes
for i in 1 2 3 4; do
    "$geotex" synth -q --level 5 --layout-seed "$i" --engraved 0.3 -o "meshes/obj-$i.ply" >/dev/null ||
        fail "synth obj-$i"
done
rm -f meshes/*.truth.json
cp "$src/dictionaries/default.yaml" dict.yaml
cp dict.yaml dict-before.yaml
"$geotex" batch meshes -o out --scale 0.05 --dictionary dict.yaml -q >/dev/null 2>batch.err ||
    { cat batch.err; fail "batch"; finish workbench; }
head -c 200 out/objects/obj-4/report.json >damaged && mv damaged out/objects/obj-4/report.json

# start_view NAME ARGS...: `geotex view ARGS` in the background; sets $pid_NAME and $url_NAME.
start_view() {
    local name=$1 url= pid
    shift
    "$geotex" view "$@" --port 0 >"view-$name.out" 2>"view-$name.err" &
    pid=$!
    for _ in $(seq 100); do
        url=$(sed -n 's/^geotex view: \(http[^ ]*\).*/\1/p' "view-$name.out")
        [ -n "$url" ] && break
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    printf -v "pid_$name" %s "$pid"
    printf -v "url_$name" %s "$url"
    [ -n "$url" ] && return 0
    cat "view-$name.out" "view-$name.err"
    kill -INT "$pid" 2>/dev/null
    fail "geotex view $* printed no URL"
    finish workbench
}
# stop_view NAME: Ctrl-C, and a clean exit 0.
stop_view() {
    local pid_var=pid_$1 rc=0
    kill -INT "${!pid_var}"
    wait "${!pid_var}" || rc=$?
    [ "$rc" = 0 ] || { cat "view-$1.err"; fail "geotex view ($1) exited $rc on SIGINT, expected 0"; }
}
start_view edit out --dictionary dict.yaml
start_view readonly out

start=$(date +%s%N)
node "$src/tests/js/workbench.mjs" "$url_edit" out result.json "$url_readonly" || fail "browser checks (above)"
echo "browser checks took $((($(date +%s%N) - start) / 1000000)) ms"
stop_view edit
stop_view readonly

# The saved dictionary: valid, a new version, the edits in it, the rest of the text untouched.
"$geotex" dict check dict.yaml >check.out 2>&1 || { cat check.out; fail "geotex dict check on the saved dictionary"; }
[ -f result.json ] || { fail "the browser test wrote no result"; finish workbench; }
/usr/bin/python3 - result.json dict-before.yaml dict.yaml <<'PY' || fail "saved dictionary (above)"
import json, math, sys, yaml
result = json.load(open(sys.argv[1]))
before_text, after_text = open(sys.argv[2]).read(), open(sys.argv[3]).read()
after = yaml.safe_load(after_text)
problems = []
if str(after['scheme']['version']) != result['version']:
    problems.append(f"file version {after['scheme']['version']}, page said {result['version']}")
if result['version'] == result['version_before']:
    problems.append('the version did not change')
concepts = {c['id']: c for f in after['features'].values() for c in f}
if 'bound' in result:
    b = result['bound']
    got = concepts[b['concept']]['interval'][0 if b['side'] == 'lower' else 1]
    if not math.isclose(float(got), float(b['value']), rel_tol=1e-12):
        problems.append(f"{b['concept']} {b['side']} is {got}, saved {b['value']}")
if 'label' in result:
    got = concepts[result['label']['concept']]['labels']['en']
    if got != result['label']['value']:
        problems.append(f"label of {result['label']['concept']} is {got!r}")
# Only the edited spans change: the same lines, and those that differ are the version,
# the modification date, the moved bound's interval lines (the concept's and its
# neighbour's) and the renamed label's line.
bl, al = before_text.split('\n'), after_text.split('\n')
if len(bl) != len(al):
    problems.append(f'{len(bl)} lines before, {len(al)} after')
else:
    diff = [(x, y) for x, y in zip(bl, al) if x != y]
    kinds = {'version:': 0, 'modified:': 0, 'interval:': 0, 'labels:': 0}
    for x, y in diff:
        kind = next((k for k in kinds if k in y), None)
        if kind is None:
            problems.append(f'unexpected change: {x!r} -> {y!r}')
        else:
            kinds[kind] += 1
    if kinds['interval:'] > 2 or kinds['labels:'] > 1 or kinds['version:'] != 1:
        problems.append(f'changed lines: {kinds}')
for p in problems:
    print('saved dictionary:', p)
sys.exit(1 if problems else 0)
PY

finish workbench
