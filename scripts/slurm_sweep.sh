#!/usr/bin/env bash
# Runs an rtbench sweep as a Slurm job array, one shard per task, then merges the shards.
#
#   scripts/slurm_sweep.sh CONFIG SHARDS [OUTPUT]      e.g. scripts/slurm_sweep.sh configs/purcell2002.toml 8
#
# Submits an array job of SHARDS tasks (task i runs `rtbench run CONFIG -o OUTPUT --shard i/SHARDS`;
# the tasks run side by side, each locking its own shard's files; a re-submitted task resumes,
# keeping the rows of its shard's CSV with the same identity), and a merge job that starts when
# every task has succeeded (`rtbench merge` checks that no run is missing or doubled, and that the
# shards ran one commit, one config, one device and the same contents of every input file). The
# merge job does not plot (matplotlib is rarely on compute nodes): its log ends with the
# `rtbench plot` command to run on a login node.
#
# CONFIG and OUTPUT are resolved against the directory you call this from. OUTPUT defaults to the
# config's experiment.output (default "out"), as `rtbench run CONFIG` would use it from there;
# results go to OUTPUT/<experiment.name>/, Slurm's logs to OUTPUT/slurm/. Build first
# (scripts/setup.sh) on a file system the compute nodes share. Options, all from the environment
# (docs/slurm.md):
#   RTBENCH_BIN=PATH          the rtbench binary (default: build/rtbench next to this script's folder)
#   RTBENCH_CPUS=N            --cpus-per-task of each shard (default 4)
#   RTBENCH_TIME=T            --time of each shard (default 02:00:00, or SBATCH_TIMELIMIT when set)
#   RTBENCH_GRES=G            --gres of each shard, e.g. gpu:1 (default: none; the merge needs no GPU)
#   RTBENCH_PARTITION=P       --partition of both jobs (default: SBATCH_PARTITION or the cluster's)
#   RTBENCH_SBATCH_ARGS="..." more sbatch options for both jobs, split at spaces (--account=x --qos=y)
#   RTBENCH_RUN_ARGS="..."    more `rtbench run` options, split at spaces (e.g. "-d nvidia")
#   RTBENCH_TASKS=LIST        submit only these tasks (e.g. 3 or 1,4-5) and a merge after them:
#                             to resume a failed task once the first array has finished
# sbatch itself also reads SBATCH_* variables (SBATCH_ACCOUNT, SBATCH_QOS, SBATCH_GRES — which
# would apply to the merge job too ...); the options above and the script's own (array, job name,
# output, dependency, chdir) win over them.
set -euo pipefail

