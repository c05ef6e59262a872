#!/usr/bin/python3
"""Mutation spot-check: does the test suite catch small deliberate bugs?

Copies the source tree to a scratch folder and builds it there ONCE; then, for each mutation of
scripts/mutations.tsv in turn (one literal replacement in one file): applies it, rebuilds
incrementally (only what depends on the mutated file), runs the CTest suite, and restores the
file, with a fresh modification time so that the next incremental build recompiles what the
mutation had changed. A mutation is killed when any test fails; the report says whether a test
other than the golden check (tests named *golden* / Golden.*) kills it, and sums up the kill rate
overall, per source folder and for the GLSL traversal sources (*.glsl) on their own.

  scripts/mutate.py [--only N,M,A-B] [--jobs J] [--keep SCRATCH] [--tests REGEX] [--exclude REGEX]
                    [--from-head [--overlay PATH[=FILE] ...]] [--check]

The suite runs in two stages per mutation, to find a kill sooner: first the tests most likely to
kill a bug in the mutated file's folder (FIRST below), stopping at the first failure; only if all
pass, the rest of the suite (without the golden check), then the golden check. Every surviving
mutation has therefore passed the whole suite. With --keep the scratch copy and its build are kept
and re-used: a second run syncs the files that changed and rebuilds only what they affect.

mutations.tsv: one per line, tab-separated: file, text to replace (must occur exactly once),
replacement, what the bug is. <TAB> and <NL> in the fields stand for a tab and a newline.
Exit status: 0 when every mutation that applies and compiles is killed, 1 otherwise, 2 on a
stale mutations.tsv (--check) or an unmutated tree that fails.
"""
import argparse
import collections
import filecmp
import os
import re
import shutil
import signal
import subprocess
import sys
import tarfile
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GOLDEN = "golden|Golden\\."
IGNORE = ("build", "build-*", ".git", "out", "__pycache__", "*.pyc")

# Tests to run first for a mutation in a folder (CTest regexes; the first matching prefix wins).
# Only an ordering: the rest of the suite runs after them when they all pass.
FIRST = [
    ("kernels/", "TieRule|WatertightEdge|BvhHand|GridHand|KernelNumerics|BranchingKernel|MultipassKernels|Bvh|Brute|Dda"),
    ("structures/bvh/", "BvhHand|TieRule|WatertightEdge|Bvh"),
    ("structures/uniform_grid/", "GridHand|TieRule|WatertightEdge|Dda|Grid|KernelNumerics|MultipassKernels|BranchingKernel"),
    ("structures/brute_force/", "TieRule|WatertightEdge|Brute"),
    ("strategies/multipass/", "MultipassKernels|BvhHand|GridHand|Multipass|Schedule"),
    ("methods/accounting", "BvhHand|GridHand|MultipassKernels|Metrics"),
    ("methods/metrics", "Metrics|EndToEnd"),
    ("methods/", "CostModel|TriangleStore|Metrics|Auto"),
    ("harness/", "Config|Check|Output|Exact|Image|EndToEnd|cli\\."),
    ("scene/", "Mesh|Scene|Simplify|Corpus|Limits|Camera"),
    ("core/", "Mesh|Scene|Config|Output|Writers"),
]


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


def parse_lines(spec):
    wanted = set()
    for part in spec.split(","):
        part = part.strip()
        if "-" in part:
            lo, hi = part.split("-", 1)
            wanted.update(range(int(lo), int(hi) + 1))
        elif part:
            wanted.add(int(part))
    return wanted


def run(cmd, cwd, timeout=None):
    return subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=timeout)


def failed_tests(ctest_output):
    return re.findall(r"^\s*\d+ - (\S+) \(", ctest_output, re.MULTILINE)


def ignored(name):
    import fnmatch
    return any(fnmatch.fnmatch(name, p) for p in IGNORE)


