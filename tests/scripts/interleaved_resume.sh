#!/usr/bin/env bash
# An interleaved sweep killed after some rounds resumes from the rounds it finished: each round's
# samples are in samples.csv as it ends, and the resumed rows are timed from them on (issue 44 §5).
#   interleaved_resume.sh RTBENCH_BINARY WORK_DIR
set -u
bin=$(realpath "$1")
work=$(realpath -m "$2")
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
printf '[experiment]\nname = "i"\norder = "interleaved"\nrepetitions = 6\nrounds = 6\nwarmups = 0\n[scene]\nsource = "procedural:christen_b"\n[camera]\nwidth = 128\nheight = 128\n[structure]\nmin_dim = [8, 16, 24]\n[strategy]\ntype = "multipass"\n[device]\nname = "llvmpipe"\n[output]\nimages = false\n' > i.toml
"$bin" run i.toml > first.txt 2>&1 &
pid=$!
rounds() { awk -F, 'NR > 1 && $3 == "kernel" { print $4 }' out/i/samples.csv 2>/dev/null | sort -u | wc -l; }
for _ in $(seq 1 1200); do  # until two rounds of every run are in (up to 120 s)
  [ "$(rounds)" -ge 2 ] && [ "$(awk -F, 'NR > 1 && $3 == "kernel" && $4 == "1"' out/i/samples.csv | wc -l)" -ge 3 ] && break
  sleep 0.1
done
kill -9 $pid 2>/dev/null
wait $pid 2>/dev/null
cat first.txt
[ "$(wc -l < out/i/runs.csv)" -eq 1 ] || { echo "FAILED: the kill came after a row was written; the test needs it earlier"; exit 1; }
kept=$(rounds)
[ "$kept" -ge 2 ] || { echo "FAILED: no two rounds in samples.csv before the kill"; exit 1; }
cp out/i/samples.csv before.csv
"$bin" run i.toml > second.txt 2>&1 || { cat second.txt; echo "FAILED: the resume"; exit 1; }
cat second.txt
grep -q "round(s) kept from the interrupted sweep" second.txt || { echo "FAILED: no round kept"; exit 1; }
/usr/bin/python3 - <<'PY' || exit 1
import csv
rows = list(csv.DictReader(open("out/i/runs.csv")))
samples = list(csv.DictReader(open("out/i/samples.csv")))
before = list(csv.DictReader(open("before.csv")))
assert len(rows) == 3 and all(r["status"] == "ok" for r in rows), [(r["run"], r["status"], r["error"]) for r in rows]
for r in rows:
    kernel = [s for s in samples if s["run"] == r["run"] and s["method"] == "kernel"]
    assert len(kernel) == int(r["timing_repetitions"]) == 6, (r["run"], len(kernel), r["timing_repetitions"])
    assert sorted(int(s["round"]) for s in kernel) == list(range(6)), r["run"]
key = lambda s: (s["run"], s["method"], s["round"], s["repetition"], s["ms"], s["t_s"])
kept = {key(s) for s in before}
assert kept <= {key(s) for s in samples}, "the interrupted sweep's rounds are in the final samples, as they were"
print(f"resumed: {len(kept)} samples of the interrupted sweep kept, 3 rows ok with 6 rounds each")
PY
