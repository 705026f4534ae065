#!/usr/bin/env bash
# No lost or partial output. Runs that replace existing outputs are killed (SIGKILL) at many
# moments, including while a temporary file is being written and between the renames;
# afterwards each output must be byte for byte the old file or the complete new one. SIGINT
# and SIGTERM must also remove the run's temporary files. A hard-killed run may leave hidden
# temporary files (.NAME.tmp.PID.N), which a later run ignores. Two runs at the same time in
# one directory both succeed; when they write the same names, each file is one run's
# complete output.
#   tests/kill_test.sh GEOTEX
set -u
geotex=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
now() { date +%s%N; }

# A pause without a process per call: read from a pipe that never has data.
mkfifo tick
exec 3<>tick
pause() { read -r -t "$1" -u 3 _; }

outputs=(out.ttl out.json out.ply)
new_run=("$geotex" annotate s.ply --scale 0.04 -o out.ttl --json out.json --segmentation out.ply --quiet)
old_run=("$geotex" annotate s.ply --scale 0.06 -o out.ttl --json out.json --segmentation out.ply --quiet)
temporary='^\.out\.(ttl|json|ply)\.tmp\.[0-9]+\.[0-9]+$'

"$geotex" synth -o s.ply --level 5 --quiet >/dev/null || fail "synth"
start=$(now)
"${new_run[@]}" >/dev/null || fail "the complete run"
duration_ms=$((($(now) - start) / 1000000))
for f in "${outputs[@]}"; do mv "$f" "new.$f"; done
"${old_run[@]}" >/dev/null || fail "the old run"
for f in "${outputs[@]}"; do
  cp "$f" "old.$f"
  cmp -s "old.$f" "new.$f" && fail "old and new $f are the same: the test could not tell them apart"
done
touch run.err
known=$(ls -A | LC_ALL=C sort)
echo "a complete run takes $duration_ms ms"

# After each run: every output is the old or the complete new file; no file appears but
# temporary files named after an output, and those only when the run was killed hard.
leftovers=0
check() {
  local label=$1 temporaries_allowed=$2 f extra
  for f in "${outputs[@]}"; do
    cmp -s "$f" "old.$f" || cmp -s "$f" "new.$f" ||
      fail "$label: $f is neither the old file nor the complete new one ($(stat -c %s "$f") bytes)"
  done
  extra=$(comm -13 <(echo "$known") <(ls -A | LC_ALL=C sort))
  [ -z "$extra" ] && return
  if grep -v -q -E "$temporary" <<<"$extra"; then
    fail "$label: unexpected files: $(grep -v -E "$temporary" <<<"$extra" | tr '\n' ' ')"
  fi
  if [ "$temporaries_allowed" = yes ]; then
    leftovers=$((leftovers + $(wc -l <<<"$extra")))
    rm -f -- $extra
  else
    fail "$label: temporary files left: $(tr '\n' ' ' <<<"$extra")"
    rm -f -- $extra
  fi
}

restore_old() { for f in "${outputs[@]}"; do cp "old.$f" "$f"; done; }

# kill_after SIGNAL SECONDS: a run replacing the old outputs, sent SIGNAL after SECONDS.
kill_after() {
  restore_old
  "${new_run[@]}" >/dev/null 2>run.err &
  local pid=$!
  pause "$2"
  kill "-$1" "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  status=$?
}

# kill_when SIGNAL CONDITION: the same, SIGNAL sent as soon as CONDITION (a shell function)
# holds; false if the run ended first.
kill_when() {
  restore_old
  "${new_run[@]}" >/dev/null 2>run.err &
  local pid=$! hit=1
  while kill -0 "$pid" 2>/dev/null; do
    if "$2"; then
      kill "-$1" "$pid" 2>/dev/null
      hit=0
      break
    fi
  done
  wait "$pid" 2>/dev/null
  status=$?
  return $hit
}

