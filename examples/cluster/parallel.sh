#!/usr/bin/env bash
# Annotates a collection over several machines with GNU parallel and ssh: one shard per host
# slot, no coordinator (shards are chosen by a hash of the object id, docs/collections.md).
# INPUT and OUTDIR must be the same path on every host (a shared file system), and geotex
# must be installed there.
#
#   examples/cluster/parallel.sh HOSTS_FILE /shared/meshes /shared/out [geotex batch options]
#
# HOSTS_FILE lists one ssh login per line (GNU parallel's --sshloginfile; ':' is this machine),
# e.g. "4/node1" runs up to 4 shards on node1. Rerunning skips complete objects; a failed
# shard is retried once (--retries 2). A summary of the whole run is printed at the end.
set -euo pipefail
HOSTS=${1:?usage: parallel.sh HOSTS_FILE INPUT OUTDIR [geotex batch options]}
INPUT=${2:?usage: parallel.sh HOSTS_FILE INPUT OUTDIR [geotex batch options]}
OUTDIR=${3:?usage: parallel.sh HOSTS_FILE INPUT OUTDIR [geotex batch options]}
shift 3
GEOTEX=${GEOTEX:-geotex}
SHARDS=${SHARDS:-$(grep -cv '^\s*\(#\|$\)' "$HOSTS")}
[ "$SHARDS" -ge 1 ] || { echo "parallel.sh: no host in $HOSTS" >&2; exit 1; }
# Each shard uses one job per machine slot; geotex's exit code 3 (some objects failed) is
# reported in the summaries, not retried.
parallel --will-cite --sshloginfile "$HOSTS" --retries 2 --halt never --tag \
  "$GEOTEX" batch "$INPUT" -o "$OUTDIR" --shard {}/"$SHARDS" --jobs 1 -q "$@" \
  ::: $(seq 1 "$SHARDS") || true
# The union of the shard summaries: one line per object.
head -n 1 "$(ls "$OUTDIR"/summary-shard-*-of-"$SHARDS".csv | head -n 1)" > "$OUTDIR/summary.csv.tmp"
for f in "$OUTDIR"/summary-shard-*-of-"$SHARDS".csv; do tail -n +2 "$f"; done | sort >> "$OUTDIR/summary.csv.tmp"
mv "$OUTDIR/summary.csv.tmp" "$OUTDIR/summary.csv"
awk -F, 'NR > 1 { n[$3]++ } END { for (s in n) printf "%s: %d\n", s, n[s] }' "$OUTDIR/summary.csv"
