#!/usr/bin/env bash
# Runs the libFuzzer targets one after the other, each for SECONDS, on its corpus.
# Usage: fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]   (default: every target)
# Corpora grow in BUILD_DIR/corpus/<target>/, crash, leak, timeout and out-of-memory inputs go
# to BUILD_DIR/artifacts/, logs to BUILD_DIR/logs/. Exits 1 when any target found a problem.
set -uo pipefail

build=${1:?usage: fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
here=$(cd "$(dirname "$0")" && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_mesh_ply fuzz_mesh_obj fuzz_mesh_off fuzz_mesh_stl fuzz_dictionary fuzz_rdf_strings fuzz_manifest fuzz_sparql)
fi
mkdir -p "$build/artifacts" "$build/logs"

# UBSan stops at the first report (the code is built with -fno-sanitize-recover=undefined).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

failed=()
for t in "${targets[@]}"; do
  exe=$build/fuzz/$t
  if [ ! -x "$exe" ]; then
    echo "run_fuzzers: no $exe (build the fuzz_all target first)" >&2
    failed+=("$t(missing)")
    continue
  fi
  mkdir -p "$build/corpus/$t"
  extra=()
  [ -f "$here/$t.dict" ] && extra+=(-dict="$here/$t.dict")
  # The default dictionary seed is 26 kB; mutants of that size run at a few dozen per second.
  [ "$t" = fuzz_dictionary ] && extra+=(-max_len=8192)
  echo "== $t: ${seconds} s" >&2
  start=$(date +%s)
  nice "$exe" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$build/artifacts/$t-" -print_final_stats=1 "${extra[@]}" \
    "$build/corpus/$t" >"$build/logs/$t.log" 2>&1
  rc=$?
  echo "   ran $(($(date +%s) - start)) s" >&2
  grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb|DONE' "$build/logs/$t.log" >&2
  echo "   corpus: $(ls "$build/corpus/$t" | wc -l) inputs" >&2
  if [ $rc -ne 0 ]; then
    echo "   FOUND A PROBLEM (exit $rc): see $build/logs/$t.log" >&2
    grep -E 'ERROR|invariant broken|runtime error|Test unit written' "$build/logs/$t.log" | head -5 >&2
    failed+=("$t")
  fi
done

if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: problems found by ${failed[*]}; the inputs are in $build/artifacts/" >&2
  exit 1
fi
echo "fuzz: no problem found" >&2
