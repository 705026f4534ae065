#!/usr/bin/env bash
# Segments one large mesh in tiles over several machines with GNU parallel and ssh
# (docs/tiles.md): one job reads and repairs the mesh, then each pass runs as one job per host slot, each job making the parts of its
# shard of the tiles, and the next pass starts when every part is made; the last command joins
# the parts into the outputs, the same bytes as one `geotex segment` of the whole mesh.
# MESH and TILEDIR must be the same path on every host (a shared file system), and geotex
# must be installed there.
#
#   examples/cluster/tiles-parallel.sh HOSTS_FILE MESH TILEDIR OUT.ply --tiles 64 --scale 0.01 \
#       [other geotex segment options, the same for every job]
#
# HOSTS_FILE lists one ssh login per line (GNU parallel's --sshloginfile; ':' is this machine),
# e.g. "2/node1" runs two jobs at once on node1. A rerun keeps the parts already made; a failed
# job is retried once (--retries 2). JSON=FILE also writes the JSON report.
set -euo pipefail
usage="usage: tiles-parallel.sh HOSTS_FILE MESH TILEDIR OUT.ply --tiles N (--scale F | --radius R) [segment options]"
HOSTS=${1:?$usage}
MESH=${2:?$usage}
DIR=${3:?$usage}
OUT=${4:?$usage}
shift 4
GEOTEX=${GEOTEX:-geotex}
SHARDS=${SHARDS:-$(grep -cv '^\s*\(#\|$\)' "$HOSTS")}
[ "$SHARDS" -ge 1 ] || { echo "tiles-parallel.sh: no host in $HOSTS" >&2; exit 1; }
# The mesh read and repaired once, by one job on one of the hosts, for the passes to read
# (-N0: the job takes none of the arguments, of which there is one).
echo "tiles-parallel.sh: pass mesh" >&2
parallel --will-cite -q -N0 --sshloginfile "$HOSTS" --retries 2 --halt now,fail=1 \
  "$GEOTEX" segment "$MESH" "$@" --tile-dir "$DIR" --pass mesh --quiet ::: 1
# A pass a run does not need (the rims with --keep-rims, ...) does nothing, quickly.
for pass in depth texels rims depth-without-rims texels-without-rims features; do
  echo "tiles-parallel.sh: pass $pass" >&2
  # -q: each word reaches the remote shell quoted, so paths with spaces survive ssh.
  parallel --will-cite -q --sshloginfile "$HOSTS" --retries 2 --halt now,fail=1 \
    "$GEOTEX" segment "$MESH" "$@" --tile-dir "$DIR" --pass "$pass" --shard {}/"$SHARDS" --quiet \
    ::: $(seq 1 "$SHARDS")
done
exec "$GEOTEX" segment "$MESH" "$@" --tile-dir "$DIR" -o "$OUT" ${JSON:+--json "$JSON"}
