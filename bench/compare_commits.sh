#!/usr/bin/env bash
# Times `geotex segment` of the working tree against another commit (default HEAD~1) on the
# same mesh, in one run, with hyperfine.
#   [BUILD=build] [SCALE=0.04] bench/compare_commits.sh [COMMIT] [LEVEL]
# BUILD is the working tree's build directory (relative to the top or absolute).
set -euo pipefail
commit=${1:-HEAD~1}
level=${2:-7}
scale=${SCALE:-0.04}
top=$(git rev-parse --show-toplevel)
build=$(cd "$top" && realpath -m "${BUILD:-build}")
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
work=$(mktemp -d)
trap 'git -C "$top" worktree remove --force "$work/old" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git -C "$top" worktree add --detach "$work/old" "$commit" >/dev/null
cmake -S "$work/old" -B "$work/old/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGEOTEX_BUILD_TESTS=OFF \
  -DGEOTEX_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
cmake --build "$work/old/build" --target geotex >/dev/null
cmake --build "$build" --target geotex >/dev/null
"$build/geotex" synth -o "$work/s.ply" --level "$level" --quiet >/dev/null
hyperfine --warmup 1 --runs 5 \
  -n "$commit" "$work/old/build/geotex segment $work/s.ply --scale $scale -o $work/a.ply --quiet" \
  -n "working tree" "$build/geotex segment $work/s.ply --scale $scale -o $work/b.ply --quiet"
