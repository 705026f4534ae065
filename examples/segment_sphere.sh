#!/usr/bin/env bash
# The paper's noise experiment at one noise level: sphere-1 with uniform noise of 0.2% of
# the radius, segmented at scale 0.04 and scored against the ground truth.
set -euo pipefail
geotex=${GEOTEX:-build/geotex}
out=${1:-out/example}
mkdir -p "$out"
"$geotex" synth -o "$out/noisy.ply" --noise 0.2 --noise-seed 3 --quiet
"$geotex" segment "$out/noisy.ply" --scale 0.04 -o "$out/noisy.seg.ply" --json "$out/noisy.json" --quiet
"$geotex" evaluate "$out/noisy.seg.ply" "$out/noisy.truth.json" --quiet
