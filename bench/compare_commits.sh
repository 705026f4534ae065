#!/usr/bin/env bash
# Times `geotex segment` of the working tree against another commit (default HEAD~1) on the
# same mesh, in one run, with hyperfine.
#   bench/compare_commits.sh [COMMIT] [LEVEL]
set -euo pipefail
commit=${1:-HEAD~1}
level=${2:-7}
top=$(git rev-parse --show-toplevel)
work=$(mktemp -d)
trap 'git -C "$top" worktree remove --force "$work/old" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git -C "$top" worktree add --detach "$work/old" "$commit" >/dev/null
cmake -S "$work/old" -B "$work/old/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGEOTEX_BUILD_TESTS=OFF \
  -DGEOTEX_BUILD_BENCH=OFF >/dev/null
cmake --build "$work/old/build" --target geotex >/dev/null
cmake --build "$top/build" --target geotex >/dev/null
"$top/build/geotex" synth -o "$work/s.ply" --level "$level" --quiet >/dev/null
hyperfine --warmup 1 --runs 5 \
  -n "$commit" "$work/old/build/geotex segment $work/s.ply --scale 0.04 -o $work/a.ply --quiet" \
  -n "working tree" "$top/build/geotex segment $work/s.ply --scale 0.04 -o $work/b.ply --quiet"
