#!/usr/bin/python3
"""Tests of scripts/plot.py on small synthetic results folders (Debian's python3-matplotlib and
python3-pandas; headless, Agg).

usage: /usr/bin/python3 scripts/test_plot.py [-v] [TestCase.test_name ...]     exit 0: all passed

Each test writes a runs.csv (config key columns first, then `run`, as rtbench writes them) and a
context.json into a temporary folder, runs the charts, and checks what they drew: one by_<key> chart
per swept key (keys no other chart knows among them), one stderr line per skipped chart, panel titles
that name the image sizes in the panel, a 0..1 axis saying "all zero" for all-zero data, error bars
from the interval columns when present, bars labelled by the swept value, failure-map
markers without lines and legends off the data, float vertices apart, titles that fit.
"""
import contextlib
import io
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
os.environ.setdefault("MPLCONFIGDIR", tempfile.mkdtemp(prefix="test_plot_mpl."))
os.environ["MPLBACKEND"] = "Agg"
sys.path.insert(0, str(HERE))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.collections import LineCollection, PathCollection  # noqa: E402

import plot  # noqa: E402
import rtbench_results  # noqa: E402

# Config key columns as rtbench writes them (before `run`), a subset of `rtbench keys`.
PARAMETERS = ["experiment_name", "experiment_output", "experiment_repetitions", "scene_source", "scene_scale",
              "scene_translate", "camera_width", "camera_height", "camera_look_at", "camera_fov_deg",
              "structure_type", "structure_min_dim", "structure_conservative", "structure_leaf_size",
              "strategy_type", "strategy_workgroup_size", "strategy_traverse_steps_per_pass",
              "strategy_intersections_per_pass", "strategy_suppress_finished_reads", "strategy_scheduling",
              "strategy_oracle_threshold", "rays_type", "path_bounce", "intersection_test", "intersection_vertex_bits"]
DEFAULTS = {"experiment_name": "synthetic", "experiment_output": "out", "experiment_repetitions": 5,
            "scene_source": "cgal:bunny00", "scene_scale": 1.0, "scene_translate": "[0 0 0]", "camera_width": 256,
            "camera_height": 256, "camera_fov_deg": 45, "structure_type": "bvh", "strategy_type": "branching",
            "strategy_workgroup_size": 64, "intersection_test": "moller_trumbore", "intersection_vertex_bits": 32}
SWEEP_KEY = {c: c.replace("_", ".", 1) for c in PARAMETERS}  # camera_fov_deg -> camera.fov_deg


def make_runs(settings, swept, sweep="sweep", failed=()):
    """Rows for runs.csv: one per dict of `settings` (config columns over DEFAULTS), with a label naming
    the `swept` keys, deterministic metrics (times from the settings, two wrong rays) and status ok, or
    failed for the indices in `failed`."""
    rows = []
    for i, given in enumerate(settings):
        row = {c: np.nan for c in PARAMETERS}
        row.update(DEFAULTS)
        if given.get("structure_type", "bvh") == "bvh":
            row["structure_leaf_size"] = 4
        if given.get("structure_type") == "uniform_grid":
            row["structure_min_dim"], row["structure_conservative"] = 64, False
        row.update(given)
        labels = " ".join(f"{SWEEP_KEY[k]}={row[k]}" for k in swept)
        row.update(run=f"{i:03d}", label=f"{sweep}:{labels}" if sweep else labels,
                   status="failed" if i in failed else "ok", error="refused" if i in failed else "",
                   config_hash=f"{i:016x}")
        rays = int(row["camera_width"]) * int(row["camera_height"])
        ms = 10.0 + 3.0 * i  # each run its own time: the tests find their points by it
        row.update(scene_triangles=1000, scene_full_triangles=1000, rays=rays,
                   kernel_ms_median=ms, kernel_ms_min=ms * 0.9, kernel_ms_max=ms * 1.2,
                   kernel_mrays_s=rays / ms / 1e3, embree1_ms_median=5.0, embree1_ms_min=4.5, embree1_ms_max=6.0,
                   embree1_mrays_s=rays / 5.0 / 1e3, speed_ratio_vs_embree1=5.0 / ms,
                   exact_rays=rays, exact_false_misses=1, exact_false_hits=1, exact_wrong_primitive=0,
                   exact_wrong_ppm=2e6 / rays, exact_distance_error_mean=1e-7, embree_exact_false_misses=0,
                   embree_exact_false_hits=0, embree_exact_wrong_primitive=0, embree_exact_wrong_ppm=0.0,
                   embree_exact_distance_error_mean=5e-8, structure_bytes_per_triangle=100.0, structure_build_ms=3.0,
                   predicted_work_per_ray=20.0, work_per_ray_mean=18.0, simd_efficiency=0.8,
                   bytes_stencil=1e6, bytes_state=2e6, bytes_voxel=3e6 + 1e5 * i, bytes_vertices=4e6, bytes_output=1e5,
                   passes_total=1)
        if row["status"] == "failed":
            for c in ("kernel_ms_median", "kernel_ms_min", "kernel_ms_max", "exact_rays", "exact_wrong_ppm"):
                row[c] = np.nan
        rows.append(row)
    frame = pd.DataFrame(rows)
    metrics = [c for c in frame.columns if c not in PARAMETERS]
    return frame[PARAMETERS + metrics]


