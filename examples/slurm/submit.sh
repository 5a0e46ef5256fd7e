#!/usr/bin/env bash
# Submits a pushplan benchmark to Slurm: SHARDS array tasks (bench.sbatch), then one job,
# run once every task has succeeded, that merges the shards into $OUT/merged (results.db
# for Planner Arena, and the plots). Prints the two job ids.
#
#   OUT=$PWD/results SHARDS=35 examples/slurm/submit.sh [more sbatch options]
#
# The paper's experiment at full size: 35 scenes x 3 planners x 20 runs x 300 s is about
# 175 core-hours; with 35 shards of one core each, about 5 hours.
set -euo pipefail
: "${OUT:?set OUT to the results folder (absolute, on a shared file system)}"
shards=${SHARDS:-8}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
array=$(sbatch --parsable --array=1-"$shards" "$@" "$here/bench.sbatch")
array=${array%%;*}
folders=()
for k in $(seq 1 "$shards"); do folders+=("$OUT/shard_$k"); done
merge=$(sbatch --parsable --job-name=pushplan-merge --dependency=afterok:"$array" \
  "$@" --output="$OUT/merge-%j.out" \
  --wrap "$(printf '%q ' "${PUSHPLAN:-pushplan}" bench merge "${folders[@]}" --out "$OUT/merged")")
echo "$array $merge"
