#!/usr/bin/env bash
# Runs an rtbench sweep as a Slurm job array, one shard per task, then merges the shards.
#
#   scripts/slurm_sweep.sh CONFIG SHARDS [OUTPUT]      e.g. scripts/slurm_sweep.sh configs/purcell2002.toml 8
#
# Submits an array job of SHARDS tasks (task i runs `rtbench run CONFIG --shard i/SHARDS`; the
# tasks run side by side, each locking its own shard's files; a re-submitted task resumes, keeping
# the rows of its shard's CSV with the same identity), and a merge job that starts when every task
# has succeeded (`rtbench merge` checks that no run is missing or doubled, and that the shards ran
# one commit, one config, one device and the same contents of every input file).
# Build first (scripts/setup.sh) on a file system the compute nodes share. Set SBATCH_* variables
# or edit the #SBATCH lines below for your cluster (partition, GPU request, time).
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:?usage: scripts/slurm_sweep.sh CONFIG SHARDS [OUTPUT]}
shards=${2:?usage: scripts/slurm_sweep.sh CONFIG SHARDS [OUTPUT]}
output=${3:-out}
name=$(sed -n 's/^name *= *"\(.*\)"/\1/p' "$config" | head -n 1)
mkdir -p "$output/slurm"

array=$(sbatch --parsable --array="0-$((shards - 1))" --job-name="rtbench-$name" \
  --output="$output/slurm/%x-%a.log" --cpus-per-task="${RTBENCH_CPUS:-4}" --time="${RTBENCH_TIME:-02:00:00}" \
  --wrap="build/rtbench run $(printf %q "$config") -o $(printf %q "$output") --shard \$SLURM_ARRAY_TASK_ID/$shards")
merge=$(sbatch --parsable --dependency="afterok:$array" --job-name="rtbench-$name-merge" \
  --output="$output/slurm/%x.log" --time=00:10:00 \
  --wrap="build/rtbench merge $(printf %q "$output/$name") && build/rtbench plot $(printf %q "$output/$name")")
echo "submitted array job $array ($shards shards) and merge job $merge; results in $output/$name/runs.csv"
