#!/usr/bin/python3
"""Mutation spot-check: does the test suite catch small deliberate bugs?

Copies the working tree to a scratch folder, builds it once, then applies each mutation of
scripts/mutations.tsv in turn (one literal replacement in one file), rebuilds, runs the whole
CTest suite and records which tests failed. A mutation is killed when any test fails; the report
says whether a test other than the golden check (tests named *golden* / Golden.*) kills it.

  scripts/mutate.py [--only N,M] [--keep SCRATCH]      (prints a Markdown table; exit 1 if any survives)

mutations.tsv: one per line, tab-separated: file, text to replace (must occur exactly once),
replacement, what the bug is. <TAB> and <NL> in the fields stand for a tab and a newline.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GOLDEN = re.compile(r"golden|Golden\.", re.IGNORECASE)


def load_mutations(path):
    mutations = []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                continue
            fields = line.rstrip("\n").split("\t")
            if len(fields) != 4:
                sys.exit(f"{path}:{number}: expected 4 tab-separated fields, got {len(fields)}")
            file, old, new, what = (x.replace("<TAB>", "\t").replace("<NL>", "\n") for x in fields)
            mutations.append({"line": number, "file": file, "old": old, "new": new, "what": what})
    return mutations


def run(cmd, cwd, timeout=1800):
    return subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=timeout)


def failed_tests(ctest_output):
    return re.findall(r"^\s*\d+ - (\S+) \(", ctest_output, re.MULTILINE)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", help="comma-separated line numbers of mutations.tsv to run")
    parser.add_argument("--keep", help="scratch folder to use and keep (default: a temporary one)")
    args = parser.parse_args()
    mutations = load_mutations(os.path.join(ROOT, "scripts", "mutations.tsv"))
    if args.only:
        wanted = {int(x) for x in args.only.split(",")}
        mutations = [m for m in mutations if m["line"] in wanted]

    scratch = args.keep or tempfile.mkdtemp(prefix="rtbench-mutate-")
    src = os.path.join(scratch, "src")
    if not os.path.isdir(src):
        ignore = shutil.ignore_patterns("build*", ".git", "out", "__pycache__")
        shutil.copytree(ROOT, src, ignore=ignore)
    build = os.path.join(scratch, "build")
    jobs = str(os.cpu_count() or 2)
    print(f"[mutate] {len(mutations)} mutation(s); scratch {scratch}", file=sys.stderr)
    r = run(["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release"], scratch)
    if r.returncode != 0:
        sys.exit(r.stdout[-3000:])
    r = run(["cmake", "--build", build, "-j", jobs], scratch)
    if r.returncode != 0:
        sys.exit("the unmutated tree does not build:\n" + r.stdout[-3000:])
    r = run(["ctest", "-j", jobs, "--timeout", "600"], build)
    if r.returncode != 0:
        sys.exit("the unmutated suite fails; fix that first:\n" + "\n".join(failed_tests(r.stdout)))

    rows = []
    for m in mutations:
        path = os.path.join(src, m["file"])
        with open(path, encoding="utf-8") as f:
            original = f.read()
        count = original.count(m["old"])
        if count != 1:
            rows.append((m, f"stale: found {count} times", []))
            continue
        with open(path, "w", encoding="utf-8") as f:
            f.write(original.replace(m["old"], m["new"]))
        start = time.time()
        try:
            r = run(["cmake", "--build", build, "-j", jobs], scratch)
            if r.returncode != 0:
                rows.append((m, "does not compile", []))
                continue
            # First without the golden check (stopping at the first failure), then the golden check
            # alone for what survives: a mutation only the goldens catch is reported as such.
            r = run(["ctest", "-j", jobs, "--timeout", "600", "-E", GOLDEN.pattern, "--stop-on-failure"], build)
            failed = failed_tests(r.stdout)
            if failed:
                rows.append((m, "killed", failed))
            else:
                r = run(["ctest", "-j", jobs, "--timeout", "600", "-R", GOLDEN.pattern], build)
                failed = failed_tests(r.stdout)
                rows.append((m, "killed (golden only)" if failed else "SURVIVED", failed))
        finally:
            with open(path, "w", encoding="utf-8") as f:
                f.write(original)
        print(f"[mutate] line {m['line']}: {rows[-1][1]} ({time.time() - start:.0f} s)", file=sys.stderr)
    run(["cmake", "--build", build, "-j", jobs], scratch)  # leave the scratch build unmutated

    killed = [r for r in rows if r[1].startswith("killed")]
    without_golden = [r for r in rows if r[1] == "killed"]
    valid = [r for r in rows if r[1].startswith("killed") or r[1] == "SURVIVED"]
    print("| # | file | bug | outcome | killed by (first 3) |\n|---|---|---|---|---|")
    for m, outcome, failed in rows:
        print(f"| {m['line']} | {m['file']} | {m['what']} | {outcome} | {', '.join(failed[:3])} |")
    print(f"\n{len(killed)} of {len(valid)} mutations killed; {len(without_golden)} by a test other than the golden check.")
    if not args.keep:
        shutil.rmtree(scratch, ignore_errors=True)
    return 0 if len(killed) == len(valid) else 1


if __name__ == "__main__":
    sys.exit(main())
