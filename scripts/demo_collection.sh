#!/usr/bin/env bash
# make demo-collection: a small synthetic collection (36 spheres whose shapes, sizes and
# reliefs vary), annotated by `geotex batch`, published into a private Virtuoso started on
# loopback from out/demo-collection/store, and one cross-object question answered by the
# store: which objects carry circular textures (ontology/queries/objects-with-concept.rq).
# The store is stopped at the end; rerunning skips the up-to-date objects.
set -euo pipefail
geotex=$(readlink -f "${1:-build/geotex}")
out=${2:-out/demo-collection}
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/meshes"

echo "== 1. a collection of 36 synthetic objects (icosphere level 5, 20,480 faces each)"
for i in $(seq 1 36); do
  f="$out/meshes/object-$(printf %02d "$i").ply"
  [ -s "$f" ] && continue
  case $((i % 4)) in  # four families: discs, squares, strokes (rectangles + small discs), all
    0) kinds=(--big-discs 20 --small-discs 0 --squares 0 --rectangles 0) ;;
    1) kinds=(--big-discs 0 --small-discs 0 --squares 20 --rectangles 0) ;;
    2) kinds=(--big-discs 0 --small-discs 25 --squares 0 --rectangles 15) ;;
    3) kinds=() ;;
  esac
  "$geotex" synth -q --level 5 --layout-seed "$i" "${kinds[@]}" \
    --displacement "0.0$((15 + i % 4 * 5))" -o "$f" >/dev/null
  rm -f "${f%.ply}.truth.json"
done
ls "$out/meshes" | head -n 3; echo "... ($(ls "$out/meshes" | wc -l) meshes)"

echo
echo "== 2. geotex batch (both cores, resumable; summary in $out/batch/summary.csv)"
"$geotex" batch "$out/meshes" -o "$out/batch" --scale 0.08 \
  --base-template 'https://collection.example.org/object/{id}/'

echo
echo "== 3. a private Virtuoso on loopback, and geotex publish (one named graph per object)"
read -r port_sql port_http < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
"$src/scripts/virtuoso.sh" start "$out/store" "$port_sql" "$port_http"
trap '"$src/scripts/virtuoso.sh" stop "$out/store" >/dev/null 2>&1 || true' EXIT
"$geotex" publish "$out/batch" --endpoint "http://127.0.0.1:$port_http/sparql-graph-crud" --graph-per-object --quiet | tail -n 1

echo
echo "== 4. asked of the store: which objects carry a texture labelled 'circular shape'?"
python3 - "http://127.0.0.1:$port_http/sparql" "$src/ontology/queries/objects-with-concept.rq" <<'PY'
import json, sys, urllib.parse, urllib.request
endpoint, query_file = sys.argv[1], sys.argv[2]
query = open(query_file, encoding="utf-8").read()
request = urllib.request.Request(endpoint, data=urllib.parse.urlencode({"query": query}).encode(),
                                 headers={"Accept": "application/sparql-results+json"})
result = json.load(urllib.request.urlopen(request, timeout=60))
names = result["head"]["vars"]
rows = [[b.get(n, {}).get("value", "") for n in names] for b in result["results"]["bindings"]]
widths = [max([len(n)] + [len(r[i]) for r in rows]) for i, n in enumerate(names)]
print("  ".join(n.ljust(w) for n, w in zip(names, widths)))
for r in rows:
    print("  ".join(v.ljust(w) for v, w in zip(r, widths)))
print(f"({len(rows)} of the 36 objects)")
PY
echo
echo "The same question without a store: geotex query ontology/queries/objects-with-concept.rq $out/batch/objects/*/annotation.ttl"
echo "Other cross-object queries: ontology/queries/README.md. The store is stopped now."
