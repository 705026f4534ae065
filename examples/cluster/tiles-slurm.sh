#!/usr/bin/env bash
# Submits one large mesh's tiled segmentation to Slurm (docs/tiles.md): a job that reads and
# repairs the mesh once (--pass mesh), then a job array per pass, each after the one before
# has succeeded (--dependency=afterok), task i of an array making shard i of the tiles' parts,
# then one job that joins the parts into the outputs, the same bytes as one `geotex segment`
# of the whole mesh. Run it on the login node; it only submits.
#
#   examples/cluster/tiles-slurm.sh MESH TILEDIR OUT.ply TASKS --tiles 64 --scale 0.01 \
#       [other geotex segment options, the same for every job]
#
# TASKS is the size of each array (at most the number of tiles is useful). Every job holds the
# whole mesh; the mesh job also repairs it, which takes about twice that again (docs/tiles.md,
# "What stays whole"), e.g. SBATCH_OPTIONS="--mem=16G --cpus-per-task=4 --time=4:00:00".
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
# A word in single quotes, as any POSIX shell reads it back (Slurm runs --wrap under /bin/sh,
# which does not read bash's $'...' quoting of control characters).
quote() { printf "'%s'" "$(printf '%s' "$1" | sed "s/'/'\\\\''/g")"; }
# The command each job runs, its words quoted for the job's shell.
segment=
for word in "$GEOTEX" segment "$MESH" "$@" --tile-dir "$DIR"; do segment+="$(quote "$word") "; done
read -r -a options <<<"${SBATCH_OPTIONS:-}"
id=$("$SBATCH" --parsable --job-name=geotex-mesh "${options[@]}" \
  --output="geotex-tiles-mesh-%j.out" --wrap="$segment --pass mesh --quiet")
echo "tiles-slurm.sh: pass mesh: job ${id%%;*}"
after=(--dependency="afterok:${id%%;*}")
for pass in depth texels rims depth-without-rims texels-without-rims features; do
  id=$("$SBATCH" --parsable --job-name="geotex-$pass" --array="1-$TASKS" "${after[@]}" "${options[@]}" \
    --output="geotex-tiles-$pass-%A_%a.out" \
    --wrap="$segment --pass $pass --shard \$SLURM_ARRAY_TASK_ID/$TASKS --quiet")
  echo "tiles-slurm.sh: pass $pass: job array ${id%%;*}"
  after=(--dependency="afterok:${id%%;*}")
done
join="$segment -o $(quote "$OUT")"
[ -n "${JSON:-}" ] && join+=" --json $(quote "$JSON")"
id=$("$SBATCH" --parsable --job-name=geotex-join "${after[@]}" "${options[@]}" \
  --output="geotex-tiles-join-%j.out" --wrap="$join")
echo "tiles-slurm.sh: join: job ${id%%;*} writes $OUT"
