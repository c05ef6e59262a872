#!/usr/bin/env bash
# Self-test of scripts/slurm_sweep.sh on a real, private one-node Slurm cluster (docs/slurm.md).
#
#   sudo scripts/slurm_selftest.sh        (root: it runs slurmctld and slurmd; exit 77 = skipped, not root)
#
# Installs Debian's slurm-wlm and munge where missing, then, all in a fresh temporary folder:
# starts its own munged (own key and socket), slurmctld and slurmd (own slurm.conf and
# cgroup.conf via SLURM_CONF, free ports, this host's CPUs and memory from `slurmd -C`, state,
# spool and logs in the folder), submits a 3-shard sweep of a tiny config through slurm_sweep.sh
# from another working directory with relative paths and RTBENCH_GRES unset, waits for the array
# and the merge job, and checks that the merged runs.csv equals an unsharded `rtbench run` of the
# same config in every parameter and count column (the deterministic kinds of `rtbench columns`)
# and that the merge job left the plot to a login node. On exit it cancels its jobs and stops every
# process it started (found by their pid and by the folder's SLURM_CONF in their environment);
# it never reads or changes /etc/slurm or a system munged. Exit 0 only when all of it held.
#   RTBENCH_BIN=PATH                 the binary (default build/rtbench next to scripts/)
#   RTBENCH_SELFTEST_TIMEOUT=S       seconds to wait for the jobs (default 240)
#   RTBENCH_SELFTEST_KEEP=1          keep the temporary folder also after a pass (kept after a failure)
set -euo pipefail

say() { echo "[slurm-selftest] $*"; }
fail() { echo "[slurm-selftest] FAIL: $*" >&2; exit 1; }

if [ "$(id -u)" -ne 0 ]; then
  say "SKIP: needs root (it installs slurm-wlm and runs slurmctld and slurmd)"
  exit 77
