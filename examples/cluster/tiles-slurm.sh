#!/usr/bin/env bash
# Submits one large mesh's tiled segmentation to Slurm (docs/tiles.md): a job array per pass,
# each after the one before has succeeded (--dependency=afterok), task i of an array making
# shard i of the tiles' parts, then one job that joins the parts into the outputs, the same
# bytes as one `geotex segment` of the whole mesh. Run it on the login node; it only submits.
#
#   examples/cluster/tiles-slurm.sh MESH TILEDIR OUT.ply TASKS --tiles 64 --scale 0.01 \
#       [other geotex segment options, the same for every job]
#
# TASKS is the size of each array (at most the number of tiles is useful). Every job reads the
# whole mesh: give it the memory of a whole-mesh run at a small scale (docs/tiles.md, "What
# stays whole"), e.g. SBATCH_OPTIONS="--mem=16G --cpus-per-task=4 --time=4:00:00".
# Resubmitting keeps the parts already made. JSON=FILE also writes the JSON report.
set -euo pipefail
usage="usage: tiles-slurm.sh MESH TILEDIR OUT.ply TASKS --tiles N (--scale F | --radius R) [segment options]"
MESH=${1:?$usage}
DIR=${2:?$usage}
OUT=${3:?$usage}
TASKS=${4:?$usage}
shift 4
GEOTEX=${GEOTEX:-geotex}
SBATCH=${SBATCH:-sbatch}
# The command each job runs, its words quoted for the job's shell.
segment=$(printf '%q ' "$GEOTEX" segment "$MESH" "$@" --tile-dir "$DIR")
read -r -a options <<<"${SBATCH_OPTIONS:-}"
after=()
for pass in depth texels rims depth-without-rims texels-without-rims features; do
  id=$("$SBATCH" --parsable --job-name="geotex-$pass" --array="1-$TASKS" "${after[@]}" "${options[@]}" \
    --output="geotex-tiles-$pass-%A_%a.out" \
    --wrap="$segment --pass $pass --shard \$SLURM_ARRAY_TASK_ID/$TASKS --quiet")
  echo "tiles-slurm.sh: pass $pass: job array ${id%%;*}"
  after=(--dependency="afterok:${id%%;*}")
done
join="$segment -o $(printf '%q' "$OUT")"
[ -n "${JSON:-}" ] && join+=" --json $(printf '%q' "$JSON")"
id=$("$SBATCH" --parsable --job-name=geotex-join "${after[@]}" "${options[@]}" \
  --output="geotex-tiles-join-%j.out" --wrap="$join")
echo "tiles-slurm.sh: join: job ${id%%;*} writes $OUT"
