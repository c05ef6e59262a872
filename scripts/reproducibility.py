#!/usr/bin/python3
"""Is one run's time its own? The same run timed alone, inside its sweep, and in three fresh
processes, each against Embree on the same rays in the same process: the spread of the kernel's
median and of the speed ratio says whether the sweep around a run, or the process it ran in,
moves its time (a question a comparison between two folders rests on).

usage: /usr/bin/python3 scripts/reproducibility.py CONFIG FILTER [FILTER ...] [--sweep-filter F ...]
                                                    [--set KEY=VALUE ...] [--bin build/rtbench] [--keep DIR]

  FILTER          rtbench run --filter terms selecting exactly one run of CONFIG (key=value or label text)
  --sweep-filter  terms selecting the sweep the run is timed inside (default: the whole CONFIG)
  --set           passed to every rtbench run (e.g. experiment.repetitions=10)
  --keep DIR      keep the results folders in DIR (default: a temporary folder, removed)

Prints one line per setting (kernel ms and Embree rtcIntersect1 ms, medians with their intervals,
and their ratio), then max/min of the kernel medians and of the ratios over the five, and each
run's timing warning. Nothing here is a test: it measures this machine as it is now; run it on a
quiet machine. Exit 0 when every run was ok.
"""
import argparse
import csv
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def run(binary, config, out, filters, settings):
    """rtbench run into `out` with these filters and settings; its runs.csv rows (ok or not)."""
    command = [binary, "run", "-q", "-o", str(out), config]
    for term in filters:
        command += ["--filter", term]
    for setting in settings:
        command += ["--set", setting]
    done = subprocess.run(command, capture_output=True, text=True)
    folders = [p for p in Path(out).iterdir() if (p / "runs.csv").is_file()] if Path(out).is_dir() else []
    if not folders:
        sys.exit(f"reproducibility: {' '.join(command)} wrote no runs.csv (exit {done.returncode}):\n{done.stderr}")
    with open(folders[0] / "runs.csv", newline="") as rows:
        return list(csv.DictReader(rows))


def matching(rows, filters):
    """The one row the run filters select: every key=value term equal, every other term in the label."""
    def selected(row):
        for term in filters:
            key, _, value = term.partition("=")
            column = key.replace(".", "_")
            if value and column in row:
                if row[column] != value:
                    return False
            elif term not in row.get("label", ""):
                return False
        return True
    found = [row for row in rows if selected(row)]
    if len(found) != 1:
        sys.exit(f"reproducibility: the filters {filters} select {len(found)} runs of the sweep, not one")
    return found[0]


def describe(name, row):
    if row.get("status") != "ok":
        return f"{name:<22} FAILED: {row.get('error', '')}", None
    kernel, embree = float(row["kernel_ms_median"]), float(row["embree1_ms_median"])
    def interval(prefix):
        low, high = row.get(f"{prefix}_ms_ci_low", ""), row.get(f"{prefix}_ms_ci_high", "")
        return f"[{low}, {high}]" if low and high else "[no interval]"
    line = (f"{name:<22} kernel {kernel:10.4g} ms {interval('kernel'):<24} Embree1 {embree:10.4g} ms "
            f"{interval('embree1'):<24} kernel / Embree1 {kernel / embree:8.4g}")
    if row.get("timing_warning"):
        line += f"   [timing warning: {row['timing_warning']}]"
    return line, (kernel, kernel / embree)


def main() -> int:
    parser = argparse.ArgumentParser(add_help=True, usage=__doc__)
    parser.add_argument("config")
    parser.add_argument("filters", nargs="+")
    parser.add_argument("--sweep-filter", action="append", default=[])
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--bin", default=str(ROOT / "build" / "rtbench"))
    parser.add_argument("--keep")
    args = parser.parse_args()
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="rtbench-reproducibility."))
    work.mkdir(parents=True, exist_ok=True)
    try:
        settings = [("alone", args.filters), ("inside its sweep", args.sweep_filter)]
        settings += [(f"fresh process {i}", args.filters) for i in (1, 2, 3)]
        lines, values, ok = [], [], True
        for k, (name, filters) in enumerate(settings):
            print(f"[{k + 1}/{len(settings)}] {name} ...", file=sys.stderr, flush=True)
            rows = run(args.bin, args.config, work / f"{k}", filters, args.set)
            line, value = describe(name, matching(rows, args.filters))
            lines.append(line)
            ok &= value is not None
            if value:
                values.append(value)
        print("\n".join(lines))
        if len(values) >= 2:
            kernels, ratios = [v[0] for v in values], [v[1] for v in values]
            print(f"max / min over {len(values)}: kernel median {max(kernels) / min(kernels):.3f}, "
                  f"kernel / Embree1 {max(ratios) / min(ratios):.3f}")
        return 0 if ok else 1
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