def export_head(dest, overlays):
    """HEAD's tree (git archive) into dest, then the working tree's files at the overlay paths."""
    if os.path.isdir(dest):
        shutil.rmtree(dest)
    os.makedirs(dest)
    archive = subprocess.run(["git", "-C", ROOT, "archive", "--format=tar", "HEAD"], stdout=subprocess.PIPE, check=True)
    with tempfile.TemporaryFile() as f:
        f.write(archive.stdout)
        f.seek(0)
        with tarfile.open(fileobj=f) as tar:
            tar.extractall(dest)
    for spec in overlays:
        rel, _, other = spec.partition("=")
        src = other or os.path.join(ROOT, rel)
        if os.path.isdir(src):
            shutil.copytree(src, os.path.join(dest, rel), dirs_exist_ok=True,
                            ignore=shutil.ignore_patterns(*IGNORE))
        elif os.path.isfile(src):
            os.makedirs(os.path.dirname(os.path.join(dest, rel)), exist_ok=True)
            shutil.copy2(src, os.path.join(dest, rel))
        else:
            sys.exit(f"--overlay {spec}: no such file or folder")


def sync_tree(source, dest):
    """Makes dest's files equal source's, touching only what differs (so a kept build stays
    incremental). Returns the number of files written or removed."""
    changed = 0
    for dirpath, dirnames, filenames in os.walk(source):
        dirnames[:] = [d for d in dirnames if not ignored(d)]
        rel = os.path.relpath(dirpath, source)
        target_dir = os.path.normpath(os.path.join(dest, rel))
        os.makedirs(target_dir, exist_ok=True)
        wanted = set(filenames) | set(dirnames)
        for name in filenames:
            if ignored(name):
                continue
            s, d = os.path.join(dirpath, name), os.path.join(target_dir, name)
            if os.path.islink(s):
                continue
            if not os.path.isfile(d) or not filecmp.cmp(s, d, shallow=False):
                shutil.copyfile(s, d)  # a new modification time: what depends on it rebuilds
                changed += 1
        for name in os.listdir(target_dir):
            if name not in wanted and not ignored(name):
                path = os.path.join(target_dir, name)
                if os.path.isfile(path) or os.path.islink(path):
                    os.remove(path)
                else:
                    shutil.rmtree(path)
                changed += 1
    return changed