fi
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=${RTBENCH_BIN:-$repo/build/rtbench}
case $bin in /*) ;; *) bin=$PWD/$bin ;; esac
[ -x "$bin" ] || fail "$bin: no rtbench binary (build first: scripts/setup.sh)"
timeout_s=${RTBENCH_SELFTEST_TIMEOUT:-240}
# The caller's Slurm settings are another cluster's: none of them reaches this one.
while read -r v; do unset "$v"; done < <(compgen -e | grep -E '^(SBATCH|SLURM|SALLOC|SRUN)_' || true)
started=$SECONDS

source "$repo/scripts/packages.sh"
t0=$SECONDS
install_missing slurm slurm-wlm munge || fail "could not install slurm-wlm and munge (apt-get, above)"
say "slurm-wlm and munge present ($((SECONDS - t0)) s)"
for tool in slurmctld slurmd sbatch squeue scontrol scancel munged mungekey /usr/bin/python3; do
  command -v "$tool" >/dev/null || fail "$tool is missing after installing slurm-wlm and munge"
done
/usr/bin/python3 -c 'import pandas' 2>/dev/null || fail "python3-pandas is missing (scripts/setup.sh installs it)"

tmp=$(mktemp -d /tmp/rtbench-slurm-selftest.XXXXXX)
chmod 711 "$tmp"  # munged wants its socket's folders searchable; nothing here is secret but the key (600)
conf=$tmp/etc/slurm.conf
pids=()  # every daemon started here
sl() { SLURM_CONF=$conf "$@"; }  # a Slurm command of this cluster (SLURM_CONF is not exported here)
passed=0

# Processes started from here: the daemons (started with this cluster's SLURM_CONF in their
# environment) and everything they start (slurmstepd, the job scripts, rtbench), which carries it.
is_ours() {  # PID: alive (not a zombie) and started from here
  local stat
  { read -r stat <"/proc/$1/stat"; } 2>/dev/null && [[ $stat =~ ^[0-9]+\ \(.*\)\ [^Z] ]] &&
    grep -qzxF "SLURM_CONF=$conf" "/proc/$1/environ" 2>/dev/null
}
ours() {
  local p
  for p in /proc/[0-9]*; do
    p=${p#/proc/}
    [ "$p" != $$ ] && [ "$p" != "$BASHPID" ] && is_ours "$p" && echo "$p"
  done
  return 0
}
cleanup() {
  local rc=$? left i
  trap - EXIT INT TERM
  set +e
  if [ -S "$tmp/munge/munge.socket" ] && ((${#pids[@]})); then
    sl timeout 10 scancel --quiet --full --user=root 2>/dev/null  # only this cluster's jobs
    for i in $(seq 20); do
      [ -z "$(sl timeout 5 squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.5
    done
  fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do is_ours "${pids[i]}" && kill -TERM "${pids[i]}"; done  # slurmd, slurmctld, munged
  for i in $(seq 40); do
    left=$(ours)
    [ -z "$left" ] && break
    ((i == 20)) && kill -KILL $left 2>/dev/null
    ((i < 20)) && ((i % 5 == 0)) && kill -TERM $left 2>/dev/null
    sleep 0.25
  done
  wait "${pids[@]}" 2>/dev/null  # reap the daemons
  left=$(ours)
  if [ -n "$left" ]; then
    echo "[slurm-selftest] FAIL: processes it started are still running: $left" >&2
    rc=1
  fi
  if ((rc == 0 && passed)) && [ -z "${RTBENCH_SELFTEST_KEEP:-}" ]; then
    rm -rf "$tmp"
  else
    say "kept $tmp (logs: $tmp/log, job logs: $tmp/work/out/slurm)"
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

show_logs() {  # everything a failure needs to be understood
  local f
  for f in "$tmp"/work/out/slurm/*.log "$tmp"/log/*.log; do
    [ -f "$f" ] || continue
    [[ $f == *.out.log && -s ${f%.out.log}.log ]] && continue  # a daemon's stderr, when its log file has it all
    echo "----- $f (last 40 lines)" >&2
    tail -n 40 "$f" >&2
  done
  if [ -S "$tmp/munge/munge.socket" ]; then
    echo "----- scontrol show job" >&2
    sl timeout 10 scontrol -o show job >&2 2>&1
  fi
}
wait_for() {  # SECONDS WHAT COMMAND...: polls COMMAND until it succeeds
  local limit=$1 what=$2 end=$((SECONDS + $1))
  shift 2
  until "$@" >/dev/null 2>&1; do
    ((SECONDS < end)) || { show_logs; fail "$what: not within $limit s"; }
    sleep 0.5
  done
}

# --- a private munged: own key, socket, pid, seed and log files
mkdir -p "$tmp"/{etc,munge,log,state,spool,work}
chmod 711 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key" >/dev/null 2>&1 ||
  dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$tmp/munge/munge.key"
SLURM_CONF=$conf munged --foreground --force --socket="$tmp/munge/munge.socket" --key-file="$tmp/munge/munge.key" \
  --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" --log-file="$tmp/log/munged.log" \
  >"$tmp/log/munged.out.log" 2>&1 &
pids+=($!)
wait_for 20 "munged to open its socket" test -S "$tmp/munge/munge.socket"

# --- slurm.conf for this host, on two free ports
node=$(slurmd -C | sed -n 's/^NodeName=\([^ ]*\) .*/\1/p')
hardware=$(slurmd -C | sed -n 's/^NodeName=[^ ]* //p')
[ -n "$node" ] && [ -n "$hardware" ] || fail "slurmd -C printed no NodeName line"
mkdir -p "$tmp/spool/$node"
read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
cat >"$conf" <<EOF
# A one-node cluster of scripts/slurm_selftest.sh; everything it writes is under $tmp.
ClusterName=rtbenchselftest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool/%n
SlurmctldPidFile=$tmp/state/slurmctld.pid
SlurmdPidFile=$tmp/spool/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$tmp/log/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
MailProg=/bin/true
PlugStackConfig=$tmp/etc/plugstack.conf
NodeName=$node NodeAddr=127.0.0.1 $hardware State=UNKNOWN
PartitionName=selftest Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
: >"$tmp/etc/plugstack.conf"
cat >"$tmp/etc/cgroup.conf" <<EOF
# Read by slurmd from beside slurm.conf; the plugins above use no cgroups.
CgroupPlugin=autodetect
IgnoreSystemd=yes
EOF
# Run from the folder so that nothing the daemons or jobs write lands where this was called from.
cd "$tmp/work"