def write_folder(root: Path, name: str, frame, device="test device (synthetic)") -> Path:
    folder = root / name
    folder.mkdir()
    frame.to_csv(folder / "runs.csv", index=False)
    context = {"config_text": "# synthetic\n[experiment]\nname = \"synthetic\"\n", "complete": True,
               "devices": [{"name": device}]}
    (folder / "context.json").write_text(json.dumps(context))
    return folder


class Charts:
    """plot.run on a folder with plot.save wrapped: the figures drawn (by chart name) after they were
    laid out and written, and what plot.py said on stdout and stderr."""

    def __init__(self, folder: Path, verbose=True):
        self.figures, original = {}, plot.save
        plot.VERBOSE = verbose

        def keep(fig, folder_, name, written, rect=None):
            original(fig, folder_, name, written, rect)
            self.figures[name] = fig
        out, err = io.StringIO(), io.StringIO()
        plot.save = keep
        try:
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                self.rc = plot.run(folder)
        finally:
            plot.save = original
        self.stdout, self.stderr = out.getvalue(), err.getvalue()


def data_axes(fig):
    return [ax for ax in fig.axes if ax.axison]


def kernel_points(ax) -> int:
    """Points of the kernels in a speed_vs_accuracy panel (marker-only lines; Embree's black squares
    and the Pareto front left out)."""
    scattered = sum(len(c.get_offsets()) for c in ax.collections
                    if isinstance(c, PathCollection) and not str(c.get_label()).startswith("Embree"))
    return scattered + sum(len(line.get_xdata()) for line in ax.get_lines()
                           if line.get_linestyle() in ("None", "none", "") and line.get_marker() not in ("None", "none", "")
                           and matplotlib.colors.to_hex(line.get_color()) != "#000000")


