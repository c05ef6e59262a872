#!/usr/bin/python3
"""The table scripts and plot read and write a results folder as plot.py always did: a file is
written through a temporary file renamed into place, never through a link planted where it goes;
a FIFO or device where a CSV belongs is refused at once, not waited on.

usage: /usr/bin/python3 scripts/test_results_io.py [-v]
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
RESULTS = HERE.parent / "results"
sys.path.insert(0, str(HERE))
import rtbench_results  # noqa: E402

TABLES = ["strategies_tables.py", "structures_tables.py", "raytypes_tables.py", "wavefront_tables.py",
          "purcell_tables.py", "division_tables.py", "christen_tables.py", "trees_tables.py", "order_tables.py"]
FOLDER = {"strategies_tables.py": "strategies", "structures_tables.py": "structures", "raytypes_tables.py": "raytypes",
          "wavefront_tables.py": "wavefront", "purcell_tables.py": "purcell2002", "division_tables.py": "division",
          "christen_tables.py": "christen2005", "trees_tables.py": "trees", "order_tables.py": "order"}


def copy_of(name: str, root: Path) -> Path:
    folder = root / name
    folder.mkdir()
    for file in ("runs.csv", "context.json", "columns.csv", "samples.csv"):
        if (RESULTS / name / file).exists():
            shutil.copyfile(RESULTS / name / file, folder / file)
    return folder


def run(script: str, folder: Path):
    env = dict(os.environ, MPLBACKEND="Agg", MPLCONFIGDIR=tempfile.mkdtemp(prefix="test_results_io_mpl."))
    return subprocess.run(["/usr/bin/python3", str(HERE / script), str(folder)], capture_output=True, text=True,
                          timeout=120, env=env)


class SpeedVerdict(unittest.TestCase):
    """Faster or slower only where the two 95% intervals separate."""

    def test_separated_overlapping_and_missing_intervals(self):
        verdict = rtbench_results.speed_verdict
        self.assertEqual(verdict((1.2, 1.4), (1.0, 1.1)), "faster")
        self.assertEqual(verdict((0.5, 0.9), (1.0, 1.1)), "slower")
        self.assertEqual(verdict((1.0, 1.2), (1.1, 1.3)), "tie")
        self.assertEqual(verdict((1.0, 1.1), (1.1, 1.3)), "tie")  # touching ends overlap
        self.assertEqual(verdict(None, (1.0, 1.1)), "not ranked")


class ResultsIo(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_results_io.")
        self.root = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_every_table_script_refuses_a_planted_link_and_leaves_its_target(self):
        for script in TABLES:
            with self.subTest(script=script):
                folder = copy_of(FOLDER[script], self.root)
                victim = self.root / f"victim-{script}"
                victim.write_text("keep\n")
                os.symlink(victim, folder / "tables.md")
                done = run(script, folder)
                self.assertNotEqual(done.returncode, 0, done.stdout)
                self.assertIn("is a symbolic link; refusing to write through it", done.stderr)
                self.assertEqual(victim.read_text(), "keep\n")
                self.assertTrue((folder / "tables.md").is_symlink())

    def test_a_table_script_writes_its_files_without_leaving_temporaries(self):
        folder = copy_of("strategies", self.root)
        done = run("strategies_tables.py", folder)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertTrue((folder / "tables.md").is_file())
        self.assertEqual([p.name for p in folder.iterdir() if p.name.endswith(".tmp")], [])

    def test_a_fifo_samples_csv_is_refused_not_waited_on(self):
        folder = copy_of("strategies", self.root)
        (folder / "samples.csv").unlink()
        os.mkfifo(folder / "samples.csv")
        done = run("strategies_tables.py", folder)  # the timeout fails the test if it hangs
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("not a regular file", done.stderr)
        with self.assertRaises(rtbench_results.UnsafePath):
            rtbench_results.read_samples(folder)

    def test_write_file_atomically_keeps_the_old_file_on_failure(self):
        target = self.root / "tables.md"
        target.write_text("old\n")

        def fail(out):
            out.write(b"half")
            raise RuntimeError("disk full")
        with self.assertRaises(RuntimeError):
            rtbench_results.write_file_atomically(target, fail)
        self.assertEqual(target.read_text(), "old\n")
        self.assertEqual([p.name for p in self.root.iterdir()], ["tables.md"])


if __name__ == "__main__":
    unittest.main()
