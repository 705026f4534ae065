#!/usr/bin/env bash
# docs/workbench.png, the README's picture of `geotex view`: a small batch (the paper's
# sphere-1 and two spheres with engraved shapes), the workbench on it, a screenshot taken by
# headless Chromium (tests/js/workbench_screenshot.mjs; scripts/setup-deps.sh installs both).
# Usage: scripts/workbench_screenshot.sh [build/geotex] [out/workbench] [docs/workbench.png]
set -euo pipefail
geotex=$(realpath "${1:-build/geotex}")
out=${2:-out/workbench}
picture=$(realpath -m "${3:-docs/workbench.png}")
src=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/meshes"
"$geotex" synth -q -o "$out/meshes/sphere-1.ply"
for i in 2 3; do
    "$geotex" synth -q --level 6 --layout-seed "$i" --engraved 0.3 -o "$out/meshes/sphere-$i.ply"
done
rm -f "$out"/meshes/*.truth.json
cp "$src/dictionaries/default.yaml" "$out/my.yaml"
# From inside $out, so that the page names the files as the README's commands do.
cd "$out"
"$geotex" batch meshes -o out --scale 0.04 --dictionary my.yaml -q
"$geotex" view out --dictionary my.yaml --port 0 >view.log 2>&1 &
server=$!
trap 'kill -INT $server 2>/dev/null; wait $server' EXIT
url=
for _ in $(seq 100); do
    url=$(sed -n 's/^geotex view: \(http[^ ]*\).*/\1/p' view.log)
    [ -n "$url" ] && break
    sleep 0.1
done
[ -n "$url" ] || { cat view.log; exit 1; }
node "$src/tests/js/workbench_screenshot.mjs" "$url" sphere-1 shape_index_mean "$picture"
echo "wrote $picture"