class ByKeyCharts(unittest.TestCase):
    """One by_<key> chart per swept key, whatever the key."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_plot.")
        self.root = Path(self.tmp.name)
        # Two keys no named chart knows (leaf size, field of view), crossed, over two scenes and two
        # strategies; one failed run at a work-group size no successful run has.
        settings = [{"scene_source": scene, "strategy_type": strategy, "structure_leaf_size": leaf,
                     "camera_fov_deg": fov}
                    for scene in ("cgal:bunny00", "procedural:christen_a") for strategy in ("branching", "multipass")
                    for leaf in (2, 4, 8) for fov in (30, 60)]
        settings.append({"structure_leaf_size": 4, "camera_fov_deg": 30, "strategy_workgroup_size": 128})
        self.frame = make_runs(settings, ["scene_source", "strategy_type", "structure_leaf_size", "camera_fov_deg"],
                               failed={len(settings) - 1})
        self.folder = write_folder(self.root, "sweep", self.frame)

    def tearDown(self):
        self.tmp.cleanup()

    def test_one_chart_per_swept_key(self):
        result = subprocess.run([sys.executable, str(HERE / "plot.py"), str(self.folder)], capture_output=True,
                                text=True, timeout=600)
        self.assertEqual(result.returncode, 0, result.stderr)
        drawn = {p.stem for p in self.folder.glob("by_*.png")}
        swept = {"by_scene_source", "by_strategy_type", "by_structure_leaf_size", "by_camera_fov_deg"}
        self.assertEqual(drawn, swept, result.stderr)
        for name in swept:
            for ext in ("png", "svg"):
                self.assertGreater((self.folder / f"{name}.{ext}").stat().st_size, 1000, f"{name}.{ext}")

    def test_a_vector_key_is_one_chart_in_three_columns_or_one(self):
        """camera.look_at written as three columns (results schema 6) or one "[x y z]" cell (before): one
        by_camera_look_at chart either way, not one per component."""
        settings = [{"camera_look_at": f"[{x} 0 {z}]"} for x, z in ((0, 0), (1, 0), (1, 1))]
        for form in ("one cell", "three columns"):
            frame = make_runs(settings, ["camera_look_at"])
            if form == "three columns":
                cells = frame.camera_look_at.str.strip("[]").str.split(" ", expand=True).astype(float)
                at = frame.columns.get_loc("camera_look_at")
                for a, axis in enumerate("xyz"):
                    frame.insert(at + a, f"camera_look_at_{axis}", cells[a])
                frame = frame.drop(columns="camera_look_at")
            charts = Charts(write_folder(self.root, form.replace(" ", "_"), frame))
            self.assertEqual(charts.rc, 0, charts.stderr)
            drawn = {name for name in charts.figures if name.startswith("by_")}
            self.assertEqual(drawn, {"by_camera_look_at"}, form)

    def test_every_chart_is_written_or_says_why_it_is_not(self):
        charts = Charts(self.folder)
        self.assertEqual(charts.rc, 0)
        written = set(re.search(r"wrote \d+ chart\(s\): (.*) \(\.png", charts.stdout).group(1).split(", "))
        lines = charts.stderr.splitlines()
        pattern = re.compile(rf"^rtbench plot: {re.escape(str(self.folder))}: skipped (\S+): (.+)$")
        for line in lines:
            self.assertRegex(line, pattern)
        skipped = {pattern.match(line).group(1): pattern.match(line).group(2) for line in lines}
        named = {"speed_vs_accuracy", "vertex_precision", "simplification", "passes_vs_threshold",
                 "bandwidth_by_category", "unrolling", "grid_resolution", "kernel_time", "structures_time",
                 "structures_memory", "structures_work", "failure_map"}
        self.assertEqual(named - written, named & set(skipped), "every named chart written or skipped")
        self.assertFalse(written & set(skipped), "no chart both written and skipped")
        # The reasons that were silent before.
        self.assertIn("grid resolutions", skipped["grid_resolution"])
        self.assertIn("structure", skipped["structures_time"])
        self.assertIn("kernel_ms_setup", skipped["kernel_time"])  # multipass runs, but no per-kernel times
        # A key only a failed run varies: its chart says so.
        self.assertIn("by_strategy_workgroup_size", skipped)
        self.assertIn("every successful run", skipped["by_strategy_workgroup_size"])

    def test_a_by_key_chart_has_a_row_per_scene_and_a_colour_per_method(self):
        charts = Charts(self.folder)
        fig = charts.figures["by_structure_leaf_size"]
        titles = [ax.get_title() for ax in data_axes(fig)]
        self.assertEqual(len(titles), 4, titles)  # 2 scenes x (time, rays wrong)
        self.assertTrue(any(t.startswith("bunny") for t in titles) and any(t.startswith("scene A") for t in titles))
        legend = [t.get_text() for ax in fig.axes for t in (ax.get_legend().get_texts() if ax.get_legend() else [])]
        for method in ("bvh branching", "bvh multipass", "Embree rtcIntersect1 (CPU, the same rays)"):
            self.assertIn(method, legend)
        self.assertTrue(any("camera_fov_deg=30" in t for t in legend), legend)  # the other key: a marker each
        self.assertIn("min-max of the repetitions", " ".join(t.get_text() for t in fig.texts))


class EmbreeBesideWholePaths(unittest.TestCase):
    """Beside a whole-path strategy (wavefront, path_megakernel) Embree traces every generation of the
    path, beside branching only the batch: two Embree series, never one median over both kinds."""

    def test_embree_gets_a_series_per_kind_of_run(self):
        with tempfile.TemporaryDirectory(prefix="test_plot.") as tmp:
            settings = [{"structure_leaf_size": leaf, "strategy_type": strategy}
                        for strategy in ("branching", "wavefront") for leaf in (2, 4, 8)]
            frame = make_runs(settings, ["structure_leaf_size", "strategy_type"])
            whole = frame.strategy_type == "wavefront"
            frame["whole_path_rays"] = np.where(whole, 3 * frame.rays, np.nan)
            frame.loc[whole, ["embree1_ms_median", "embree1_ms_min", "embree1_ms_max"]] = [15.0, 14.0, 16.0]
            charts = Charts(write_folder(Path(tmp), "paths", frame))
            self.assertEqual(charts.rc, 0, charts.stderr)
            fig = charts.figures["by_structure_leaf_size"]
            time = data_axes(fig)[0]
            black = [line for line in time.get_lines()  # Embree's lines through its medians (not the bars' caps)
                     if matplotlib.colors.to_hex(line.get_color()) == "#000000" and line.get_linestyle() != "None"]
            levels = sorted({round(float(y), 6) for line in black for y in line.get_ydata()})
            self.assertEqual(levels, [5.0, 15.0])  # not 10, the median over both kinds
            legend = " ".join(" ".join(t.get_text().split()) for ax in fig.axes
                              for t in (ax.get_legend().get_texts() if ax.get_legend() else []))
            self.assertIn("Embree rtcIntersect1 (CPU, the same rays)", legend)
            self.assertIn("every generation of the path", legend)
            self.assertIn("Diamonds", " ".join(t.get_text() for t in fig.texts))


class ErrorBars(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_plot.")
        settings = [{"structure_leaf_size": leaf} for leaf in (2, 4, 8)]
        self.frame = make_runs(settings, ["structure_leaf_size"])

    def tearDown(self):
        self.tmp.cleanup()

    def bars(self, frame):
        fig = Charts(write_folder(Path(self.tmp.name), f"f{len(os.listdir(self.tmp.name))}", frame)) \
            .figures["by_structure_leaf_size"]
        time = data_axes(fig)[0]
        ends = set()
        for collection in time.collections:
            if isinstance(collection, LineCollection):
                ends |= {(round(float(s[0][1]), 6), round(float(s[1][1]), 6)) for s in collection.get_segments()}
        return ends, " ".join(t.get_text() for t in fig.texts)

    def test_interval_columns_are_used_when_present(self):
        frame = self.frame.assign(kernel_ms_ci_low=self.frame.kernel_ms_median - 0.5,
                                  kernel_ms_ci_high=self.frame.kernel_ms_median + 0.25)
        ends, caption = self.bars(frame)
        for low, high in zip(frame.kernel_ms_ci_low, frame.kernel_ms_ci_high):
            self.assertIn((round(low, 6), round(high, 6)), ends)
        self.assertIn("95% interval of the median (kernel_ms_ci_low/high)", caption)

    def test_min_max_without_them(self):
        ends, caption = self.bars(self.frame)
        for low, high in zip(self.frame.kernel_ms_min, self.frame.kernel_ms_max):
            self.assertIn((round(low, 6), round(high, 6)), ends)
        self.assertIn("min-max of the repetitions (kernel_ms_min/max)", caption)
        self.assertNotIn("interval of the median", caption)


class SpeedVsAccuracy(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_plot.")
        self.root = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_panel_titles_name_the_sizes_in_the_panel(self):
        # The first row at 1024x1024: the old title took its size for the 512x512 runs as well.
        settings = [{"camera_width": 1024, "camera_height": 1024, "structure_leaf_size": leaf} for leaf in (2, 4, 8)]
        settings += [{"camera_width": 512, "camera_height": 512, "structure_leaf_size": leaf} for leaf in (2, 4)]
        charts = Charts(write_folder(self.root, "sizes", make_runs(settings, ["camera_width", "camera_height",
                                                                              "structure_leaf_size"])))
        panels = {}
        for ax in data_axes(charts.figures["speed_vs_accuracy"]):
            sizes = re.findall(r"\d+x\d+", ax.get_title())
            self.assertEqual(len(sizes), 1, ax.get_title())
            panels.setdefault(sizes[0], []).append(kernel_points(ax))
        self.assertEqual(panels, {"1024x1024": [3, 3], "512x512": [2, 2]})
        # camera_height goes with camera_width: one chart for both, and a line saying so.
        self.assertIn("skipped by_camera_height: camera_height goes one for one with camera_width", charts.stderr)
        self.assertIn("by_camera_width", charts.figures)

    def test_all_zero_data_get_a_0_to_1_axis_or_one_line_of_text(self):
        frame = make_runs([{"structure_leaf_size": leaf} for leaf in (2, 4, 8)], ["structure_leaf_size"])
        frame[["exact_false_misses", "exact_false_hits", "exact_wrong_ppm"]] = 0
        charts = Charts(write_folder(self.root, "zero", frame))
        ax = data_axes(charts.figures["speed_vs_accuracy"])[0]  # speed on x: the points still say something
        low, high = ax.get_ylim()
        self.assertTrue(-0.1 < low <= 0 and high >= 1, f"y from {low} to {high}")
        self.assertIn("all zero", [t.get_text() for t in ax.texts])
        by_key = charts.figures["by_structure_leaf_size"]  # an accuracy panel of zeros: a line of text
        self.assertEqual(len(data_axes(by_key)), 1, "the time panel alone")
        self.assertIn("Rays wrong against the exact reference: none in any run drawn",
                      " ".join(t.get_text() for t in by_key.texts))

    def test_time_per_ray_traced_where_the_batch_differs(self):
        settings = [{"structure_type": "bvh", "path_bounce": b} for b in (1, 2, 3)]
        frame = make_runs(settings, ["path_bounce"])
        frame["rays"] = frame["exact_rays"] = [65536, 9000, 950]
        charts = Charts(write_folder(self.root, "paths", frame))
        left = data_axes(charts.figures["by_path_bounce"])[0]
        self.assertIn("ns per ray traced", left.get_ylabel())
        kernel = [line for line in left.get_lines() if len(line.get_xdata()) == 3 and line.get_color() != "k"]
        ys = sorted(np.round(np.asarray(kernel[0].get_ydata(), dtype=float), 3))
        expected = sorted(np.round([1e6 * ms / rays for ms, rays in zip(frame.kernel_ms_median, frame.rays)], 3))
        self.assertEqual(ys, expected)
        same = make_runs(settings, ["path_bounce"])  # one batch: ms per frame
        left = data_axes(Charts(write_folder(self.root, "same", same)).figures["by_path_bounce"])[0]
        self.assertIn("ms per frame", left.get_ylabel())

    def test_nonzero_data_stay_inside_the_axis(self):
        frame = make_runs([{"structure_leaf_size": leaf} for leaf in (2, 4, 8)], ["structure_leaf_size"])
        charts = Charts(write_folder(self.root, "some", frame))
        ax = data_axes(charts.figures["speed_vs_accuracy"])[0]
        self.assertGreater(ax.get_ylim()[1], frame.exact_wrong_ppm.max() * 1.5)
        self.assertNotIn("all zero", [t.get_text() for t in ax.texts])

    def test_simplified_runs_get_a_front_of_their_own(self):
        settings = [{"structure_leaf_size": leaf} for leaf in (2, 4, 2, 4)]
        frame = make_runs(settings, ["structure_leaf_size"])
        frame.loc[2:, "scene_triangles"] = 100  # runs 2 and 3 on a simplified scene
        frame.loc[2:, "exact_wrong_primitive"] = np.nan
        charts = Charts(write_folder(self.root, "simplified", frame))
        labels = [line.get_label() for line in data_axes(charts.figures["speed_vs_accuracy"])[0].lines]
        self.assertEqual(sum(label.startswith("Pareto front") for label in labels), 2, labels)
        self.assertTrue(any("simplified" in label for label in labels if label.startswith("Pareto")), labels)


class NamedCharts(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_plot.")
        self.root = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_build_times_put_each_scene_against_embree_and_its_ratio_against_1(self):
        settings = [{"scene_source": scene, "structure_type": "uniform_grid", "structure_min_dim": d}
                    for scene in ("cgal:bunny00", "procedural:christen_b") for d in (16, 32, 64)]
        frame = make_runs(settings, ["scene_source", "structure_min_dim"])
        cells = frame.structure_min_dim ** 3
        frame = frame.assign(build_rounds=9, grid_cells=cells, structure_build_ms_median=cells / 1e4,
                             embree_build_ms_median=[5.0] * 3 + [0.5] * 3)
        frame = frame.assign(build_ratio_vs_embree=frame.structure_build_ms_median / frame.embree_build_ms_median)
        frame = frame.assign(build_ratio_ci_low=frame.build_ratio_vs_embree * 0.9, build_ratio_ci_high=frame.build_ratio_vs_embree * 1.2)
        charts = Charts(write_folder(self.root, "builds", frame))
        left, right = data_axes(charts.figures["build_times"])[:2]
        solid = [line for line in left.lines if line.get_linestyle() == "-"]
        dashed = sorted(line.get_ydata()[0] for line in left.lines if line.get_linestyle() == "--")
        self.assertEqual(len(solid), 2)  # one line per scene through its three grids
        self.assertEqual(dashed, [0.5, 5.0])  # each scene's Embree build
        self.assertIn(1.0, [line.get_ydata()[0] for line in right.lines if line.get_linestyle() == "-" and len(line.get_ydata()) == 2])
        self.assertEqual(len(right.containers), 2)  # the ratios with their intervals, per scene
        # Without build rounds the chart is not called for, and says why.
        quiet = Charts(write_folder(self.root, "no_rounds", make_runs(settings, ["scene_source", "structure_min_dim"])))
        self.assertNotIn("build_times", quiet.figures)
        self.assertIn("skipped build_times: no build rounds", quiet.stderr)

    def test_bandwidth_bars_name_the_swept_value(self):
        settings = [{"structure_type": "uniform_grid", "structure_min_dim": d} for d in (8, 16, 32, 64)]
        charts = Charts(write_folder(self.root, "bandwidth", make_runs(settings, ["structure_min_dim"])))
        ax = data_axes(charts.figures["bandwidth_by_category"])[0]
        labels = [t.get_text() for t in ax.get_xticklabels()]
        self.assertEqual(len(labels), 4, labels)
        for d in (8, 16, 32, 64):
            self.assertTrue(any(f"min_dim={d}" in label for label in labels), labels)

    def test_device_control_adds_the_oracle_and_the_ray_lists(self):
        # Multipass with the oracle on the device: its time is a part of kernel_ms_median, and its
        # list entries (bytes_compaction) a part of bytes_total; the host-control run has neither.
        settings = [{"structure_type": "uniform_grid", "strategy_type": "multipass"} for _ in range(2)]
        runs = make_runs(settings, [])
        runs.insert(len(PARAMETERS), "strategy_control", ["host", "device"])  # a key column, before `run`
        runs = runs.assign(kernel_ms_setup=1.0, kernel_ms_traverse=2.0, kernel_ms_intersect=3.0, kernel_ms_write=0.5,
                           kernel_ms_oracle=[np.nan, 0.25], bytes_compaction=[np.nan, 5e6])
        charts = Charts(write_folder(self.root, "device", runs))
        time_ax = data_axes(charts.figures["kernel_time"])[0]
        self.assertIn("oracle (on the device)", [t.get_text() for t in time_ax.get_legend().get_texts()])
        tops = sorted(p.get_y() + p.get_height() for p in time_ax.containers[-1])
        self.assertEqual(tops, [6.5, 6.75])  # the host run's four passes; the device run's and its oracle
        bytes_ax = data_axes(charts.figures["bandwidth_by_category"])[0]
        self.assertIn("ray lists (oracle on the device)", [t.get_text() for t in bytes_ax.get_legend().get_texts()])
        heights = [p.get_height() for p in bytes_ax.containers[-1]]
        self.assertEqual(sorted(heights), [0.0, 5.0])  # MB: only the device run's bar has lists

    def test_stacked_bar_legends_stay_off_the_bars(self):
        # Bars of nearly one height leave no free corner: the legend sits above the tallest bar.
        settings = [{"structure_type": "uniform_grid", "strategy_type": "multipass"} for _ in range(3)]
        runs = make_runs(settings, [])
        runs.insert(len(PARAMETERS), "strategy_control", ["host", "device", "device"])
        runs.insert(len(PARAMETERS), "strategy_list_partitions", [np.nan, 1, 2])
        runs = runs.assign(kernel_ms_setup=1.0, kernel_ms_traverse=2.0, kernel_ms_intersect=3.0, kernel_ms_write=0.5,
                           kernel_ms_oracle=[np.nan, 0.25, 0.25], bytes_compaction=[np.nan, 5e6, 5e6])
        charts = Charts(write_folder(self.root, "legends", runs))
        for name in ("kernel_time", "bandwidth_by_category"):
            ax = data_axes(charts.figures[name])[0]
            renderer = ax.figure.canvas.get_renderer()
            legend = ax.get_legend().get_window_extent(renderer)
            bars = [p.get_window_extent(renderer) for container in ax.containers for p in container if p.get_height() > 0]
            self.assertTrue(bars)
            for bar in bars:
                self.assertFalse(bar.overlaps(legend), f"{name}: a bar under the legend")

    def test_failure_map_draws_markers_and_keeps_legends_off_the_data(self):
        settings = [{"scene_translate": f"[{d} {d} {d}]", "intersection_test": test}
                    for d in (0, 1, 100, 10000) for test in ("moller_trumbore", "watertight")]
        frame = make_runs(settings, ["scene_translate", "intersection_test"])
        frame.loc[3, "exact_wrong_primitive"] = 1  # one ray wrong at one offset
        charts = Charts(write_folder(self.root, "moved", frame))
        fig = charts.figures["failure_map"]
        panels = data_axes(fig)
        self.assertTrue(panels)
        for ax in panels:
            self.assertIsNone(ax.get_legend(), "no legend over a panel")
            for line in ax.lines:
                if len(line.get_xdata()) > 1 and line.get_label() != "_nolegend_":
                    self.assertEqual(line.get_linestyle(), "None", f"a line through {line.get_label()}")
        self.assertTrue(any(ax.get_legend() is not None for ax in fig.axes if not ax.axison), "one legend, beside")

    def test_vertex_precision_keeps_float_apart(self):
        settings = [{"intersection_vertex_bits": bits} for bits in (8, 12, 16, 32)]
        charts = Charts(write_folder(self.root, "packed", make_runs(settings, ["intersection_vertex_bits"])))
        for ax in data_axes(charts.figures["vertex_precision"]):
            joined = [line for line in ax.lines if line.get_linestyle() != "None" and len(line.get_xdata()) > 1]
            self.assertTrue(joined)
            for line in joined:
                self.assertLess(max(line.get_xdata()), 32, "no line from 16 bits to float")
            self.assertTrue(any(line.get_marker() == "*" and list(line.get_xdata()) == [32] for line in ax.lines))

    def test_titles_fit_their_figure_and_axes(self):
        frame = make_runs([{"structure_leaf_size": leaf} for leaf in (2, 4, 8)], ["structure_leaf_size"])
        device = "A device with a very long name " * 8
        charts = Charts(write_folder(self.root, "long", frame, device=device))
        self.assertIn("by_structure_leaf_size", charts.figures)
        for name, fig in charts.figures.items():
            renderer = fig.canvas.get_renderer()
            if fig._suptitle is not None:
                self.assertLessEqual(fig._suptitle.get_window_extent(renderer).width, fig.bbox.width, name)
                self.assertGreaterEqual(fig._suptitle.get_window_extent(renderer).x0, 0, name)
            for ax in data_axes(fig):
                self.assertLessEqual(ax.title.get_window_extent(renderer).width,
                                     ax.get_window_extent(renderer).width + 1, f"{name}: {ax.get_title()}")


class ReadRuns(unittest.TestCase):
    """rtbench_results.read_runs: the dtypes columns.csv gives, and an older folder's vector cells."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.folder = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_types_come_from_the_column_dictionary(self):
        (self.folder / "runs.csv").write_text(
            "camera_up_x,camera_up_y,camera_up_z,structure_conservative,run,config_hash,grid_res_x,exact_wrong_ppm\n"
            "0,1,0,true,007,0012345678901234,64,inf\n"
            "0,1,0,,008,00ab,,2.5\n")
        (self.folder / "columns.csv").write_text(
            "column,kind,type,unit,since_schema,written_when,meaning\n"
            "camera_up_x,parameter,number,,1,,\ncamera_up_y,parameter,number,,1,,\ncamera_up_z,parameter,number,,1,,\n"
            "structure_conservative,parameter,boolean,,2,,\nrun,parameter,text,,1,,\nconfig_hash,parameter,text,,1,,\n"
            "grid_res_x,count,integer,cells,1,,\nexact_wrong_ppm,count,number,ppm,2,,\n")
        runs = rtbench_results.read_runs(self.folder)
        self.assertEqual(list(runs.run), ["007", "008"], "run numbers keep their zeros")
        self.assertEqual(runs.config_hash[0], "0012345678901234", "a hash of digits stays text")
        self.assertEqual(str(runs.grid_res_x.dtype), "Int64")
        self.assertEqual(runs.grid_res_x[0], 64)
        self.assertTrue(pd.isna(runs.grid_res_x[1]))
        self.assertEqual(str(runs.structure_conservative.dtype), "boolean")
        self.assertTrue(runs.structure_conservative[0])
        self.assertEqual(runs.exact_wrong_ppm[0], float("inf"))
        self.assertEqual(runs.camera_up_y.dtype, np.float64)
        self.assertEqual(plot.text_value(runs.grid_res_x[1]), "", "a missing value (<NA>) is no value, not a label")
        self.assertEqual(rtbench_results.method_name(pd.Series({"structure_type": "uniform_grid",
                                                                 "structure_min_dim": pd.NA})), "grid")

    def test_an_older_folders_vector_cells_become_three_numeric_columns(self):
        (self.folder / "runs.csv").write_text("scene_translate,camera_look_at,run\n[1e6 -2 0.5],,000\n[0 0 0],,001\n")
        runs = rtbench_results.read_runs(self.folder)
        self.assertEqual(list(runs.columns), ["scene_translate_x", "scene_translate_y", "scene_translate_z",
                                              "camera_look_at_x", "camera_look_at_y", "camera_look_at_z", "run"])
        self.assertEqual(list(runs.iloc[0][:3]), [1e6, -2.0, 0.5])
        self.assertTrue(runs.camera_look_at_z.isna().all())
        self.assertEqual(list(runs.run), ["000", "001"])

    def test_round_ratios_pair_the_rounds_of_two_runs(self):
        # Run 001 over run 000 round by round: round 0 holds two repetitions of each (their medians,
        # 7 and 2), round 1 one; run 002 has no round 1 and method embree1 is not the kernel.
        (self.folder / "samples.csv").write_text(
            "run,config_hash,method,round,repetition,ms,t_s\n"
            "000,a,kernel,0,0,1.0,0\n000,a,kernel,0,1,3.0,0\n001,b,kernel,0,0,6.0,0\n001,b,kernel,0,1,8.0,0\n"
            "000,a,kernel,1,0,4.0,0\n001,b,kernel,1,0,10.0,0\n000,a,embree1,1,0,100.0,0\n002,c,kernel,0,0,5.0,0\n")
        samples = rtbench_results.read_samples(self.folder)
        ratios = rtbench_results.round_ratios(samples, "001", "000")
        self.assertEqual(list(ratios.index), [0, 1])
        self.assertEqual(list(ratios), [3.5, 2.5])
        self.assertEqual(list(rtbench_results.round_ratios(samples, "002", "000")), [2.5], "rounds both runs have")
        self.assertEqual(list(rtbench_results.round_times(samples, "000", "embree1")), [100.0])
        self.assertTrue(rtbench_results.round_ratios(samples, "003", "000").empty, "a run without samples")
        (self.folder / "samples.csv").unlink()
        samples = rtbench_results.read_samples(self.folder)
        self.assertTrue(rtbench_results.round_ratios(samples, "001", "000").empty, "a folder without samples.csv")