usage="usage: scripts/slurm_sweep.sh CONFIG SHARDS [OUTPUT]   (options: see the top of this script)"
die() { echo "slurm_sweep.sh: $*" >&2; exit 2; }
# A path as seen from the caller's working directory, made absolute before anything else.
absolute() { case $1 in /*) printf '%s\n' "$1" ;; *) printf '%s\n' "$PWD/$1" ;; esac; }

[ $# -ge 2 ] && [ $# -le 3 ] || die "$usage"
[ -n "$1" ] || die "CONFIG is empty; $usage"
config=$(absolute "$1")
shards=$2
[ -f "$config" ] && [ -r "$config" ] || die "$1: no such readable config file (from $PWD)"
[[ $shards =~ ^[1-9][0-9]*$ ]] || die "SHARDS must be a positive integer, not '$shards'; $usage"
if [ $# -eq 3 ]; then
  [ -n "$3" ] || die "OUTPUT is empty; $usage"
  output=$(absolute "$3")
fi

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=$(absolute "${RTBENCH_BIN:-$repo/build/rtbench}")
[ -f "$bin" ] && [ -x "$bin" ] || die "$bin: no rtbench binary; build first (scripts/setup.sh) or set RTBENCH_BIN"
command -v sbatch >/dev/null || die "sbatch is not on PATH: run this on a Slurm login node"

# experiment.NAME of the config: a string in [experiment] (name = "x", 'x', "name" = ...) or a
# top-level experiment.name = ...; python3's tomllib (3.11+) reads it exactly where present.
experiment_key() {  # KEY: prints the value, or nothing when the config does not set it
  if python3 -c 'import tomllib' 2>/dev/null; then
    python3 - "$config" "$1" <<'EOF'
import sys, tomllib
try:
    with open(sys.argv[1], "rb") as f:
        value = tomllib.load(f).get("experiment", {}).get(sys.argv[2])
except (OSError, tomllib.TOMLDecodeError) as e:
    sys.exit(f"{sys.argv[1]}: {e}")
if value is not None:
    if not isinstance(value, str):
        sys.exit(f"experiment.{sys.argv[2]} is not a string")
    print(value)
EOF
    return
  fi
  awk -v key="$1" '
    BEGIN { section = "" }
    { line = $0; sub(/^[[:space:]]+/, "", line) }
    line ~ /^\[/ { s = line; sub(/\].*/, "]", s); gsub(/[[:space:]"\047]/, "", s); section = s; next }
    {
      k = ""
      if (section == "[experiment]") k = "(" key "|\"" key "\"|\047" key "\047)"
      else if (section == "") k = "experiment[[:space:]]*\\.[[:space:]]*" key
      if (k == "" || !match(line, "^" k "[[:space:]]*=[[:space:]]*")) next
      v = substr(line, RLENGTH + 1)
      q = substr(v, 1, 1)
      if ((q != "\"" && q != "\047") || (rest = substr(v, 2)) == "" || (e = index(rest, q)) == 0) { bad = 1; exit }
      out = substr(rest, 1, e - 1); tail = substr(rest, e + 1)
      if ((q == "\"" && index(out, "\\")) || tail !~ /^[[:space:]]*(#.*)?$/) { bad = 1; exit }
      print out; exit
    }
    END { if (bad) { print "experiment." key ": not a plain one-line string (install python3 3.11+ to read any TOML)" > "/dev/stderr"; exit 1 } }
  ' "$config"
}
name=$(experiment_key name) || die "$config: cannot read experiment.name"
[ -n "$name" ] || die "$config: sets no experiment.name"
[[ $name != */* && $name != . && $name != .. && $name != *[[:cntrl:]]* ]] ||
  die "$config: experiment.name '$name' is not a plain folder name"
if [ -z "${output:-}" ]; then
  output=$(experiment_key output) || die "$config: cannot read experiment.output"
  output=$(absolute "${output:-out}")
fi
folder=$output/$name

# The tasks to submit (all, or RTBENCH_TASKS), each checked against SHARDS.
tasks=${RTBENCH_TASKS:-0-$((shards - 1))}
IFS=, read -ra task_items <<<"$tasks"
[ ${#task_items[@]} -gt 0 ] || die "RTBENCH_TASKS is empty"
for item in "${task_items[@]}"; do
  [[ $item =~ ^([0-9]+)(-([0-9]+))?$ ]] || die "RTBENCH_TASKS='$tasks': expected indices and ranges such as 3 or 1,4-5"
  first=$((10#${BASH_REMATCH[1]})) last=$((10#${BASH_REMATCH[3]:-${BASH_REMATCH[1]}}))
  ((first <= last && last < shards)) || die "RTBENCH_TASKS='$tasks': $item is not within 0-$((shards - 1))"
done

common=(--parsable --chdir="$output")
[ -z "${RTBENCH_PARTITION:-}" ] || common+=(--partition="$RTBENCH_PARTITION")
if [ -n "${RTBENCH_SBATCH_ARGS:-}" ]; then
  read -ra extra <<<"$RTBENCH_SBATCH_ARGS"
  common+=("${extra[@]}")
fi
shard_opts=(--cpus-per-task="${RTBENCH_CPUS:-4}")
[[ ${RTBENCH_CPUS:-4} =~ ^[1-9][0-9]*$ ]] || die "RTBENCH_CPUS must be a positive integer, not '$RTBENCH_CPUS'"
if [ -n "${RTBENCH_TIME:-}" ]; then shard_opts+=(--time="$RTBENCH_TIME")
elif [ -z "${SBATCH_TIMELIMIT:-}" ]; then shard_opts+=(--time=02:00:00); fi
[ -z "${RTBENCH_GRES:-}" ] || shard_opts+=(--gres="$RTBENCH_GRES")
run_args=()
[ -z "${RTBENCH_RUN_ARGS:-}" ] || read -ra run_args <<<"$RTBENCH_RUN_ARGS"

mkdir -p "$output/slurm"
q() { printf '%q' "$1"; }  # quoted for the bash job scripts below

task_script=$(cat <<EOF
#!/bin/bash
set -euo pipefail
echo "rtbench shard \$SLURM_ARRAY_TASK_ID/$shards of $(q "$config") on \$(hostname), job \$SLURM_JOB_ID"
exec $(q "$bin") run $(q "$config") -o $(q "$output") --shard "\$SLURM_ARRAY_TASK_ID/$shards"$(for a in ${run_args[@]+"${run_args[@]}"}; do printf ' %q' "$a"; done)
EOF
)
if ((shards > 1)); then merge_cmd="$(q "$bin") merge $(q "$folder")"
else merge_cmd="[ -f $(q "$folder/runs.csv") ]  # one shard: its runs.csv is the whole sweep, nothing to merge"; fi
merge_script=$(cat <<EOF
#!/bin/bash
set -euo pipefail
[ -d $(q "$folder") ] || { echo "no results folder $(q "$folder"): did the shards write elsewhere?" >&2; exit 1; }
$merge_cmd
echo "results: $(q "$folder/runs.csv")"
echo "plot it on a login node (matplotlib): $(q "$bin") plot $(q "$folder")"
EOF
)

array=$(sbatch "${common[@]}" "${shard_opts[@]}" --array="$tasks" --job-name="rtbench-$name" \
  --output="$output/slurm/rtbench-$name-%A-%a.log" <<<"$task_script") ||
  die "sbatch refused the array job (its message is above); nothing was submitted"
array=${array%%;*}
[[ $array =~ ^[0-9]+$ ]] || die "sbatch gave no job id for the array: '$array'"
merge=$(sbatch "${common[@]}" --time=00:10:00 --cpus-per-task=1 --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --job-name="rtbench-$name-merge" --output="$output/slurm/rtbench-$name-merge-%j.log" <<<"$merge_script") ||
  die "sbatch refused the merge job (above) after submitting the array job $array: scancel $array, or merge by hand when it ends"
merge=${merge%%;*}
[[ $merge =~ ^[0-9]+$ ]] || die "sbatch gave no job id for the merge (the array job $array is submitted): '$merge'"

echo "submitted array job $array (tasks $tasks of $shards shards) and merge job $merge"
echo "results: $folder/runs.csv   logs: $output/slurm/   watch: squeue -j $array,$merge"
echo "then plot on a login node: $(q "$bin") plot $(q "$folder")"
