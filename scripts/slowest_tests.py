#!/usr/bin/python3
"""The slowest tests of a CTest run and the suite's total, from its JUnit file (ctest --output-junit).

usage: scripts/slowest_tests.py JUNIT_XML [N]     (N: how many, default 20)
docs/testing.md: a new test over 20 s says why, where it is declared.
"""
import sys
import xml.etree.ElementTree as ET


def main() -> int:
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        return 2
    try:
        root = ET.parse(sys.argv[1]).getroot()
    except (OSError, ET.ParseError) as e:
        print(f"slowest_tests: {sys.argv[1]}: {e}", file=sys.stderr)
        return 1
    n = int(sys.argv[2]) if len(sys.argv) == 3 else 20
    cases = sorted(((float(c.get("time", 0)), c.get("name", "?"), c.get("status", "")) for c in root.iter("testcase")),
                   reverse=True)
    total = sum(t for t, _, _ in cases)
    print(f"[tests] {len(cases)} tests, {total:.0f} s of test time in all; the {min(n, len(cases))} slowest:")
    for t, name, status in cases[:n]:
        print(f"[tests] {t:7.1f} s  {name}{'' if status in ('run', '') else '  (' + status + ')'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
