#!/usr/bin/env bash
# The workbench's two speed targets (issue 19), measured through HTTP as the page meets them:
#   1. from the request to the last byte of the GTXM mesh of a 1.3M-face object
#      (geotex synth --level 8), first request and again (the server keeps recent meshes);
#   2. POST /api/preview of one bound move, which re-annotates every loaded object from its
#      geometry cache, over N objects (default 100, icosphere level 5).
# Usage: bench/view_bench.sh path/to/geotex [N]     (prints the numbers; takes about 1 min)
set -euo pipefail
G=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
N=${2:-100}
SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
server=
cleanup() {
  [ -n "$server" ] && kill "$server" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work"

# serve PATH ARGS...: starts geotex view with --host (so the token is printed); sets URL,
# PORT and TOKEN.
serve() {
  "$G" view "$@" --port 0 --host 127.0.0.1 >view.out 2>view.err &
  server=$!
  for _ in $(seq 1 600); do grep -q '^geotex view:' view.out && break; sleep 0.1; done
  URL=$(sed -n 's|^geotex view: ||p' view.out)
  PORT=$(echo "$URL" | sed 's|.*:\([0-9]*\)/.*|\1|')
  TOKEN=${URL##*=}
}
stop() { kill -INT "$server"; wait "$server" || true; server=; }

mkdir big
"$G" synth -q --level 8 -o big/big.ply >/dev/null
rm -f big/*.truth.json
"$G" batch big -o big-out --scale 0.04 -q >/dev/null
serve big-out
faces=$(grep -o '"faces": [0-9]*' big-out/objects/big/report.json | head -1 | tr -dc 0-9)
echo "mesh of one object of $faces faces:"
for i in 1 2 3; do
  curl -s -o /dev/null -H "X-Geotex-Token: $TOKEN" \
    -w "  request $i: %{size_download} bytes, first byte %{time_starttransfer} s, last byte %{time_total} s\n" \
    "http://127.0.0.1:$PORT/api/objects/big/mesh"
done
stop

mkdir many
for i in $(seq 1 "$N"); do
  "$G" synth -q --level 5 --layout-seed "$i" -o "many/obj-$(printf %03d "$i").ply" >/dev/null
done
rm -f many/*.truth.json
"$G" batch many -o many-out --scale 0.1 -q >/dev/null
cp "$SRC/dictionaries/default.yaml" dict.yaml
serve many-out --dictionary dict.yaml
echo "POST /api/preview, one bound moved, $N objects re-annotated:"
for v in 0.31 0.5 0.7 0.8; do
  curl -s -o preview.json -X POST -H "X-Geotex-Token: $TOKEN" -H 'Content-Type: application/json' \
    -d "{\"edits\": [{\"op\": \"bound\", \"concept\": \"intermediate-relief\", \"side\": \"upper\", \"value\": \"$v\"}]}" \
    -w "  bound 0.8 -> $v: %{time_total} s" "http://127.0.0.1:$PORT/api/preview"
  /usr/bin/python3 -c "import json; p = json.load(open('preview.json')); print(', %d objects, %d textures changed words' % (len(p['objects']), len(p['changed'])))"
done
stop
