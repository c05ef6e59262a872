#!/usr/bin/env bash
# A results folder renamed away mid-run and a symlink to another folder put in its place: the run
# stops with an error naming the folder, and the other folder is left as it was (issue 45 §1).
#   folder_swap.sh RTBENCH_BINARY WORK_DIR
set -u
bin=$(realpath "$1")
work=$(realpath -m "$2")
rm -rf "$work" && mkdir -p "$work/other" && cd "$work" || exit 1
echo keep > other/runs.csv
printf '[experiment]\nname = "s"\nrepetitions = 300\nwarmups = 0\n[scene]\nsource = "procedural:christen_b"\n[camera]\nwidth = 64\nheight = 64\n[structure]\nmin_dim = [4, 5, 6, 7, 8, 9, 10, 11]\n[device]\nname = "llvmpipe"\n[output]\nimages = false\n' > s.toml
"$bin" run -q s.toml > run.txt 2>&1 &
pid=$!
for _ in $(seq 1 1200); do  # until the first row is in (up to 60 s)
  [ "$(wc -l 2>/dev/null < out/s/runs.csv || echo 0)" -ge 2 ] && break
  sleep 0.05
done
[ "$(wc -l < out/s/runs.csv)" -ge 2 ] || { echo "FAILED: no first row"; cat run.txt; kill $pid; exit 1; }
mv out/s out/s.moved && ln -s "$work/other" out/s
wait $pid
rc=$?
cat run.txt
[ $rc -ne 0 ] || { echo "FAILED: the run finished with rc 0 through the swapped folder"; exit 1; }
grep -q "out/s: the results folder now is a symlink; rtbench never writes through one" run.txt ||
  { echo "FAILED: no error naming the folder"; exit 1; }
[ "$(ls other)" = runs.csv ] && [ "$(cat other/runs.csv)" = keep ] || { echo "FAILED: the other folder was written"; ls -la other; exit 1; }
echo "folder swap refused; the other folder untouched"