SLURM_CONF=$conf slurmctld -D -i -f "$conf" >"$tmp/log/slurmctld.out.log" 2>&1 &
pids+=($!)
wait_for 30 "slurmctld to answer (scontrol ping)" sl bash -c 'scontrol ping | grep -q UP'
SLURM_CONF=$conf slurmd -D -N "$node" -f "$conf" >"$tmp/log/slurmd.out.log" 2>&1 &
pids+=($!)
wait_for 30 "node $node to become idle" sl bash -c "sinfo -h -n '$node' -o %T | grep -qx idle"
say "cluster up: node $node ($hardware), ports $ctld_port/$slurmd_port, in $tmp ($((SECONDS - started)) s)"

# --- the sweep: 8 runs (2 scenes x 2 structures x 2 strategies) in 3 shards, relative paths
cat >"$tmp/work/tiny.toml" <<'EOF'
# The self-test's sweep (scripts/slurm_selftest.sh): small and procedural, seconds on lavapipe.
[experiment]
name = 'slurm selftest'    # a literal string with a space: what slurm_sweep.sh must read
repetitions = 1
warmups = 0

[scene]
source = ["procedural:christen_a", "procedural:christen_b"]

[camera]
width = 64
height = 64

[structure]
type = ["uniform_grid", "bvh"]

[strategy]
type = ["branching", "multipass"]

[device]
name = "llvmpipe"

[output]
images = false
EOF
mkdir -p "$tmp/work/elsewhere"
cd "$tmp/work/elsewhere"
submitted=$(env -u RTBENCH_GRES -u RTBENCH_PARTITION -u RTBENCH_SBATCH_ARGS -u RTBENCH_TASKS -u RTBENCH_RUN_ARGS \
  SLURM_CONF="$conf" RTBENCH_BIN="$bin" RTBENCH_CPUS=1 RTBENCH_TIME=00:05:00 \
  "$repo/scripts/slurm_sweep.sh" ../tiny.toml 3 ../out) || { show_logs; fail "slurm_sweep.sh failed"; }
echo "$submitted"
cd "$tmp/work"
array=$(sed -n 's/^submitted array job \([0-9]*\) .* merge job \([0-9]*\)$/\1/p' <<<"$submitted")
merge=$(sed -n 's/^submitted array job \([0-9]*\) .* merge job \([0-9]*\)$/\2/p' <<<"$submitted")
[ -n "$array" ] && [ -n "$merge" ] || fail "slurm_sweep.sh printed no job ids"

# --- wait for the array and the merge, then read how each ended
end=$((SECONDS + timeout_s))
while [ -n "$(sl squeue -h -j "$array,$merge" -o %i 2>/dev/null)" ]; do
  if ((SECONDS >= end)); then
    show_logs
    fail "jobs $array (array) and $merge (merge) not finished within $timeout_s s"
  fi
  sleep 1
