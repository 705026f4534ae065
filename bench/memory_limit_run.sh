#!/bin/bash
# Runs a command under a memory limit, as on a machine with that much memory and no swap:
# a cgroup (v1) memory controller whose limit counts what the process holds and the page
# cache it uses, which the system takes back (clean pages first) as the limit nears. Shows
# whether a job that reads a file or its scratch files through mappings ends at all where
# the file is larger than the memory given (bench/RESULTS.md, "The mesh job reads the
# positions from disk"). Needs root and cgroup v1's memory controller.
#
#   bench/memory_limit_run.sh LIMIT_MIB COMMAND...
#
# e.g. bench/memory_limit_run.sh 1600 build/geotex segment s11.ply --scale 0.01 --tiles 16 \
#        --tile-dir D --pass mesh
# Prints the command's output, then its exit code (137: killed at the limit), wall seconds,
# the cgroup's largest use and how often it met the limit. Stop a run that thrashes with
# `timeout`.
set -uo pipefail
LIMIT=${1:?usage: memory_limit_run.sh LIMIT_MIB COMMAND...}
shift
[[ $LIMIT =~ ^[1-9][0-9]*$ ]] ||
  { echo "memory_limit_run.sh: LIMIT_MIB must be a whole number of MiB above 0, not '$LIMIT'" >&2; exit 2; }
[ $# -gt 0 ] || { echo "memory_limit_run.sh: no command" >&2; exit 2; }
root=/sys/fs/cgroup/memory
[ -w "$root" ] || { echo "memory_limit_run.sh: needs root and cgroup v1 ($root)" >&2; exit 2; }
cg=$root/geotex-limit-$$
mkdir "$cg" || exit 2
trap 'sleep 0.5; rmdir "$cg" 2>/dev/null' EXIT
echo $((LIMIT * 1024 * 1024)) >"$cg/memory.limit_in_bytes"
start=$(date +%s.%N)
# The subshell joins the cgroup, then becomes the command.
(echo $BASHPID >"$cg/cgroup.procs" && exec "$@")
rc=$?
end=$(date +%s.%N)
printf 'exit %d; %.1f s; largest use %d MiB of %d; limit met %d times\n' "$rc" \
  "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" $(($(cat "$cg/memory.max_usage_in_bytes") / 1048576)) \
  "$LIMIT" "$(cat "$cg/memory.failcnt")"
exit $rc
