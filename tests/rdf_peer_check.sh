#!/bin/sh
# Independent check of a Turtle file written by geotex, with parsers and a validator that
# share no code with Raptor2:
#   tests/rdf_peer_check.sh FILE.ttl SHAPES.ttl [MORE_DATA.ttl ...]
# 1. rdflib (Debian's python3-rdflib, through /usr/bin/python3) parses FILE.ttl;
# 2. rapper (raptor2-utils) parses it;
# 3. N3.js parses it as strict Turtle (tests/js);
# 4. the three agree on the number of distinct triples;
# 5. rdf-validate-shacl finds that FILE.ttl (merged with MORE_DATA.ttl, if any) conforms to
#    SHAPES.ttl.
# Needs: python3-rdflib, raptor2-utils, nodejs, npm; then once `npm ci --prefix tests/js`.
# Exit status 0 when every check passes, 1 otherwise (the failing check is named on stderr).

set -u

fail() {
    echo "rdf_peer_check: FAILED: $*" >&2
    exit 1
}

[ $# -ge 2 ] || fail "usage: $0 FILE.ttl SHAPES.ttl [MORE_DATA.ttl ...]"
file=$1
shapes=$2
shift 2
for f in "$file" "$shapes" "$@"; do
    [ -r "$f" ] || fail "cannot read $f"
done
js_dir=$(cd "$(dirname "$0")/js" && pwd) || fail "tests/js not found next to $0"

# 1. rdflib. Only the system Python sees Debian's rdflib.
[ -x /usr/bin/python3 ] || fail "/usr/bin/python3 not found"
rdflib_count=$(/usr/bin/python3 - "$file" <<'EOF'
import sys
try:
    import rdflib
except ImportError:
    sys.exit("rdflib is missing: apt-get install -y python3-rdflib")
graph = rdflib.Graph()
try:
    graph.parse(sys.argv[1], format="turtle")
except Exception as e:  # rdflib raises several unrelated types on syntax errors
    sys.exit("rdflib: %s: %s" % (sys.argv[1], e))
print(len(graph))
EOF
) || fail "rdflib could not parse $file"
echo "rdflib: $file: $rdflib_count triples"

# 2. rapper. Its N-Triples output has one triple per line; duplicates are counted once,
# as rdflib and N3.js count them.
command -v rapper >/dev/null 2>&1 || fail "rapper not found: apt-get install -y raptor2-utils"
tmp=$(mktemp -d) || fail "mktemp"
trap 'rm -rf "$tmp"' EXIT
if ! rapper -q -i turtle -o ntriples "$file" >"$tmp/out.nt" 2>"$tmp/rapper.err"; then
    cat "$tmp/rapper.err" >&2
    fail "rapper could not parse $file"
fi
if [ -s "$tmp/rapper.err" ]; then
    cat "$tmp/rapper.err" >&2
    fail "rapper reported problems in $file"
fi
rapper_all=$(wc -l <"$tmp/out.nt" | tr -d ' ')
rapper_count=$(LC_ALL=C sort -u "$tmp/out.nt" | wc -l | tr -d ' ')
echo "rapper: $file: $rapper_count triples ($rapper_all statements)"

# 3. N3.js (strict Turtle) and 5. rdf-validate-shacl.
command -v node >/dev/null 2>&1 || fail "node not found: apt-get install -y nodejs npm"
[ -d "$js_dir/node_modules/n3" ] && [ -d "$js_dir/node_modules/rdf-validate-shacl" ] ||
    fail "npm packages missing: run  npm ci --prefix $js_dir"
node "$js_dir/validate.mjs" "$file" "$shapes" "$@" >"$tmp/node.out" 2>"$tmp/node.err"
node_status=$?
cat "$tmp/node.out"
cat "$tmp/node.err" >&2
n3_count=$(sed -n 's/^n3-triples=//p' "$tmp/node.out")
[ -n "$n3_count" ] || fail "N3.js could not parse $file"

# 4. The same triples for everyone.
if [ "$rdflib_count" != "$rapper_count" ] || [ "$rapper_count" != "$n3_count" ]; then
    fail "triple counts differ: rdflib $rdflib_count, rapper $rapper_count, N3.js $n3_count"
fi
echo "triple counts agree: $rapper_count"

[ "$node_status" -eq 0 ] || fail "SHACL validation of $file against $shapes"
echo "rdf_peer_check: OK: $file"