done
ended() {  # JOBID: "JobId=.. [ArrayTaskId=..] JobState=.. ExitCode=.." of each of its records
  sl scontrol -o show job "$1" | sed -n 's/^\(JobId=[0-9]*\) .*JobState=\([A-Z_]*\) .*ExitCode=\([0-9:]*\) .*/\1 JobState=\2 ExitCode=\3/p'
}
tasks_ended=$(ended "$array") merge_ended=$(ended "$merge")
printf '%s\n' "$tasks_ended" "$merge_ended" | sed 's/^/[slurm-selftest]   /'
if [ "$(grep -c "JobState=COMPLETED ExitCode=0:0$" <<<"$tasks_ended")" -ne 3 ] || [ "$(wc -l <<<"$tasks_ended")" -ne 3 ] ||
  ! grep -q "JobState=COMPLETED ExitCode=0:0$" <<<"$merge_ended"; then
  show_logs
  fail "expected the 3 array tasks and the merge job COMPLETED with exit 0"
fi
merged="$tmp/work/out/slurm selftest/runs.csv"
[ -f "$merged" ] || { show_logs; fail "no merged $merged"; }
grep -q "^plot it on a login node (matplotlib): .* plot " "$tmp"/work/out/slurm/*-merge-"$merge".log ||
  { show_logs; fail "the merge job's log names no plot command for a login node"; }
! ls "$tmp/work/out/slurm selftest/"*.png "$tmp/work/out/slurm selftest/"*.svg >/dev/null 2>&1 ||
  fail "the merge job plotted on the compute node"
say "array $array (3 tasks) and merge $merge completed ($((SECONDS - started)) s)"

# --- the same config unsharded, then every deterministic column compared
"$bin" run "$tmp/work/tiny.toml" -o "$tmp/work/unsharded" -q >"$tmp/log/unsharded.log" 2>&1 ||
  { cat "$tmp/log/unsharded.log" >&2; fail "the unsharded rtbench run failed"; }
"$bin" columns >"$tmp/work/columns.md"
/usr/bin/python3 - "$merged" "$tmp/work/unsharded/slurm selftest/runs.csv" "$tmp/work/columns.md" <<'EOF' ||
import sys
import pandas as pd

merged_path, single_path, columns_path = sys.argv[1:]
kinds = {}
for line in open(columns_path):
    cells = [c.strip().strip("`") for c in line.split("|")]
    if len(cells) > 3 and cells[2] in ("parameter", "count", "reference", "timing", "context"):
        kinds[cells[1]] = cells[2]
read = lambda p: pd.read_csv(p, dtype=str, keep_default_na=False)
merged, single = read(merged_path), read(single_path)
problems = []
if list(merged.columns) != list(single.columns):
    problems.append(f"columns differ: only merged {sorted(set(merged.columns) - set(single.columns))}, "
                    f"only unsharded {sorted(set(single.columns) - set(merged.columns))}")
# Deterministic: the declared parameter and count columns, and the config keys (not declared there).
compared = [c for c in single.columns if kinds.get(c, "parameter") in ("parameter", "count")]
if len(single) != 8 or (single["status"] != "ok").any():
    problems.append(f"the unsharded run has {len(single)} rows, status {sorted(set(single['status']))}; expected 8 ok")
if list(merged["run"]) != list(single["run"]):
    problems.append(f"runs differ: merged {list(merged['run'])}, unsharded {list(single['run'])}")
else:
    for c in compared:
        if c not in merged.columns:
            continue
        for i in (merged[c] != single[c]).to_numpy().nonzero()[0]:
            problems.append(f"run {single['run'][i]} {c}: merged {merged[c][i]!r}, unsharded {single[c][i]!r}")
counts = sum(kinds.get(c) == "count" for c in compared)
if problems:
    print("\n".join(problems[:40]), file=sys.stderr)
    sys.exit(1)
print(f"[slurm-selftest] merged runs.csv equals the unsharded run: {len(single)} runs, "
      f"{len(compared)} columns compared ({counts} count, {len(compared) - counts} parameter and config keys)")
EOF
  fail "the merged runs.csv differs from the unsharded run (above)"

passed=1
say "PASS in $((SECONDS - started)) s"
