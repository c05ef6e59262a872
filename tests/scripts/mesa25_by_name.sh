#!/usr/bin/env bash
# Mesa 25's lavapipe as a device of record (issue 47 §4): with both lavapipes present (Debian's Mesa
# 22.3 and the backports' Mesa 25, added by VK_ADD_DRIVER_FILES; they share a device name), `-d "Mesa
# 25"` picks the newer one, whose driver's ray query then traces a run the exact reference judges,
# its Mesa version in the row; the same run on Debian's lavapipe (`-d "Mesa 22"`) fails naming what
# the device lacks.
#   mesa25_by_name.sh RTBENCH_BINARY WORK_DIR ICD_JSON
set -u
bin=$(realpath "$1")
work=$(realpath -m "$2")
icd=$(realpath "$3")
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
printf '[experiment]\nname = "m"\nrepetitions = 1\nwarmups = 0\n[scene]\nsource = "procedural:christen_b"\n[camera]\nwidth = 24\nheight = 16\n[structure]\ntype = "driver"\n[strategy]\ntype = "ray_query"\n[rays]\ntype = ["primary", "shadow"]\n[output]\nimages = false\n' > m.toml
export VK_ADD_DRIVER_FILES="$icd"
"$bin" run -q -d "Mesa 25" m.toml > run25.txt 2>&1 || { echo "FAILED: the run on Mesa 25 failed"; cat run25.txt; exit 1; }
/usr/bin/python3 - out/m/runs.csv <<'PY' || exit 1
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, f"{len(rows)} rows, not 2"
for r in rows:
    label = f"{r['rays_type']} rays"
    assert r["status"] == "ok", f"{label}: {r['status']} {r['error']}"
    assert r["driver"].startswith("llvmpipe Mesa 25."), f"{label}: driver {r['driver']!r}"
    assert r["exact_false_misses"] != "" and r["exact_false_hits"] != "", f"{label}: not judged by the exact reference"
    wrong = int(r["exact_false_misses"]) + int(r["exact_false_hits"]) + int(r["exact_wrong_primitive"] or 0)
    assert wrong * 100 <= int(r["rays"]), f"{label}: {wrong} of {r['rays']} rays contradict the exact reference"
    assert float(r["structure_build_ms"]) > 0, f"{label}: no build time of the driver's structure"
print("Mesa 25 by name: 2 runs ok, judged by the exact reference, driver", rows[0]["driver"])
PY
"$bin" run -q -d "Mesa 22" -o out22 m.toml > run22.txt 2>&1
[ $? -ne 0 ] || { echo "FAILED: Debian's lavapipe ran the driver's ray query"; cat out22/m/runs.csv; exit 1; }
grep -q "VK_KHR_ray_query" out22/m/runs.csv || { echo "FAILED: the failed row does not name the extension"; cat out22/m/runs.csv; exit 1; }
echo "Mesa 22 by name: refused, naming VK_KHR_ray_query"