def write_newer(path, text, than_ns):
    """Writes text to path with a modification time after than_ns (even on a file system whose
    clock granularity is coarse), so make sees it as newer than anything built before."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    mtime = os.stat(path).st_mtime_ns
    if mtime <= than_ns:
        stamp = than_ns + 1_000_000
        os.utime(path, ns=(stamp, stamp))
        while os.stat(path).st_mtime_ns <= than_ns:  # granularity coarser than 1 ms
            stamp += 1_000_000_000
            os.utime(path, ns=(stamp, stamp))
        while time.time_ns() < os.stat(path).st_mtime_ns:  # let the clock pass it: no "future" mtime
            time.sleep(0.01)


def folder_of(file):
    return os.path.dirname(file) or "."


def first_tests(file, only):
    if only:
        return None
    for prefix, regex in FIRST:
        if file.startswith(prefix):
            return regex
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", help="line numbers of mutations.tsv to run: N,M,A-B")
    parser.add_argument("--jobs", "-j", type=int, default=os.cpu_count() or 2,
                        help="parallel build jobs and CTest tests (default: the CPU count)")
    parser.add_argument("--keep", help="scratch folder to use and keep (default: a temporary one, removed)")
    parser.add_argument("--tests", help="CTest regex: run only these tests (a quick check; not a full kill rate)")
    parser.add_argument("--exclude", help="CTest regex: leave these tests out of every run (e.g. to measure what the "
                                          "rest of the suite kills without them)")
    parser.add_argument("--from-head", action="store_true",
                        help="mutate git HEAD's tree instead of the working tree (others' work in progress left out)")
    parser.add_argument("--overlay", action="append", default=[],
                        help="with --from-head: a working-tree file or folder copied over HEAD's, or PATH=FILE: "
                             "FILE copied to PATH (repeatable)")
    parser.add_argument("--test-timeout", type=int, default=600, help="seconds per test (CTest --timeout)")
    parser.add_argument("--check", action="store_true",
                        help="only check that every selected mutation applies exactly once (no build)")
    args = parser.parse_args()
    mutations = load_mutations(os.path.join(ROOT, "scripts", "mutations.tsv"))
    if args.only:
        wanted = parse_lines(args.only)
        mutations = [m for m in mutations if m["line"] in wanted]
    jobs = str(max(1, args.jobs))

    scratch = args.keep or tempfile.mkdtemp(prefix="rtbench-mutate-")
    os.makedirs(scratch, exist_ok=True)
    src = os.path.join(scratch, "src")
    build = os.path.join(scratch, "build")
    if args.from_head:
        head = os.path.join(scratch, "head")
        export_head(head, args.overlay)
        source = head
    else:
        source = ROOT

    # Every mutation must apply exactly once, to the tree that will be built.
    stale = []
    for m in mutations:
        path = os.path.join(source, m["file"])
        count = open(path, encoding="utf-8").read().count(m["old"]) if os.path.isfile(path) else 0
        m["applies"] = count == 1
        if count != 1:
            stale.append(f"line {m['line']} ({m['file']}): found {count} times")
    if args.check:
        print("\n".join(stale) if stale else f"{len(mutations)} mutation(s), each applies exactly once")
        if not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)
        return 2 if stale else 0

    start_all = time.time()
    fresh = not os.path.isdir(src)
    changed = sync_tree(source, src)
    print(f"[mutate] {len(mutations)} mutation(s); scratch {scratch} "
          f"({'new copy' if fresh else f'{changed} file(s) synced'}); {jobs} jobs", file=sys.stderr)
    if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
        r = run(["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release"], scratch)
        if r.returncode != 0:
            sys.exit(r.stdout[-3000:])
    t0 = time.time()
    r = run(["cmake", "--build", build, "-j", jobs], scratch)
    built_ns = time.time_ns()  # everything the build wrote is older than this
    if r.returncode != 0:
        print("the unmutated tree does not build:\n" + r.stdout[-3000:], file=sys.stderr)
        return 2
    print(f"[mutate] unmutated build {time.time() - t0:.0f} s", file=sys.stderr)
    ctest = ["ctest", "-j", jobs, "--timeout", str(args.test_timeout)]
    selection = (["-R", args.tests] if args.tests else []) + (["-E", args.exclude] if args.exclude else [])
    excl = f"|{args.exclude}" if args.exclude else ""
    t0 = time.time()
    r = run(ctest + selection, build)
    if r.returncode != 0:
        print("the unmutated suite fails; fix that first:\n" + "\n".join(failed_tests(r.stdout) or [r.stdout[-2000:]]),
              file=sys.stderr)
        return 2
    print(f"[mutate] unmutated suite passes ({time.time() - t0:.0f} s)", file=sys.stderr)

    # SIGTERM as Ctrl-C: the mutated file is restored (the finally below) and the rows so far reported.
    def interrupted(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, interrupted)
    rows = []
    try:
        run_mutations(mutations, rows, args, src, build, scratch, jobs, ctest, selection, excl, built_ns)
    except KeyboardInterrupt:
        print(f"[mutate] interrupted after {len(rows)} mutation(s); the scratch copy is unmutated", file=sys.stderr)
    run(["cmake", "--build", build, "-j", jobs], scratch)  # leave the scratch build unmutated
    report(rows, start_all)
    if not args.keep:
        shutil.rmtree(scratch, ignore_errors=True)
    valid = [r for r in rows if r[1].startswith("killed") or r[1].startswith("SURVIVED")]
    return 0 if all(r[1].startswith("killed") for r in valid) and len(rows) == len(mutations) else 1


def run_mutations(mutations, rows, args, src, build, scratch, jobs, ctest, selection, excl, built_ns):
    for m in mutations:
        if not m["applies"]:
            rows.append((m, "stale: does not apply exactly once", [], 0.0, 0.0))
            continue
        path = os.path.join(src, m["file"])
        with open(path, encoding="utf-8") as f:
            original = f.read()
        start = time.time()
        build_s = test_s = 0.0
        write_newer(path, original.replace(m["old"], m["new"]), built_ns)
        try:
            r = run(["cmake", "--build", build, "-j", jobs], scratch)
            if r.returncode != 0:  # once more: a transient failure (e.g. test discovery timing out under load)
                r = run(["cmake", "--build", build, "-j", jobs], scratch)
            built_ns = time.time_ns()
            build_s = time.time() - start
            t0 = time.time()
            if r.returncode != 0:
                outcome, failed = "does not compile", []
                errors = [line for line in r.stdout.splitlines() if "error" in line.lower()]
                print("\n".join(errors[:5] or r.stdout.splitlines()[-5:]), file=sys.stderr)
            elif args.tests:
                failed = failed_tests(run(ctest + selection, build).stdout)
                outcome = "killed" if failed else "SURVIVED (the selected tests)"
            else:
                # Stage 1: the tests likeliest to kill it; stage 2: the rest but the golden check;
                # then the golden check alone (a mutation only the goldens catch is said so).
                failed = []
                first = first_tests(m["file"], args.tests)
                if first:
                    failed = failed_tests(run(ctest + ["-R", first, "-E", GOLDEN + excl, "--stop-on-failure"], build).stdout)
                if not failed:
                    rest = ["-E", (f"{GOLDEN}|{first}" if first else GOLDEN) + excl]
                    failed = failed_tests(run(ctest + rest + ["--stop-on-failure"], build).stdout)
                if failed:
                    outcome = "killed"
                else:
                    failed = failed_tests(run(ctest + ["-R", GOLDEN] + (["-E", args.exclude] if args.exclude else []),
                                              build).stdout)
                    outcome = "killed (golden only)" if failed else "SURVIVED"
            test_s = time.time() - t0
            rows.append((m, outcome, failed, build_s, test_s))
        finally:
            # Restore the file, newer than everything the mutated build wrote: the next build
            # recompiles what the mutation changed (with the next mutation's own rebuild).
            write_newer(path, original, built_ns)
        print(f"[mutate] line {m['line']}: {rows[-1][1]} (build {build_s:.0f} s, tests {test_s:.0f} s)", file=sys.stderr)


def report(rows, start_all):
    print("| # | file | bug | outcome | build s | tests s | killed by (first 3) |\n|---|---|---|---|---|---|---|")
    for m, outcome, failed, build_s, test_s in rows:
        print(f"| {m['line']} | {m['file']} | {m['what']} | {outcome} | {build_s:.0f} | {test_s:.0f} | "
              f"{', '.join(failed[:3])} |")
    valid = [r for r in rows if r[1].startswith("killed") or r[1].startswith("SURVIVED")]
    killed = [r for r in valid if r[1].startswith("killed")]

    def rate(subset):
        k = sum(1 for r in subset if r[1].startswith("killed"))
        return f"{k} of {len(subset)} killed ({100.0 * k / len(subset):.0f}%)" if subset else "none"

    print(f"\nOverall: {rate(valid)}; {sum(1 for r in valid if r[1] == 'killed')} by a test other than the golden check.")
    by_folder = collections.defaultdict(list)
    for r in valid:
        by_folder[folder_of(r[0]["file"])].append(r)
    for folder in sorted(by_folder):
        print(f"  {folder}/: {rate(by_folder[folder])}")
    print(f"  GLSL traversal sources (*.glsl): {rate([r for r in valid if r[0]['file'].endswith('.glsl')])}")
    others = [r for r in rows if r not in valid]
    if others:
        print(f"Not counted: {len(others)} ({', '.join(sorted(set(r[1] for r in others)))})")
    timed = [r for r in valid]
    if timed:
        print(f"Time per mutation: build {sum(r[3] for r in timed) / len(timed):.0f} s, "
              f"tests {sum(r[4] for r in timed) / len(timed):.0f} s (mean); total {time.time() - start_all:.0f} s")


if __name__ == "__main__":
    sys.exit(main())
