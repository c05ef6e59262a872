#!/usr/bin/python3
"""Writes `rtbench columns` into docs/columns.md between its markers (the test
Columns.TheColumnsPageIsTheDeclaredColumns keeps the page equal to the declarations).

usage: /usr/bin/python3 scripts/columns_page.py [RTBENCH_BINARY]     (default build/rtbench)
"""
import subprocess
import sys
from pathlib import Path

from rtbench_results import write_text_atomically

ROOT = Path(__file__).resolve().parent.parent
BEGIN, END = "<!-- columns: begin (rtbench columns) -->\n", "<!-- columns: end -->"


def main(args) -> int:
    binary = args[0] if args else str(ROOT / "build" / "rtbench")
    page = ROOT / "docs" / "columns.md"
    text = page.read_text()
    start, end = text.index(BEGIN) + len(BEGIN), text.index(END)
    table = subprocess.run([binary, "columns"], capture_output=True, text=True, check=True).stdout
    write_text_atomically(page, text[:start] + table + text[end:])
    print(page)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
