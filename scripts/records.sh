#!/bin/bash
# Runs the configs of record and makes their charts and tables: results/bunny, results/structures,
# results/purcell2002 (or under OUT, e.g. results/h200 on a GPU machine; DEVICE picks the device).
#   scripts/records.sh [OUT] [DEVICE]        (about 25 minutes on 2 cores with lavapipe)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results}
device=${2:-}
bin=build/rtbench
args=(-o "$out")
[ -n "$device" ] && args+=(-d "$device")
for config in bunny structures purcell2002; do
  echo "== $config -> $out/$config"
  start=$(date +%s)
  # A failed run is a result too (a row naming why); rtbench then exits 1.
  "$bin" run --force "${args[@]}" "configs/$config.toml" || echo "== $config: some runs failed (see runs.csv)"
  echo "== $config: $(( $(date +%s) - start )) s"
  "$bin" plot "$out/$config"
done
/usr/bin/python3 scripts/structures_tables.py "$out/structures" > /dev/null
/usr/bin/python3 scripts/purcell_tables.py "$out/purcell2002" > /dev/null
echo "== done: $out/{bunny,structures,purcell2002}"
