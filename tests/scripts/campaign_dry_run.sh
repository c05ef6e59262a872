#!/usr/bin/env bash
# scripts/gpu_campaign.sh dry-run on lavapipe: the bundle, its unpacking, the first run of every
# config of record (one process each), the merge that writes the runs not run as failed rows saying
# why, and the tarball that comes back; then unpacked as a results folder per config.
#   [CONFIGS="bunny ..."] campaign_dry_run.sh RTBENCH_BINARY WORK_DIR
set -euo pipefail
bin=$(realpath "$1")
work=$(realpath -m "$2")
cd "$(dirname "$0")/../.."
rm -rf "$work" && mkdir -p "$work/out"
configs=(${CONFIGS:-bunny structures purcell2002 stability accuracy raytypes wavefront})
OUT="$work/out" BIN="$bin" CONFIGS="${configs[*]}" bash scripts/gpu_campaign.sh dry-run
cat "$work/out/campaign.log"
BIN="$bin" bash scripts/gpu_campaign.sh unpack "$work/out/campaign.tar.xz" "$work/results" > /dev/null
for config in "${configs[@]}"; do
  folder="$work/results/$config"
  planned=$("$bin" plan "configs/$config.toml" -o "$work/none" | sed -n 's/^\([0-9][0-9]*\) run(s).*/\1/p')
  /usr/bin/python3 - "$folder" "$planned" <<'PY'
import csv, json, sys
folder, planned = sys.argv[1], int(sys.argv[2])
rows = list(csv.DictReader(open(f"{folder}/runs.csv")))
assert len(rows) == planned, f"{folder}: {len(rows)} rows, the plan has {planned} runs"
assert [r["run"] for r in rows] == [f"{i:03d}" for i in range(planned)], f"{folder}: runs out of order or missing"
first, rest = rows[0], rows[1:]
assert first["status"] == "ok", f"{folder}: run 000 {first['status']}: {first['error']}"
assert first["device"].startswith("llvmpipe"), first["device"]
for r in rest:
    assert r["status"] == "failed" and r["error"].startswith("no row from its shard: "), (r["run"], r["status"], r["error"])
    assert r["config_hash"] and r["device"] == first["device"] and r["git_commit"] == first["git_commit"], r["run"]
context = json.load(open(f"{folder}/context.json"))
assert context["complete"] is (planned == 1), f"{folder}: complete {context['complete']} with {planned} runs planned"
assert context["shard"] == ""
print(f"{folder}: {planned} rows, run 000 ok, {len(rest)} failed rows saying why")
PY
  ls "$folder" | grep -q 'shard' && { echo "$folder: shard files left after the merge"; exit 1; }
done
echo "campaign dry run: every config's results folder is whole"
