#!/usr/bin/python3
"""Every chart plot.py draws, read as a reader would: for every results folder in results/ and for
three synthetic folders (a shadow-ray sweep, a path-bounce sweep whose batch shrinks, one run), no
chart fails, no axes is drawn empty, and no legend entry stands for two series (two labels alike,
or two entries drawn alike).

usage: /usr/bin/python3 scripts/test_every_chart.py [-v] [TestCase ...]    exit 0: every chart passed
       /usr/bin/python3 scripts/test_every_chart.py FOLDER ...            the problems of these folders' charts

Over 20 s (about 90 s on a 2-core machine): it draws the hundred-odd charts of record, because a
chart's failure shows only on the data it is drawn from. Figures are laid out as plot.save lays
them out but not written to disk (the other plot tests check the files).
"""
import contextlib
import io
import os
import shutil
import sys
import tempfile
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
os.environ.setdefault("MPLCONFIGDIR", tempfile.mkdtemp(prefix="test_every_chart_mpl."))
os.environ["MPLBACKEND"] = "Agg"
sys.path.insert(0, str(HERE))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.colors as mcolors  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

import plot  # noqa: E402
from test_plot import make_runs, write_folder  # noqa: E402

RESULTS = HERE.parent / "results"
READ = ("runs.csv", "context.json", "columns.csv")  # what plot.py reads of a folder


def has_data(ax) -> bool:
    """Something drawn from data: a line with points, a scatter or error bars, a bar, an image."""
    if any(len(line.get_xdata()) for line in ax.get_lines()):
        return True
    if any(len(c.get_offsets()) or len(c.get_paths()) for c in ax.collections):
        return True
    return bool(ax.patches) or bool(ax.images)


def style(handle):
    """How a legend entry looks (None for a heading: an entry with no line, marker or patch)."""
    if isinstance(handle, Line2D):
        line = handle.get_linestyle() not in ("None", "none", "", " ")
        marker = handle.get_marker() not in ("None", "none", "", " ", None)
        if not line and not marker:
            return None
        face = handle.get_markerfacecolor()
        face = "#ffffff" if str(face).lower() == "none" else mcolors.to_hex(face)  # hollow on white: white
        return ("line", mcolors.to_hex(handle.get_color()), handle.get_linestyle() if line else "",
                handle.get_marker() if marker else "", face if marker else "", handle.get_fillstyle() if marker else "")
    if isinstance(handle, Patch):
        return ("patch", mcolors.to_hex(handle.get_facecolor()), handle.get_hatch())
    def hexes(colors):
        return tuple(mcolors.to_hex(c) for c in colors) if len(colors) else ("none",)
    paths = handle.get_paths() if hasattr(handle, "get_paths") else []
    shape = tuple(np.round(paths[0].vertices, 2).ravel()) if len(paths) else ()
    return ("collection", hexes(handle.get_facecolor()), hexes(handle.get_edgecolor()), shape)


def legend_problems(legend) -> list:
    labels = [t.get_text() for t in legend.get_texts()]
    handles = legend.legend_handles if hasattr(legend, "legend_handles") else legend.legendHandles
    problems = [f"legend entry {label!r} twice" for label in sorted(set(labels)) if labels.count(label) > 1]
    seen = {}
    for handle, label in zip(handles, labels):
        look = style(handle)
        if look is None:
            continue
        if look in seen and seen[look] != label:
            problems.append(f"legend entries {seen[look]!r} and {label!r} drawn alike")
        seen.setdefault(look, label)
    return problems


def figure_problems(name, fig) -> list:
    problems = []
    for i, ax in enumerate(fig.axes):
        if ax.axison and not has_data(ax):
            problems.append(f"{name}: axes {i} ({ax.get_title()[:60]!r}) drawn empty")
        legends = [ax.get_legend()] if ax.get_legend() else []
        problems += [f"{name}: {p}" for legend in legends for p in legend_problems(legend)]
    problems += [f"{name}: {p}" for legend in fig.legends for p in legend_problems(legend)]
    return problems


def audit(folder: Path) -> list:
    """Every chart of one folder drawn (laid out, not written): its problems, one line each."""
    problems, original_write = [], plot.write_atomically
    original_save = plot.save

    def checked(fig, folder_, name, written, rect=None):
        problems.extend(figure_problems(name, fig))
        original_save(fig, folder_, name, written, rect)
    plot.write_atomically = lambda fig, target, ext: None  # laid out by save (tight_layout draws); not written
    plot.save = checked
    err = io.StringIO()
    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            rc = plot.run(folder)
    except plot.PlotError as e:
        return [f"plot: {e}"]
    finally:
        plot.save, plot.write_atomically = original_save, original_write
    problems += [line for line in err.getvalue().splitlines() if "could not draw" in line]
    if rc != 0:
        problems.append(f"plot exit {rc}")
    return problems


def copy_of(folder: Path, root: Path) -> Path:
    target = root / folder.name
    target.mkdir()
    for name in READ:
        if (folder / name).is_file():
            shutil.copyfile(folder / name, target / name)
    return target


class ChartsOfRecord(unittest.TestCase):
    """Each folder of results/ is a subtest: its charts drawn as `rtbench plot` draws them."""

    def test_every_chart_of_every_results_folder(self):
        folders = sorted(f for f in RESULTS.iterdir() if (f / "runs.csv").is_file())
        self.assertGreater(len(folders), 5)
        with tempfile.TemporaryDirectory(prefix="test_every_chart.") as tmp:
            for folder in folders:
                with self.subTest(folder=folder.name):
                    problems = audit(copy_of(folder, Path(tmp)))
                    self.assertEqual(problems, [], "\n".join(problems))


class SyntheticFolders(unittest.TestCase):
    """Folders results/ does not hold: any-hit rays, a batch that shrinks, a single run."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_every_chart.")
        self.root = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_a_shadow_sweep(self):
        settings = [{"structure_type": "uniform_grid", "structure_min_dim": d} for d in (8, 16, 32, 64, 128)]
        settings.append({"structure_type": "bvh"})
        frame = make_runs(settings, ["structure_type", "structure_min_dim"])
        frame[["exact_distance_error_mean", "embree_exact_distance_error_mean"]] = np.nan
        frame["query"], frame["rays_type"] = "any", "shadow"
        self.assertEqual(audit(write_folder(self.root, "shadow", frame)), [])

    def test_a_path_bounce_sweep(self):
        settings = [{"structure_type": t, "strategy_type": s, "path_bounce": b}
                    for t in ("bvh", "uniform_grid") for s in ("branching", "multipass") for b in (1, 2, 3)]
        frame = make_runs(settings, ["structure_type", "strategy_type", "path_bounce"])
        frame["rays_type"] = "path"
        frame["rays"] = frame.path_bounce.map({1: 65536, 2: 9000, 3: 950})
        frame["exact_rays"] = frame.rays
        self.assertEqual(audit(write_folder(self.root, "paths", frame)), [])

    def test_one_run(self):
        frame = make_runs([{"structure_type": "bvh"}], [])
        self.assertEqual(audit(write_folder(self.root, "one", frame)), [])


def main() -> int:
    args = [a for a in sys.argv[1:] if Path(a).is_dir()]
    if args:  # folders named on the command line: their problems, not the suite
        problems = []
        with tempfile.TemporaryDirectory(prefix="test_every_chart.") as tmp:
            for folder in map(Path, args):
                problems += [f"{folder}: {p}" for p in audit(copy_of(folder, Path(tmp)))]
        print("\n".join(problems) or "no problems")
        return 1 if problems else 0
    return 0 if unittest.main(exit=False).result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