class ChartsSurvive(unittest.TestCase):
    """One chart's failure is that chart's: the others are drawn, the failure is named with its reason,
    and plot exits 0 when it wrote any chart; the charts a folder does not call for are one line
    unless -v; any-hit rays (no hit distance) draw no distance axis."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_plot.")
        self.root = Path(self.tmp.name)
        # A shadow-ray sweep (any-hit: no distance error) over grid resolutions and the BVH.
        settings = [{"structure_type": "uniform_grid", "structure_min_dim": d, "query": "any"} for d in (8, 16, 32, 64, 128)]
        settings.append({"structure_type": "bvh", "query": "any"})
        frame = make_runs(settings, ["structure_type", "structure_min_dim"])
        for column in ("exact_distance_error_mean", "embree_exact_distance_error_mean"):
            frame[column] = np.nan
        frame["rays_type"] = "shadow"
        self.folder = write_folder(self.root, "shadow", frame)

    def tearDown(self):
        self.tmp.cleanup()

    def test_any_hit_rays_draw_speed_against_hit_miss_agreement_and_no_distance_axis(self):
        charts = Charts(self.folder)
        self.assertEqual(charts.rc, 0, charts.stderr)
        self.assertNotIn("could not draw", charts.stderr)
        left, right = charts.figures["speed_vs_accuracy"].axes[:2]
        self.assertIn("hit/miss", left.get_ylabel())
        self.assertFalse(right.axison, "no distance axis for rays that return no distance")
        self.assertIn("any-hit rays", " ".join(t.get_text() for t in right.texts))
        self.assertIn("any-hit rays", left.get_title())

    def test_a_chart_that_fails_is_named_and_the_others_are_drawn(self):
        original = plot.speed_vs_accuracy

        def broken(*args):
            raise ValueError("Data has no positive values, and therefore can not be log-scaled.")
        broken.__name__ = "speed_vs_accuracy"
        plot.speed_vs_accuracy = broken
        try:
            charts = Charts(self.folder, verbose=False)
        finally:
            plot.speed_vs_accuracy = original
        self.assertEqual(charts.rc, 0, charts.stderr)
        self.assertIn(f"rtbench plot: {self.folder}: could not draw speed_vs_accuracy: ValueError: Data has no "
                      "positive values", charts.stderr)
        self.assertIn("1 chart(s) could not be drawn: speed_vs_accuracy", charts.stderr)
        self.assertNotIn("speed_vs_accuracy", charts.figures)
        self.assertIn("by_structure_min_dim", charts.figures)

    def test_charts_not_called_for_are_one_line_unless_verbose(self):
        quiet = Charts(self.folder, verbose=False)
        self.assertNotIn("skipped", quiet.stderr)
        self.assertRegex(quiet.stdout, r"\d+ chart\(s\) not called for by these runs \(-v names them\)")
        loud = Charts(self.folder, verbose=True)
        self.assertIn(f"rtbench plot: {self.folder}: skipped passes_vs_threshold: ", loud.stderr)
        self.assertNotIn("not called for", loud.stdout)

    def test_no_chart_written_is_exit_1_saying_so(self):
        original = plot.save

        def refuse(*args, **kwargs):
            raise RuntimeError("cannot lay out")
        plot.save = refuse
        err = io.StringIO()
        try:
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                rc = plot.main_with([str(self.folder)])
        finally:
            plot.save = original
        self.assertEqual(rc, 1)
        self.assertIn("could not draw speed_vs_accuracy: RuntimeError: cannot lay out", err.getvalue())
        self.assertIn(f"rtbench plot: {self.folder}: no chart could be drawn from these runs", err.getvalue())


class Palette(unittest.TestCase):
    """One palette: a structure's colour family in every chart, its resolutions in numeric order and
    apart; categorical values as points, not joined; flagged timings hollow."""

    def test_methods_sort_by_number_and_keep_their_family(self):
        methods = ["grid 8", "bvh", "grid 16", "grid 128", "grid 32", "brute force", "auto (bvh)"]
        ordered = sorted(methods, key=plot.method_sort_key)
        self.assertEqual(ordered, ["grid 8", "grid 16", "grid 32", "grid 128", "bvh", "brute force", "auto (bvh)"])
        colors = plot.method_colors(methods)
        self.assertEqual(len(set(colors.values())), len(methods), "no two methods share a colour")
        for m in ("grid 8", "grid 16", "grid 32", "grid 128"):
            rgb = matplotlib.colors.to_rgb(colors[m])
            self.assertGreater(rgb[2], rgb[0], f"{m}: a blue")
        self.assertEqual(plot.method_colors(["bvh"])["bvh"], plot.method_colors(["bvh", "grid 8"])["bvh"],
                         "a structure's colour does not depend on the chart's other structures")
        self.assertNotIn(plot.STRATEGY_COLORS["branching"], colors.values())

    def test_legends_list_methods_in_numeric_order(self):
        with tempfile.TemporaryDirectory(prefix="test_plot.") as tmp:
            settings = [{"structure_type": "uniform_grid", "structure_min_dim": d, "camera_fov_deg": f}
                        for d in (128, 8, 32, 16) for f in (30, 60)]
            frame = make_runs(settings, ["structure_min_dim", "camera_fov_deg"])
            charts = Charts(write_folder(Path(tmp), "grids", frame))
            self.assertEqual(charts.rc, 0, charts.stderr)
            texts = [t.get_text() for ax in charts.figures["by_camera_fov_deg"].axes if ax.get_legend()
                     for t in ax.get_legend().get_texts()]
            dims = [t for t in texts if t.startswith("min_dim=")]
            self.assertEqual(dims, ["min_dim=8", "min_dim=16", "min_dim=32", "min_dim=128"], texts)

    def test_a_narrow_span_of_distance_errors_is_a_linear_axis_from_zero(self):
        # 1e-7 (kernels) and 5e-8 (Embree): a factor of 2, which a log axis would stretch to its height.
        with tempfile.TemporaryDirectory(prefix="test_plot.") as tmp:
            frame = make_runs([{"structure_type": t} for t in ("bvh", "uniform_grid")], ["structure_type"])
            charts = Charts(write_folder(Path(tmp), "narrow", frame))
            right = charts.figures["speed_vs_accuracy"].axes[1]
            self.assertEqual(right.get_yscale(), "linear")
            self.assertEqual(right.get_ylim()[0], 0.0)
            self.assertNotIn("(log)", right.get_ylabel())

    def test_categorical_values_are_points_and_noisy_times_hollow(self):
        with tempfile.TemporaryDirectory(prefix="test_plot.") as tmp:
            settings = [{"structure_type": t, "strategy_type": s} for t in ("bvh", "uniform_grid") for s in ("branching", "multipass")]
            frame = make_runs(settings, ["structure_type", "strategy_type"])
            frame["timing_warning"] = ["", "cv 0.2 over 0.05", "", ""]
            charts = Charts(write_folder(Path(tmp), "categories", frame))
            self.assertEqual(charts.rc, 0, charts.stderr)
            left = charts.figures["by_strategy_type"].axes[0]
            joined = [line for line in left.get_lines() if line.get_linestyle() not in ("None", "none", "") and len(line.get_xdata()) > 1]
            self.assertEqual(joined, [], "categories are not joined by lines")
            hollow = [line for line in left.get_lines() if line.get_markerfacecolor() in ("white", (1.0, 1.0, 1.0, 1.0))]
            self.assertEqual(len(hollow), 1, "the flagged run's time is hollow")
            legend = " ".join(t.get_text() for ax in charts.figures["by_strategy_type"].axes for t in ax.texts)
            self.assertIn("timing warning", legend + " ".join(
                t.get_text() for ax in charts.figures["by_strategy_type"].axes if ax.get_legend()
                for t in ax.get_legend().get_texts()))


if __name__ == "__main__":
    unittest.main()
