#!/usr/bin/env bash
# A Slurm job array that annotates a collection on many nodes: task i runs shard i of N.
# No coordinator: shards are chosen by a hash of the object id (docs/collections.md), every
# task writes its own objects and its own summary-shard-i-of-N.csv into the shared OUTDIR,
# and a resubmitted array skips what is already complete.
#
#   sbatch --array=1-16 examples/cluster/slurm-array.sh /shared/meshes /shared/out
#
# The array's size is N: keep it the same across resubmissions so that each object stays in
# the same shard (a different N is fine too: complete objects are skipped whatever their shard).
#SBATCH --job-name=geotex
#SBATCH --cpus-per-task=4
#SBATCH --mem=8G
#SBATCH --time=12:00:00
#SBATCH --output=geotex-%A_%a.out
set -euo pipefail
INPUT=${1:?usage: sbatch --array=1-N slurm-array.sh INPUT OUTDIR [geotex batch options]}
OUTDIR=${2:?usage: sbatch --array=1-N slurm-array.sh INPUT OUTDIR [geotex batch options]}
shift 2
GEOTEX=${GEOTEX:-geotex}
: "${SLURM_ARRAY_TASK_ID:?submit with sbatch --array=1-N}"
N=${SLURM_ARRAY_TASK_COUNT:-${SLURM_ARRAY_TASK_MAX:?}}
# One mesh per allotted core pair; each mesh's run uses the rest.
JOBS=$(( ${SLURM_CPUS_PER_TASK:-2} / 2 )); [ "$JOBS" -ge 1 ] || JOBS=1
exec "$GEOTEX" batch "$INPUT" -o "$OUTDIR" --shard "$SLURM_ARRAY_TASK_ID/$N" --jobs "$JOBS" \
  --base-template "${BASE_TEMPLATE:-https://example.org/object/{id}/}" --scale "${SCALE:-0.04}" "$@"
