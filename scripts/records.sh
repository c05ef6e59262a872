#!/bin/bash
# Runs the configs of record and makes their charts and tables: results/bunny, results/structures, results/builds,
# results/purcell2002, results/stability, results/accuracy, results/raytypes, results/strategies, results/multipass_device, results/division, results/control, results/driver, results/christen2005, results/wavefront, results/trees, results/order (or under OUT, e.g. results/nvidia-h200 on a GPU machine; DEVICE picks the
# Vulkan device by a name substring).
#   scripts/records.sh [OUT] [DEVICE]        (about 3.5 hours on 2 cores with lavapipe; purcell2002 alone 112 minutes)
# Environment:
#   RTBENCH_BIN=path      the rtbench binary (default build/rtbench)
#   EMBREE_CONFIG=isa=avx2  Embree device config for every run (where its default ISA crashes)
#   CHARTS=0              run only (a machine without Python); later `scripts/records.sh --charts OUT`
#                         draws the charts and tables here
#   RETIME=2              re-time each config's flagged runs up to this many tries (0: none)
#   CONFIGS="bunny ..."   only these configs of record (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
configs=(${CONFIGS:-bunny structures builds purcell2002 stability accuracy raytypes strategies multipass_device division control driver christen2005 wavefront trees order})
bin=${RTBENCH_BIN:-build/rtbench}

charts() {
  local out=$1
  for config in "${configs[@]}"; do
    [ -f "$out/$config/runs.csv" ] || { echo "== $config: no $out/$config/runs.csv: no charts"; continue; }
    # PNGs from the hit records that a binary built without OpenImageIO writes instead
    if compgen -G "$out/$config/*.hits" > /dev/null; then "$bin" images "$out/$config"; fi
    "$bin" plot "$out/$config"
  done
  /usr/bin/python3 scripts/structures_tables.py "$out/structures" > /dev/null
  /usr/bin/python3 scripts/purcell_tables.py "$out/purcell2002" > /dev/null
  /usr/bin/python3 scripts/raytypes_tables.py "$out/raytypes" > /dev/null
  /usr/bin/python3 scripts/strategies_tables.py "$out/strategies" > /dev/null
  /usr/bin/python3 scripts/division_tables.py "$out/division" > /dev/null
  /usr/bin/python3 scripts/christen_tables.py "$out/christen2005" > /dev/null
  /usr/bin/python3 scripts/wavefront_tables.py "$out/wavefront" > /dev/null
  /usr/bin/python3 scripts/trees_tables.py "$out/trees" > /dev/null
  /usr/bin/python3 scripts/order_tables.py "$out/order" > /dev/null
}

if [ "${1:-}" = "--charts" ]; then
  charts "${2:?usage: scripts/records.sh --charts OUT}"
  exit 0
fi

out=${1:-results}
device=${2:-}
args=(-o "$out")
[ -n "$device" ] && args+=(-d "$device")
[ -n "${EMBREE_CONFIG:-}" ] && args+=(--embree-config "$EMBREE_CONFIG")
for config in "${configs[@]}"; do
  echo "== $config -> $out/$config"
  start=$(date +%s)
  # A failed run is a result too (a row naming why); rtbench then exits 1.
  # --force re-runs every run; the rows it replaces (the last record's, which git keeps) are set
  # aside in superseded-* files (rtbench never drops a row): removed here. Retime's superseded-*
  # files below are the flagged timings it replaced, and stay with the record.
  # configs/driver.toml names both lavapipes (Debian's and Mesa 25's, which scripts/setup.sh unpacks
  # into the build folder): the loader is told of the second for it alone.
  driver_files=()
  [ "$config" = driver ] && driver_files=(env VK_ADD_DRIVER_FILES="$PWD/build/lavapipe-ray-query/lvp_icd.json")
  "${driver_files[@]}" "$bin" run --force "${args[@]}" "configs/$config.toml" || echo "== $config: some runs failed (see runs.csv)"
  rm -f "$out/$config"/superseded-*
  # The runs the noise guard flagged, re-timed (RETIME tries each; column retimed says which try
  # was kept and why); a count that moved fails it, and the record stays as it was.
  [ "${RETIME:-2}" = 0 ] || "${driver_files[@]}" "$bin" retime "$out/$config" --tries "${RETIME:-2}" || echo "== $config: retime refused (see above)"
  echo "== $config: $(( $(date +%s) - start )) s"
done
[ "${CHARTS:-1}" = 0 ] || charts "$out"
echo "== done: ${configs[*]/#/$out/}"