shopt -s nullglob
writing() { local t=(.out.ttl.tmp.*); [ ${#t[@]} -gt 0 ]; }
writing_last() { local t=(.out.ply.tmp.*); [ ${#t[@]} -gt 0 ]; }
# The RDF has been renamed into place while the other outputs may still wait for theirs.
first_renamed=no
renaming() {
  local t=(.out.ttl.tmp.*)
  [ ${#t[@]} -gt 0 ] && first_renamed=seen
  [ "$first_renamed" = seen ] && [ ${#t[@]} -eq 0 ]
}

# --- SIGKILL at moments spread over the whole run --------------------------------------------
sweep=20
finished=0
for ((i = 0; i < sweep; i++)); do
  delay_ms=$((duration_ms * (2 * i + 1) * 6 / (10 * sweep)))  # 3% to 117% of a run
  kill_after KILL "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  [ "$status" -eq 0 ] && finished=$((finished + 1))
  [ "$status" -eq 0 ] || [ "$status" -eq 137 ] || fail "SIGKILL after $delay_ms ms: exit $status: $(cat run.err)"
  check "SIGKILL after $delay_ms ms" yes
done
[ "$finished" -lt "$sweep" ] || fail "no run was killed before it finished"

# --- SIGKILL while writing, and between the renames ---------------------------------------------
hits=0
for condition in writing writing_last renaming writing writing_last renaming; do
  first_renamed=no
  if kill_when KILL "$condition"; then
    hits=$((hits + 1))
    check "SIGKILL when $condition" yes
  else
    check "run that ended before '$condition' was seen" no
  fi
done
[ "$hits" -gt 0 ] || fail "no run could be killed while writing"
[ "$leftovers" -gt 0 ] || fail "no SIGKILL left a temporary file: the writing window was never hit"

# A hard-killed run's temporary file is hidden, names its output, and is left alone by the
# next run, whose outputs are complete.
for attempt in 1 2 3; do
  kill_when KILL writing
  stale=(.out.ttl.tmp.*)
  [ ${#stale[@]} -eq 1 ] && break
done
if [ ${#stale[@]} -eq 1 ]; then
  cp -- "${stale[0]}" stale.copy
  "${new_run[@]}" >/dev/null || fail "a run after a killed one"
  for f in "${outputs[@]}"; do cmp -s "$f" "new.$f" || fail "a run after a killed one: $f is not the complete output"; done
  cmp -s -- "${stale[0]}" stale.copy || fail "a run after a killed one touched the stale temporary file"
  rm -f -- "${stale[0]}" stale.copy
else
  fail "expected one temporary RDF file after SIGKILL while writing it, found ${#stale[@]}"
  check "after SIGKILL while writing" yes
fi

# --- SIGINT and SIGTERM remove the temporary files ------------------------------------------------
for signal in INT TERM; do
  for condition in writing writing_last; do
    if kill_when "$signal" "$condition"; then
      [ "$status" -eq 0 ] || [ "$status" -gt 128 ] || fail "SIG$signal when $condition: exit $status: $(cat run.err)"
      check "SIG$signal when $condition" no
    else
      check "run that ended before '$condition' was seen" no
    fi
  done
  for percent in 20 60 90; do
    delay_ms=$((duration_ms * percent / 100))
    kill_after "$signal" "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
    [ "$status" -eq 0 ] || [ "$status" -gt 128 ] || fail "SIG$signal after $delay_ms ms: exit $status: $(cat run.err)"
    check "SIG$signal after $delay_ms ms" no
  done
done

# --- two runs at the same time in one directory ------------------------------------------------
for round in 1 2 3; do
  "$geotex" annotate s.ply --scale 0.04 -o a.ttl --json a.json --segmentation a.ply --quiet >/dev/null 2>a.err &
  a=$!
  "$geotex" annotate s.ply --scale 0.04 -o b.ttl --json b.json --segmentation b.ply --quiet >/dev/null 2>b.err &
  b=$!
  wait "$a" || fail "concurrent runs, different names (round $round): first run failed: $(cat a.err)"
  wait "$b" || fail "concurrent runs, different names (round $round): second run failed: $(cat b.err)"
  for run in a b; do
    for ext in ttl json ply; do
      cmp -s "$run.$ext" "new.out.$ext" || fail "concurrent runs, different names (round $round): $run.$ext is not complete"
    done
    rm -f "$run".*
  done

  restore_old
  rm -f "${outputs[@]}"
  "${new_run[@]}" >/dev/null 2>a.err &
  a=$!
  "${old_run[@]}" >/dev/null 2>b.err &
  b=$!
  wait "$a" || fail "concurrent runs, same names (round $round): first run failed: $(cat a.err)"
  wait "$b" || fail "concurrent runs, same names (round $round): second run failed: $(cat b.err)"
  rm -f a.err b.err
  check "concurrent runs, same names (round $round)" no
done

exec 3<&-
echo "$sweep timed kills ($finished runs finished first), $hits kills while writing, $leftovers temporary files left by SIGKILL"
[ "$failures" -eq 0 ] && echo "kill tests passed" || { echo "$failures kill test(s) failed"; exit 1; }
