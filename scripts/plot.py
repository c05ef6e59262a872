#!/usr/bin/python3
"""Charts for an rtbench results folder: PNG and SVG next to runs.csv.

usage: scripts/plot.py [-v] RESULTS_DIR      (or: build/rtbench plot [-v] RESULTS_DIR)
Besides the charts of the configs of record, one chart per swept key (by_<key>: time and rays
wrong against the key's values, coloured by method, one row per scene). A chart the folder's runs
do not call for (a paper's chart of another experiment) is counted in one line; -v names each with
its reason: "rtbench plot: DIR: skipped CHART: why". A chart that fails while it is drawn is left
out with its reason, "rtbench plot: DIR: could not draw CHART: why", and the others are still
drawn. Exit 0 when any chart was written, 1 when none was. Uses Debian's python3-matplotlib and
python3-pandas only.
"""
import errno
import json
import math
import os
import re
import sys
import tempfile
import textwrap
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "rtbench"  # the SVG's ids from its content, not at random
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib import ticker, transforms  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from rtbench_results import (AXES, VECTOR_KEYS, christen_iterations, host_against_device, live_headline, load, method_name,  # noqa: E402
                             scene_name, UnsafePath, write_file_atomically, wrong_rays)
# One palette for every chart: a colour family per acceleration structure (shades for its
# resolutions, in numeric order), a colour per strategy apart from all of them, Embree in black.
# A colour means the same thing in every file.
STRUCTURE_CMAPS = {"grid": "Blues", "grid conservative": "GnBu", "bvh": "Reds", "brute force": "Greys",
                   "auto": "Purples", "ray_query": "RdPu"}
STRATEGY_COLORS = {"branching": "#1b9e77", "multipass": "#d95f02", "megakernel": "#e6ab02", "persistent": "#66a61e",
                   "wavefront": "#17becf", "path_megakernel": "#bcbd22", "plain": "#fb9a99", "cpu": "#b15928",
                   "ray_query": "#e7298a", "control": "#7570b3"}
EMBREE_COLOR = "k"
COLORS = dict(STRATEGY_COLORS, **{"Embree rtcIntersect1": EMBREE_COLOR})


def structure_family(method: str) -> str:
    """The structure a method name ("grid 64", "grid 32 conservative", "auto (bvh)") belongs to."""
    if method.startswith("brute"):
        return "brute force"
    first = method.split(" ")[0]
    return "grid conservative" if first == "grid" and "conservative" in method else first


def natural_key(text: str):
    """Text with its numbers compared as numbers: "min_dim=8" before "min_dim=16"."""
    return [(0, float(part), "") if re.fullmatch(r"-?\d+(?:\.\d+)?", part) else (1, 0.0, part)
            for part in re.split(r"(-?\d+(?:\.\d+)?)", text) if part]


def method_sort_key(method: str):
    """Methods in a reader's order: grids by resolution (8 before 16), then bvh, brute force, auto."""
    family = structure_family(method)
    numbers = [int(n) for n in re.findall(r"\d+", method)]
    rank = list(STRUCTURE_CMAPS).index(family) if family in STRUCTURE_CMAPS else len(STRUCTURE_CMAPS)
    return (rank, numbers, method)


def method_colors(methods) -> dict:
    """A colour per method: its structure's family, a shade per member (darker: finer), none shared."""
    colors = {m: STRATEGY_COLORS[m] for m in methods if m in STRATEGY_COLORS and m not in STRUCTURE_CMAPS}  # by strategy
    ordered = sorted(set(methods) - set(colors), key=method_sort_key)
    for family in dict.fromkeys(structure_family(m) for m in ordered):
        members = [m for m in ordered if structure_family(m) == family]
        cmap = matplotlib.colormaps[STRUCTURE_CMAPS.get(family, "Greys")]
        for i, m in enumerate(members):
            colors[m] = matplotlib.colors.to_hex(cmap(0.7 if len(members) == 1 else 0.4 + 0.55 * i / (len(members) - 1)))
    return colors
BYTES = [("bytes_stencil", "stencil"), ("bytes_state", "state variables"), ("bytes_stack", "node stack"),
         ("bytes_voxel", "voxel data"), ("bytes_node", "BVH nodes"), ("bytes_triangle_list", "triangle lists"),
         ("bytes_vertices", "triangle vertices"), ("bytes_output", "output"),
         ("bytes_compaction", "ray lists (oracle on the device)")]
KERNELS = [("kernel_ms_setup", "setup"), ("kernel_ms_traverse", "traverse"), ("kernel_ms_intersect", "intersect"),
           ("kernel_ms_write", "write")]
ORACLE = ("kernel_ms_oracle", "oracle (on the device)")  # a part of kernel_ms_median where the oracle runs on the device


class PlotError(Exception):
    """What stops the charts, said in one line: "<path>: <why>"."""


def write_atomically(fig, target: Path, ext: str):
    """fig as `ext` into `target`: a new temporary file in the same folder (O_EXCL, O_NOFOLLOW:
    mkstemp), then os.replace over the target, which replaces a name and never writes through a
    link. A target that exists as a symbolic link is refused; a failed write leaves the old chart."""
    if target.is_symlink():
        raise PlotError(f"{target}: is a symbolic link; refusing to write a chart through it")
    if target.exists() and not target.is_file():
        raise PlotError(f"{target}: exists and is not a regular file; cannot write a chart there")
    # SVGs without a date and with fixed ids: a chart of the same runs is the same file.
    write_file_atomically(target, lambda out: fig.savefig(out, format=ext, dpi=110,
                                                          **({"metadata": {"Date": None}} if ext == "svg" else {})))


VERBOSE = False  # -v: name every chart the runs do not call for
SKIPPED = []  # charts the runs do not call for, this invocation
FAILED = []  # charts that failed while drawn, this invocation


def skip(folder: Path, name: str, reason: str):
    """A chart the runs do not call for: counted, and with -v one line on stderr naming it and why."""
    SKIPPED.append(name)
    if VERBOSE:
        print(f"rtbench plot: {folder}: skipped {name}: {reason}", file=sys.stderr)


def fit_text(text, width: float, renderer):
    """Wrap each line of a title (a Text) to `width` pixels, then shrink it if a word is still wider."""
    lines = text.get_text().split("\n")
    fitted = []
    for line in lines:
        text.set_text(line)
        measured = text.get_window_extent(renderer).width
        if measured <= width or len(line) < 2:
            fitted.append(line)
            continue
        chars = max(12, int(len(line) * width / measured))
        while True:
            text.set_text(textwrap.fill(line, chars))
            if text.get_window_extent(renderer).width <= width or chars <= 12:
                break
            chars -= max(1, chars // 10)
        fitted.append(text.get_text())
    text.set_text("\n".join(fitted))
    while text.get_window_extent(renderer).width > width and text.get_fontsize() > 6:
        text.set_fontsize(text.get_fontsize() - 0.5)


def fit_titles(fig):
    """No clipped titles: every axes title wrapped to its axes' width, the figure's to the figure's."""
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        if ax.get_title():
            fit_text(ax.title, ax.get_window_extent(renderer).width, renderer)
    if fig._suptitle is not None:
        fit_text(fig._suptitle, 0.96 * fig.bbox.width, renderer)


def save(fig, folder: Path, name: str, written: list, rect=None):
    """tight_layout within `rect` below the figure's title (matplotlib 3.6 lets a tall figure's rows
    run into it), titles fitted to their widths, then PNG and SVG."""
    rect = list(rect or (0, 0, 1, 1))
    fig.tight_layout(rect=rect)
    fit_titles(fig)
    fig.tight_layout(rect=rect)
    clear_legends_of_bars(fig)
    for _ in range(3):
        if fig._suptitle is None or not fig._suptitle.get_text():
            break
        renderer = fig.canvas.get_renderer()
        below = fig._suptitle.get_window_extent(renderer).y0 - 6
        top = max(ax.get_tightbbox(renderer).y1 for ax in fig.axes)
        if top <= below:
            break
        fig.subplots_adjust(top=fig.subplotpars.top - (top - below) / fig.bbox.height)
    for ext in ("png", "svg"):
        write_atomically(fig, folder / f"{name}.{ext}", ext)
    plt.close(fig)
    written.append(name)


def stacked_bars(ax, labels, frame, columns, scale=1.0):
    """One bar per row of `frame`, stacked over (column, legend name) pairs."""
    bottom = [0.0] * len(frame)
    for column, name in columns:
        values = (frame[column].fillna(0) * scale).tolist()
        ax.bar(labels, values, bottom=bottom, label=name)
        bottom = [b + v for b, v in zip(bottom, values)]
    ax.legend(fontsize=8, loc="upper left", ncol=1 if len(columns) < 4 else 2)
    ax.bar_top = max(bottom, default=0.0)  # save() raises the axis so that the bars end below the legend


def clear_legends_of_bars(fig):
    """Each stacked-bar axes' y axis raised so that its tallest bar ends below its legend (upper
    left): "best" found no free corner once a bar reached the top on either side."""
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        top, legend = getattr(ax, "bar_top", 0.0), ax.get_legend()
        if top <= 0 or legend is None or ax.get_yscale() != "linear":
            continue
        below = legend.get_window_extent(renderer).transformed(ax.transAxes.inverted()).y0 - 0.03
        if below > 0.2:
            ax.set_ylim(0, top / below)


def size_of(run) -> str:
    return f"{int(run.camera_width)}x{int(run.camera_height)}"


def size(frame) -> str:
    """The image sizes of the runs in `frame`, largest first: "1024x1024" or "1024x1024 and 512x512"."""
    pairs = frame[["camera_width", "camera_height"]].drop_duplicates().dropna()
    pairs = sorted(((int(w), int(h)) for w, h in pairs.itertuples(index=False)), key=lambda p: (-p[0] * p[1], p))
    names = [f"{w}x{h}" for w, h in pairs]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1] if names else "no size"


def pareto(points):
    """Points (speed, error) no other point beats in both (faster and at most as wrong), by speed."""
    front, best = [], float("inf")
    for x, y in sorted(points, key=lambda p: (-p[0], p[1])):
        if y < best:
            front.append((x, y))
            best = y
    return sorted(front)


def any_hit(frame):
    """True per run whose rays ask whether anything is hit (query = any: shadow, ambient occlusion),
    not where: such a run has no hit distance (folders from before the column: closest)."""
    return frame["query"].eq("any") if "query" in frame else pd.Series(False, frame.index)


def timing_warned(frame):
    """True per run the noise guard flagged (a timing_warning): its time is not a timing of record."""
    if "timing_warning" not in frame:
        return pd.Series(False, frame.index)
    return frame.timing_warning.fillna("").astype(str) != ""


def wrong_ppm(frame, prefix="exact_"):
    """Rays wrong against the exact reference per million: false misses + false hits + wrong triangle
    (a simplified scene has other triangles: no wrong triangle counted)."""
    return 1e6 * wrong_rays(frame, prefix) / frame.exact_rays


def finite(values):
    values = pd.to_numeric(pd.Series(np.asarray(values, dtype=float).ravel()), errors="coerce")
    return values[np.isfinite(values)]


def all_zero_axis(ax, note="all zero"):
    """A y axis whose data are all 0 (or absent): 0 to 1, linear, and said so (not -0.1 to 0.055)."""
    ax.set_yscale("linear")
    ax.set_ylim(-0.05, 1.0)
    ax.set_yticks([0, 0.5, 1])
    ax.text(0.5, 0.55, note, transform=ax.transAxes, ha="center", va="center", color="0.4", fontsize=9)


def wrong_ppm_axis(ax, values, label=None):
    """A y axis of rays wrong per million: 0 sits on the axis, 1 ppm and up are logarithmic, the
    largest value below the top; all zero: 0 to 1 with a note."""
    values = finite(values)
    if label:
        ax.set_ylabel(label)
    if values.empty or values.max() <= 0:
        all_zero_axis(ax, "all zero" if not values.empty else "no values")
        return
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set_ylim(-0.1, max(2.0, values.max() * 2.5))


def log_axis(ax, values, axis="y"):
    """A log axis over the positive values when they span a factor of 10 or more; a narrower span on a
    linear axis from 0 (a log axis would blow 0.3% up to its height); all zero: 0 to 1 with a note."""
    values = finite(values)
    positive = values[values > 0]
    if positive.empty:
        if axis == "y":
            all_zero_axis(ax, "all zero" if not values.empty else "no values")
        return
    if positive.max() < 10 * positive.min() and (values >= 0).all():
        (ax.set_yscale if axis == "y" else ax.set_xscale)("linear")
        (ax.set_ylim if axis == "y" else ax.set_xlim)(0, 1.15 * positive.max())
        return
    (ax.set_yscale if axis == "y" else ax.set_xscale)("log")
    if len(positive) < len(values) and axis == "y":
        ax.text(0.01, 0.01, f"{len(values) - len(positive)} zero values not on this log axis", transform=ax.transAxes,
                fontsize=6, color="0.4")


def vertex_bits(frame):
    """intersection.vertex_bits per run (32, float vertices, for folders from before it)."""
    return frame["intersection_vertex_bits"].fillna(32) if "intersection_vertex_bits" in frame else pd.Series(32, frame.index)


def simplified(frame):
    """Whether each run traced a simplified scene (scene.simplify_*)."""
    if "scene_full_triangles" not in frame:
        return pd.Series(False, frame.index)
    return frame.scene_triangles != frame.scene_full_triangles


def variant(frame):
    """How each run's scene differs from its source: "" (as is), "packed" or "simplified"."""
    return pd.Series("", frame.index).where(vertex_bits(frame) == 32, "packed").where(~simplified(frame), "simplified")


def wrong_ppm_summed(frame, by, prefix="exact_"):
    """wrong_ppm over the runs of each value of `by` together (e.g. a point's several views)."""
    columns = [prefix + "false_misses", prefix + "false_hits", prefix + "wrong_primitive", "exact_rays"]
    return wrong_ppm(frame.groupby(by)[columns].sum(), prefix)


def method_label(run) -> str:
    """structure, strategy and triangle test of one run: "grid 64 branching MT"."""
    test = {"moller_trumbore": "MT", "watertight": "watertight"}.get(run.get("intersection_test"), "MT")
    return f"{method_name(run)} {run.strategy_type} {test}"


# Markers per strategy in speed_vs_accuracy (squares are Embree's, x the Pareto front's).
STRATEGY_MARKERS = {"branching": "o", "multipass": "P", "megakernel": "^", "persistent": "h", "wavefront": "p",
                    "path_megakernel": "*", "plain": "8", "cpu": "X", "ray_query": ">", "control": "v"}
# Markers per scene variant, (Moller-Trumbore, watertight).
VARIANT_MARKERS = {"": ("o", "^"), "packed": ("D", "d"), "simplified": ("v", "<")}


# Config key columns: every column before `run` (harness/columns.cpp writes the config schema's keys
# first); for a CSV without `run`, the columns named after a config section.
SECTIONS = ("experiment", "scene", "camera", "structure", "strategy", "intersection", "baseline", "accuracy",
            "device", "output")
NOT_SWEPT = {"experiment_name", "experiment_output"}  # the same for every run of a config
METHOD_KEYS = ("structure_type", "strategy_type")
LOOK_AT = ("camera_look_at_x", "camera_look_at_y", "camera_look_at_z")  # camera.look_at, three columns  # the colour of the by_<key> charts
STRUCTURE_NAMES = {"uniform_grid": "grid", "brute_force": "brute force"}


def parameter_columns(frame) -> list:
    """The config key columns, a 3-vector key as its one "[x y z]" column (rtbench_results.with_vector_text)."""
    columns = list(frame.columns)
    head = columns[:columns.index("run")] if "run" in columns else [c for c in columns if c.split("_")[0] in SECTIONS]
    components = {key + axis for key in VECTOR_KEYS if key in columns for axis in AXES}
    return [c for c in head if c not in NOT_SWEPT and c not in components]


def text_value(value) -> str:
    """One spelling per value, as a label: 64 and 64.0 alike, False as "false", an empty cell as ""."""
    if value is None or value is pd.NA or (isinstance(value, float) and math.isnan(value)):
        return ""  # pandas' missing values: NaN, and <NA> in the typed columns of read_runs
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, float, np.integer, np.floating)):
        return f"{float(value):.6g}"
    return str(value)


def as_text(frame, columns) -> pd.DataFrame:
    return pd.DataFrame({c: frame[c].map(text_value) for c in columns}, index=frame.index)


def swept_keys(everything) -> list:
    """The config keys that take two or more values over the runs (an empty cell, a key that does not
    apply to a run's structure or strategy, is no value)."""
    text = as_text(everything, parameter_columns(everything))
    return [c for c in text if text[c][text[c] != ""].nunique() >= 2]


def key_classes(everything, keys) -> list:
    """The swept keys in classes whose values go together one for one (camera.width with camera.height):
    [(first key, [keys that follow it])], in column order."""
    text = as_text(everything, keys)
    classes = []
    for key in keys:
        for first, followers in classes:
            if text.groupby(first)[key].nunique().max() == 1 and text.groupby(key)[first].nunique().max() == 1:
                followers.append(key)
                break
        else:
            classes.append((key, []))
    return classes


def short_key(column: str) -> str:
    """A key without its section where the rest says enough, for labels: structure_min_dim -> min_dim
    (camera_width stays: "width" alone could be anything)."""
    section, _, rest = column.partition("_")
    return rest if section in ("structure", "strategy", "intersection") and rest else column


def run_labels(frame, first, keys) -> list:
    """A bar label per run: `first` columns' values, then key=value for each of `keys` that varies in
    `frame`, so that no two bars of different runs read alike."""
    text = as_text(frame, keys)
    varying = [k for k in keys if text[k][text[k] != ""].nunique() > 1]
    labels = []
    for index, run in frame.iterrows():
        parts = [str(run[c]) for c in first] + [f"{short_key(k)}={text.at[index, k]}" for k in varying
                                                if text.at[index, k] != ""]
        labels.append("\n".join(parts))
    # Runs that still read alike (they differ in a key left out) would share one bar: name each run.
    return [f"{label}\nrun {run}" if labels.count(label) > 1 else label for label, run in zip(labels, frame["run"])]


def speed_vs_accuracy(runs, device, folder, written):
    """Per scene and image size: rays wrong against the exact reference (log above 1 per million)
    and mean distance error against speed, one point per run, Embree beside them, the kernels'
    Pareto fronts: one over the runs on the full scene (as is or packed: wrong = missed, false hit
    or wrong triangle), another over simplified scenes (other triangles: wrong = hit/miss only)."""
    if "exact_rays" not in runs:  # a folder from before the exact reference
        return skip(folder, "speed_vs_accuracy", "no exact_rays column (a folder from before the exact reference)")
    runs = runs.assign(size=[size_of(r) for r in runs.itertuples()], any_hit=any_hit(runs))
    panels = []  # (scene, size, any-hit): a panel per image size and query, as their speeds and counts differ
    for scene in sorted(runs.scene.unique()):
        of_scene = runs[runs.scene == scene]
        for name in sorted(of_scene["size"].unique(), key=lambda n: -np.prod([int(v) for v in n.split("x")])):
            of_size = of_scene[of_scene["size"] == name]
            for query in sorted(of_size.any_hit.unique()):
                panels.append((scene, name + (", any-hit rays" if query else ""), of_size[of_size.any_hit == query]))
    kinds = [method_name(r).split(" ")[0] + (" conservative" if "conservative" in method_name(r) else "")
             for _, r in runs.iterrows()]
    runs = runs.assign(kind=kinds, method=[f"{k} {s}" for k, s in zip(kinds, runs.strategy_type)],
                       test=runs.get("intersection_test", "moller_trumbore"), variant=variant(runs))
    colors = method_colors(runs.method.unique())  # a colour per structure x strategy, the same in every panel
    fig, axes = plt.subplots(len(panels), 2, figsize=(15, 4.4 * len(panels)), squeeze=False)
    any_noisy = False
    for (left, right), (scene, name, of_scene) in zip(axes, panels):
        points = {False: [], True: []}  # simplified or not: the front of each
        of_scene = runs.loc[of_scene.index]
        for (method, test, how), group in sorted(of_scene.groupby(["method", "test", "variant"]),
                                                 key=lambda item: (method_sort_key(item[0][0]), item[0][1:])):
            # Colour: structure x strategy; marker: the strategy (or the scene's variant); half filled:
            # watertight; hollow: a timing warning.
            marker = STRATEGY_MARKERS.get(group.strategy_type.iloc[0], "o") if not how else VARIANT_MARKERS[how][0]
            fill = "left" if test == "watertight" else "full"
            name_ = f"{method}, {'watertight' if test == 'watertight' else 'Moller-Trumbore'}" + (f", {how}" if how else "")
            ppm = wrong_ppm(group)
            noisy = timing_warned(group)
            any_noisy |= bool(noisy.any())
            low, high, _ = interval(group, "kernel")  # the speed's interval, from the time's
            rays = pd.to_numeric(group.rays, errors="coerce") if "rays" in group else group.kernel_mrays_s * group.kernel_ms_median * 1e3
            speed = group.kernel_mrays_s
            xerr = np.vstack([(speed - rays / high / 1e3).clip(lower=0).fillna(0), (rays / low / 1e3 - speed).clip(lower=0).fillna(0)])
            left.errorbar(speed, ppm, xerr=xerr, fmt="none", ecolor=colors[method], elinewidth=0.7, alpha=0.6)
            for flagged in (False, True):
                at = noisy == flagged
                style = dict(ls="none", marker=marker, color=colors[method], alpha=0.85, ms=7,
                             **({"mfc": "white", "fillstyle": "full"} if flagged else {"fillstyle": fill}))
                left.plot(speed[at], ppm[at], **style)
                right.plot(speed[at], group.exact_distance_error_mean[at], **style)
            left.plot([], [], ls="none", marker=marker, ms=7, color=colors[method], fillstyle=fill, label=name_)
            if how:  # which precision or simplification each point is
                tags = [f"{int(b)} b" for b in vertex_bits(group)] if how == "packed" else \
                    [f"{100 * t / f:.3g}%" for t, f in zip(group.scene_triangles, group.scene_full_triangles)]
                for x, y, tag in zip(speed, ppm, tags):
                    left.annotate(tag, (x, y), fontsize=6, xytext=(3, 2), textcoords="offset points", color=colors[method])
            points[how == "simplified"] += list(zip(speed, ppm))
        embree = of_scene[of_scene.variant == ""].drop_duplicates(["camera_width", "camera_height", *LOOK_AT])
        embree_ppm = wrong_ppm(embree, "embree_exact_")
        left.scatter(embree.embree1_mrays_s, embree_ppm, marker="s",
                     color=COLORS["Embree rtcIntersect1"], label="Embree rtcIntersect1 (CPU, same rays)")
        right.scatter(embree.embree1_mrays_s, embree.embree_exact_distance_error_mean, marker="s",
                      color=COLORS["Embree rtcIntersect1"], label="Embree rtcIntersect1 (CPU, same rays)")
        for simplified_, style, label in ((False, "k--", "Pareto front of the kernels, full scene\n(wrong: missed, "
                                                         "false hit or wrong triangle)"),
                                          (True, "--", "Pareto front of the kernels, simplified scenes\n(wrong: "
                                                       "missed or false hit; other triangles)")):
            front = pareto(points[simplified_])
            if front:
                left.plot([p[0] for p in front], [p[1] for p in front], style, marker="x", lw=1, label=label,
                          **({"color": "tab:purple"} if simplified_ else {}))
        all_ppm = [p[1] for p in points[False] + points[True]] + list(embree_ppm)
        any_hit_panel = bool(of_scene.any_hit.all())
        wrong_ppm_axis(left, all_ppm, "rays whose hit/miss differs\nfrom exact (per million; log above 1)" if any_hit_panel
                       else "rays wrong vs exact\n(per million; log above 1)")
        distances = finite(list(of_scene.exact_distance_error_mean) + list(embree.embree_exact_distance_error_mean))
        if any_hit_panel or distances.empty:  # any-hit rays report whether, not where: no distance to compare
            right.cla()
            right.set_axis_off()
            right.text(0.0, 0.5, "any-hit rays: accuracy is hit/miss agreement with the exact reference (left);\n"
                       "they return no hit distance, so there is none to compare" if any_hit_panel else
                       "no hit distance was compared in these runs", transform=right.transAxes, fontsize=8, color="0.3",
                       va="center")
        else:
            log_axis(right, distances)
            right.set_ylabel("mean |t - t_exact| / t_exact" + (" (log)" if right.get_yscale() == "log" else ""))
        for ax in (left, right) if right.axison else (left,):
            ax.set_xscale("log")
            ax.set_xlabel("speed (Mrays/s, log scale)")
            ax.set_title(f"{scene}, {name} ({len(of_scene)} run{'s' if len(of_scene) != 1 else ''})", fontsize=9)
        handles, labels = left.get_legend_handles_labels()
        if any_noisy:
            handles.append(Line2D([], [], ls="none", marker="o", mfc="white", mec="0.3"))
            labels.append("hollow: a timing warning\n(the noise guard: not a timing of record)")
        right.legend(handles, labels, fontsize=7, loc="upper left",
                     bbox_to_anchor=(1.02, 1.0))  # one legend (the left panel's, with the fronts), beside the points
    fig.text(0.01, 0.005, "Horizontal bars: the speed's interval, from the kernel time's (95% interval of "
             "the median where recorded, else min-max of the repetitions).", fontsize=7.5, color="0.2")
    fig.suptitle(f"Speed against accuracy (the exact reference), one point per run, a row per scene and image size"
                 f"\n{device}", fontsize=10)
    save(fig, folder, "speed_vs_accuracy", written, rect=(0, 0.3 / fig.get_size_inches()[1], 1, 1))


def reduced_lines(runs, how):
    """Per scene and method (structure, strategy, test): the runs of variant `how` with the same
    method's run on the scene as it is, for lines from the full scene down."""
    runs = runs.assign(variant=variant(runs), method=[method_label(r) for _, r in runs.iterrows()])
    for scene in sorted(runs.scene.unique()):
        of_scene = runs[runs.scene == scene]
        reduced = of_scene[of_scene.variant == how]
        for method in sorted(reduced.method.unique(), key=method_sort_key):
            yield scene, method, of_scene[(of_scene.method == method) & of_scene.variant.isin(["", how])]


def vertex_precision(runs, device, folder, written):
    """Packed vertices: rays wrong against the exact reference and vertex bytes per ray against the
    bits per axis; float vertices (32 bits) are a point of their own, not joined to the packed ones."""
    lines = list(reduced_lines(runs, "packed"))
    if not lines:
        return skip(folder, "vertex_precision", "no runs with packed vertices (intersection.vertex_bits < 32)")
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6))
    drawn, ppms = [], []
    for scene, method, group in lines:
        group = group.assign(bits=vertex_bits(group)).sort_values("bits")
        packed, floats = group[group.bits < 32], group[group.bits >= 32]
        for ax, values in ((left, wrong_ppm), (right, lambda g: g.bytes_vertices / g.rays)):
            line, = ax.plot(packed.bits, values(packed), marker="o", label=f"{scene}: {method}")
            if not floats.empty:  # float vertices: a star at "float", no line from 16 bits to it
                ax.plot(floats.bits, values(floats), ls="none", marker="*", ms=11, color=line.get_color())
        drawn.append(group)
        ppms += list(wrong_ppm(group))
    wrong_ppm_axis(left, ppms, "rays wrong vs exact (per million; log above 1)")
    right.set_ylabel("triangle vertex bytes read per ray")
    bits = sorted(vertex_bits(pd.concat(drawn)).unique())
    for ax in (left, right):
        ax.set_xlabel("vertex bits per axis (packed); float vertices apart, a star")
        ax.set_xscale("log", base=2)
        ax.set_xticks(bits, [str(int(b)) if b < 32 else "float" for b in bits])
        ax.minorticks_off()
        if bits[-1] >= 32 and len(bits) > 1:
            ax.axvline(math.sqrt(bits[-2] * bits[-1]), color="0.6", ls=":", lw=1)  # packed | float
        ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"Reduced vertex precision: accuracy against bandwidth ({size(pd.concat(drawn))})\n{device}",
                 fontsize=10)
    save(fig, folder, "vertex_precision", written)


def simplification(runs, device, folder, written):
    """Simplified scenes judged against the full one: rays wrong and speed against the triangles kept."""
    lines = list(reduced_lines(runs, "simplified"))
    if not lines:
        return skip(folder, "simplification", "no runs on a simplified scene (scene.simplify_*)")
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6))
    drawn, ppms, embree_drawn = [], [], []
    for scene, method, group in lines:
        group = group.sort_values("scene_triangles")
        # A simplified scene has other triangles: only a miss or a false hit is wrong. The line counts
        # those on every point, the full scene's too; its wrong triangles as well: a hollow marker.
        hit_miss = 1e6 * (group.exact_false_misses + group.exact_false_hits) / group.exact_rays
        line, = left.plot(group.scene_triangles, hit_miss, marker="o", label=f"{scene}: {method}")
        full = group[~simplified(group)]
        if not full.empty and (wrong_ppm(full) != hit_miss[full.index]).any():
            left.scatter(full.scene_triangles, wrong_ppm(full), marker="o", s=60, facecolors="none",
                         edgecolors=line.get_color(), label=f"{scene}: {method}, full scene with wrong triangles")
        line, = right.plot(group.scene_triangles, group.kernel_mrays_s, marker="o", label=f"{scene}: {method}")
        if scene not in embree_drawn:  # Embree on the scene's versions: once per scene, black
            right.plot(group.scene_triangles, group.embree1_mrays_s, ls=":", color="k",
                       marker="s^v<>"[len(embree_drawn) % 5], ms=4, label=f"{scene}: Embree rtcIntersect1 on the same scene")
            embree_drawn.append(scene)
        drawn.append(group)
        ppms += list(hit_miss) + list(wrong_ppm(full))
    left.axhline(1000, color="gray", lw=1, ls="--", label="0.1% of the rays")
    wrong_ppm_axis(left, ppms + [1000], "rays missed or falsely hit vs exact, full scene (per million)")
    right.set_yscale("log")
    right.set_ylabel("Mrays/s (log)")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_xlabel("triangles traced (log; the rightmost point is the full scene)")
        ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"Simplified scenes (CGAL edge collapse): accuracy and speed ({size(pd.concat(drawn))})\n{device}",
                 fontsize=10)
    save(fig, folder, "simplification", written)


def dodge(ax, i: int, n: int, step: float = 5.0):
    """ax.transData moved sideways by a few points for the i-th of n series at the same x: coincident
    points stay visible and no value changes."""
    step = min(step, 36.0 / max(n, 1))
    return transforms.offset_copy(ax.transData, fig=ax.figure, x=(i - (n - 1) / 2) * step, y=0, units="points")


def anchor(ax, xs, ys):
    """Points drawn through dodge() (an offset transform) do not widen the axes: their data do here."""
    xy = np.column_stack([np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)])
    xy = xy[np.isfinite(xy).all(axis=1)]
    if len(xy):
        ax.update_datalim(xy)
        ax.autoscale_view()


def legend_beside(fig, legend_ax, handles_labels, title=None, fontsize=7):
    """One legend for the figure in its own (blank) axes to the right: it covers no data."""
    seen = {}
    for handle, label in handles_labels:
        seen.setdefault(label, handle)
    legend_ax.axis("off")
    legend_ax.legend(list(seen.values()), list(seen.keys()), loc="upper left", fontsize=fontsize, title=title,
                     title_fontsize=fontsize, frameon=False, borderaxespad=0.0)


def failure_map(runs, failed, device, folder, written):
    """Rays wrong against the exact reference as a scene moves (scene.translate) or scales (scene.scale):
    one panel per swept axis and scene, one marker per method and value (no lines: a single ray
    wrong at one offset is not a trend between offsets), Embree black, refused runs marked."""
    if "exact_rays" not in runs:
        return skip(folder, "failure_map", "no exact_rays column (a folder from before the exact reference)")
    if "scene_translate_x" not in runs:
        return skip(folder, "failure_map", "no scene_translate columns")
    everything = concat([runs, failed.assign(scene=failed.scene_source.map(scene_name))])
    everything["ok"] = everything.status == "ok"
    everything["offset"] = everything.scene_translate_x.astype(float)
    panels = []
    for scene, group in everything.groupby("scene"):
        if group.offset.nunique() > 1:
            panels.append((f"{scene} moved by (d, d, d)", "offset d", group[group.scene_scale == 1.0], "offset"))
        if group.scene_scale.nunique() > 1:
            panels.append((f"{scene} scaled", "scale", group[group.offset == 0.0], "scene_scale"))
    if not panels:
        return skip(folder, "failure_map", "no scene was moved (scene.translate) or scaled (scene.scale) across runs")
    grid = plt.GridSpec(1, len(panels) + 1, width_ratios=[1] * len(panels) + [0.75])
    fig = plt.figure(figsize=(4.6 * len(panels) + 3.4, 4.8))
    axes = [fig.add_subplot(grid[0, i]) for i in range(len(panels))]
    handles = []
    methods = sorted({method_label(r) for _, r in everything[everything.ok].iterrows()})
    markers = dict(zip(methods, "osD^vP<>Xhp*" * 3))
    for ax, (title, xlabel, group, x) in zip(axes, panels):
        ok = group[group.ok].copy()
        ok["method"] = [method_label(r) for _, r in ok.iterrows()]
        present = [m for m in methods if (ok.method == m).any()]
        values = []
        # Sum over the views of a point (e.g. the closed meshes' three look-at directions).
        for i, method in enumerate(present):
            ppm = wrong_ppm_summed(ok[ok.method == method], x)
            watertight = method.endswith("watertight")
            ax.plot(ppm.index, ppm, ls="none", marker=markers[method], ms=5, label=method, color=method_color(method),
                    mfc="none" if watertight else method_color(method), alpha=0.5 if "multipass" in method else 0.9,
                    transform=dodge(ax, i, len(present) + 1, 3.0))
            values += list(ppm)
            anchor(ax, ppm.index, ppm)
        embree = ok.drop_duplicates([x, *LOOK_AT, "scene_source"] if "camera_look_at_x" in ok else [x, "scene_source"])
        ppm = wrong_ppm_summed(embree, x, "embree_exact_")
        ax.plot(ppm.index, ppm, ls="none", marker="s", color="k", ms=5, label="Embree rtcIntersect1 (CPU)",
                transform=dodge(ax, len(present), len(present) + 1, 3.0))
        values += list(ppm)
        refused = sorted(set(group[~group.ok][x]))
        for v in refused:
            ax.axvline(v, color="tab:red", lw=6, alpha=0.15)
        if refused:
            ax.plot([], [], color="tab:red", lw=6, alpha=0.3, label="refused: outside the methods' range")
        ax.set_xscale("symlog" if x == "offset" else "log", **({"linthresh": 1.0} if x == "offset" else {}))
        xs = sorted(set(group[x]))  # refused runs too (axvline does not widen the axis)
        ax.set_xlim(-0.5 if x == "offset" else xs[0] / 3, xs[-1] * 3)
        wrong_ppm_axis(ax, values, "rays wrong vs exact (per million; log above 1)")
        ax.set_xlabel(xlabel + " (log)")
        ax.set_title(title, fontsize=9)
        handles += list(zip(*ax.get_legend_handles_labels()))
    rank = {m: i for i, m in enumerate(methods)}  # the methods in order, then Embree and the refused runs
    handles.sort(key=lambda hl: rank.get(hl[1], len(rank) + ("refused" in hl[1])))
    legend_beside(fig, fig.add_subplot(grid[0, -1]), handles,
                  "hollow: watertight test; points of one value side by side", fontsize=7)
    fig.suptitle(f"Failure map: leaks, false hits and wrong triangles against the exact reference\n{device}", fontsize=10)
    save(fig, folder, "failure_map", written)


def passes_vs_threshold(runs, device, folder, written):
    if "strategy_oracle_threshold" not in runs:
        return skip(folder, "passes_vs_threshold", "no strategy_oracle_threshold column")
    oracle = runs[(runs.strategy_type == "multipass") & (runs.strategy_scheduling == "oracle")]
    if oracle.sweep.isin(["oracle"]).any():  # the threshold sweep and the runs at the base threshold
        oracle = oracle[oracle.sweep.isin(["oracle", "architecture"])]
    if oracle.strategy_oracle_threshold.nunique() < 3:
        return skip(folder, "passes_vs_threshold", f"oracle thresholds among the multipass runs with oracle scheduling: "
                    f"{oracle.strategy_oracle_threshold.nunique()} (needs 3)")
    k, m = oracle.strategy_traverse_steps_per_pass.mode()[0], oracle.strategy_intersections_per_pass.mode()[0]
    oracle = oracle[(oracle.strategy_traverse_steps_per_pass == k) & (oracle.strategy_intersections_per_pass == m)]
    scenes = sorted(oracle.scene.unique())
    fig, axes = plt.subplots(1, len(scenes), figsize=(4.2 * len(scenes), 4), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        group = oracle[oracle.scene == scene].sort_values("strategy_oracle_threshold")
        ax.plot(group.strategy_oracle_threshold, group.passes_traverse + group.passes_intersect, "o-", label="traverse + intersect passes")
        ax.plot(group.strategy_oracle_threshold, group.passes_intersect, "s:", label="intersect passes")
        ax.axhline(group.passes_lower_bound.iloc[0], color="k", ls="--", lw=1, label="lower bound (Purcell)")
        ax.set_yscale("log")
        ax.set_xlabel("oracle threshold (waiting / active rays)")
        ax.set_ylabel("passes (log scale)")
        ax.set_title(f"{scene}, {size(group)}")
        ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"Passes against oracle threshold, K = {int(k)}, M = {int(m)}; {device}")
    save(fig, folder, "passes_vs_threshold", written)


def bandwidth_by_category(runs, device, folder, written):
    """Bytes read and written per frame by data type: a bar per run (of the architecture sweep, if
    any), labelled by scene, strategy and every swept key that differs between the bars."""
    if runs.structure_type.nunique() > 1:
        return skip(folder, "bandwidth_by_category", "several structures (structure_type): the structures_* charts "
                    "compare them")
    chosen = runs[runs.sweep == "architecture"] if (runs.sweep == "architecture").any() else runs
    keys = [k for k in swept_keys(chosen) if k not in ("scene_source", "strategy_type")]
    chosen = chosen.drop_duplicates(["scene", "strategy_type"] + keys).sort_values(["scene", "strategy_type"] + keys)
    if len(chosen) > 40:
        return skip(folder, "bandwidth_by_category", f"{len(chosen)} different runs: too many bars for one chart "
                    f"(the by_<key> charts show them)")
    labels = run_labels(chosen, ["scene", "strategy_type"], keys)
    fig, ax = plt.subplots(figsize=(max(7, 1.25 * len(chosen)), 5.0))
    present = [(c, n) for c, n in BYTES if c in chosen and chosen[c].fillna(0).any()]
    stacked_bars(ax, labels, chosen, present, 1e-6)
    ax.set_ylabel("bytes read and written per frame (MB)")
    ax.set_title(f"Bandwidth by data type (Purcell Fig. 8 style), {size(chosen)}\n{device}")
    save(fig, folder, "bandwidth_by_category", written)


# Purcell Fig. 9's data types: the cache_ratio_<kind> column of each bytes_<column> (cells: voxels or
# BVH nodes); output is written, never cached (ratio 1).
CACHED = [("bytes_stencil", "stencil"), ("bytes_state", "state"), ("bytes_stack", "stack"), ("bytes_voxel", "cells"),
          ("bytes_node", "cells"), ("bytes_triangle_list", "triangle_list"), ("bytes_vertices", "vertices"),
          ("bytes_output", None)]


def texture_cache(runs, device, folder, written):
    """Purcell et al. 2002 Fig. 9: memory traffic with the texture cache over traffic without, a bar
    per run (cache.simulate), each split by data type: a type's traffic with the cache over the
    run's total without it, so the bar's height is cache_ratio_total."""
    if "cache_ratio_total" not in runs or runs.cache_ratio_total.isna().all():
        return skip(folder, "texture_cache", "no run with cache.simulate = true")
    chosen = runs[runs.cache_ratio_total.notna()]
    keys = [k for k in swept_keys(chosen) if k not in ("scene_source", "strategy_type")]
    keys = [first for first, _ in key_classes(chosen, keys)]  # camera_height goes with camera_width
    chosen = chosen.sort_values(["scene", "strategy_type"] + keys)
    labels = run_labels(chosen, ["scene", "strategy_type"], keys)
    parts = pd.DataFrame(index=chosen.index)
    for column, kind in CACHED:
        if column not in chosen or not chosen[column].fillna(0).any():
            continue
        ratio = 1.0 if kind is None else chosen[f"cache_ratio_{kind}"].fillna(0)
        parts[column] = chosen[column].fillna(0) * ratio / chosen.bytes_total
    if ((parts.sum(axis=1) - chosen.cache_ratio_total).abs() > 1e-3).any():
        raise PlotError(f"{folder}: texture_cache: the data types' parts do not add up to cache_ratio_total")
    names = dict(BYTES)
    lines = max(label.count("\n") + 1 for label in labels)
    fig, ax = plt.subplots(figsize=(max(7, 1.6 * len(chosen)), 4.0 + 0.2 * lines))
    stacked_bars(ax, labels, parts, [(c, names[c]) for c in parts.columns])
    ax.tick_params(axis="x", labelsize=8)
    ax.axhline(1.0, color="grey", linewidth=0.8, linestyle=":")
    ax.set_ylabel("traffic with the cache / without it")
    cache = chosen.iloc[0]
    ax.set_title(f"Texture cache (Purcell Fig. 9 style): {int(cache.cache_capacity_bytes):,} bytes, "
                 f"{int(cache.cache_line_bytes)}-byte lines, {int(cache.cache_ways)}-way; {size(chosen)}\n"
                 f"replayed on the CPU, the same on every device (kernels timed on {device})")
    save(fig, folder, "texture_cache", written)


def time_line(ax, xs, group, fmt, speed=False, **style):
    """The kernel's median time (or speed, Mrays/s) of each run against xs, with its interval as bars
    (interval(): the 95% interval of the median, else min-max of the repetitions)."""
    low, high, _ = interval(group, "kernel")
    y = group.kernel_ms_median.astype(float)
    if speed:  # Mrays/s = rays / ms / 1e3: the slowest time is the lowest speed
        rays = group.kernel_mrays_s * y * 1e3
        y, low, high = group.kernel_mrays_s, rays / high / 1e3, rays / low / 1e3
    yerr = np.vstack([(y - low).clip(lower=0).fillna(0), (high - y).clip(lower=0).fillna(0)])
    ax.errorbar(xs, y, yerr=yerr, fmt=fmt, capsize=2, elinewidth=0.8, **style)


def christen_grid_size(runs, device, folder, written):
    """Christen 2005 Fig. 6.9: frame time against grid size (sweeps fig6_9 and fig6_8 of
    configs/christen2005.toml), a line per scene and GPU architecture."""
    if not (runs.sweep == "fig6_9").any():
        return skip(folder, "christen_grid_size", "no run of a sweep named fig6_9")
    sizes = runs[runs.sweep.isin(["fig6_8", "fig6_9"]) & runs.strategy_type.isin(["multipass", "branching"])]
    fig, ax = plt.subplots(figsize=(8, 5))
    for (scene, method), g in sizes.groupby(["scene", "strategy_type"]):
        g = g.sort_values("grid_res_x")
        time_line(ax, g.grid_res_x, g, "o-" if method == "multipass" else "^--", label=f"{scene}, {method}")
    ax.set_yscale("log")
    ax.set_xlabel("grid cells along each axis (n × n × n)")
    ax.set_ylabel("frame time, median (ms, log scale)")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"Render time against grid size (Christen 2005 Fig. 6.9 style), {size(sizes)}\n{device}")
    save(fig, folder, "christen_grid_size", written)


def christen_gpu_cpu(runs, device, folder, written):
    """Christen 2005 Figs. 6.10-6.11: frame time by iteration (1: the camera rays, sweep fig6_8;
    2-4: mirror reflections 1-3, sweep fig6_11) of both GPU architectures and of the CPU running
    the same grid traversal, a panel per scene."""
    if not (runs.sweep == "fig6_11").any():
        return skip(folder, "christen_gpu_cpu", "no run of a sweep named fig6_11")
    scenes = runs[runs.sweep == "fig6_11"].scene_source.unique()
    gens = runs[runs.sweep.isin(["fig6_8", "fig6_11"]) & runs.scene_source.isin(scenes)].copy()
    gens["iteration"] = christen_iterations(gens)
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 4.5), squeeze=False)
    for ax, source in zip(axes[0], scenes):
        part = gens[gens.scene_source == source]
        for method, g in part.groupby("strategy_type"):
            g = g.sort_values("iteration")
            time_line(ax, g.iteration, g, "o-", label=method, color=COLORS.get(method))
        ax.set_yscale("log")
        ax.set_xticks(sorted(part.iteration.unique()))
        ax.set_xlabel("iteration (1: camera rays; n: mirror reflection n - 1)")
        ax.set_ylabel("frame time, median (ms, log scale; cpu: wall time)")
        ax.set_title(part.scene.iloc[0])
        ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"Christen 2005 Figs. 6.10-6.11 style, {size(gens)}; {device}:\n"
                 f"{host_against_device(gens, device)}, on the same grid")
    save(fig, folder, "christen_gpu_cpu", written)


def unrolling(runs, device, folder, written):
    unroll = runs[runs.sweep.str.startswith("unroll")]
    if unroll.empty:
        return skip(folder, "unrolling", "no runs of a sweep named unroll*")
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for suppress, style in ((False, "-"), (True, "--")):
        part = unroll[unroll.strategy_suppress_finished_reads == suppress]
        for m, group in part.groupby("strategy_intersections_per_pass"):
            group = group.sort_values("strategy_traverse_steps_per_pass")
            label = f"M = {int(m)}" + (", suppressed" if suppress else "")
            axes[0].plot(group.strategy_traverse_steps_per_pass, group.passes_total, "o" + style, label=label)
            axes[1].plot(group.strategy_traverse_steps_per_pass, group.bytes_per_ray, "o" + style, label=label)
            axes[2].plot(group.strategy_traverse_steps_per_pass, (group.bytes_voxel + group.bytes_vertices) / 1e6, "o" + style, label=label)
    for ax, ylabel in zip(axes, ["passes", "bytes per ray (all categories)", "voxel + vertex data read (MB)"]):
        ax.set_xscale("log", base=2)
        ax.set_xlabel("traversal steps per pass K (log2)")
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"Loop unrolling: K steps by M intersections per pass — {unroll.scene.iloc[0]}, {size(unroll)}; {device}")
    save(fig, folder, "unrolling", written)


def grid_resolution(runs, device, folder, written):
    if runs.structure_type.nunique() > 1:
        return skip(folder, "grid_resolution", "several structures (structure_type): the structures_* charts compare them")
    grid = runs[runs.sweep == "grid"] if (runs.sweep == "grid").any() else runs
    if "structure_min_dim" not in grid:
        return skip(folder, "grid_resolution", "no structure_min_dim column")
    grid = grid[grid.structure_min_dim.notna()]
    if grid.structure_min_dim.nunique() < 3:
        return skip(folder, "grid_resolution", f"grid resolutions (structure_min_dim) among the runs: "
                    f"{grid.structure_min_dim.nunique()} (needs 3)")
    branching = grid[grid.strategy_type == "branching"].sort_values("structure_min_dim")
    data = branching if not branching.empty else grid.drop_duplicates("structure_min_dim").sort_values("structure_min_dim")
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.plot(data.structure_min_dim, data.voxels_per_ray_mean, "o-", label="voxels visited per ray")
    left.plot(data.structure_min_dim, data.triangles_per_ray_mean, "s-", label="triangle tests per ray")
    left.set_xscale("log", base=2)
    left.set_yscale("log")
    left.set_xlabel("min_dim (cells along the smallest extent, log2)")
    left.set_ylabel("per ray, mean (log scale)")
    left.legend(fontsize=8)
    for method, group in grid.groupby("strategy_type"):
        group = group.sort_values("structure_min_dim")
        time_line(right, group.structure_min_dim, group, "o-", speed=True, label=method, color=COLORS.get(method))
    right.set_xscale("log", base=2)
    right.set_yscale("log")
    right.set_xlabel("min_dim (log2)")
    right.set_ylabel("speed (Mrays/s, log scale)")
    right.legend(fontsize=8)
    fig.suptitle(f"Traversal against intersection by grid resolution — {data.scene.iloc[0]}, {size(data)}; {device}")
    save(fig, folder, "grid_resolution", written)


INSTRUCTIONS = [("instructions_traverse", "traverser"), ("instructions_intersect", "intersector"),
                ("instructions_other", "others")]


def compute_by_kernel(runs, device, folder, written):
    """Purcell et al. 2002 Fig. 7: compute by kernel (the instruction estimate: static SPIR-V counts x
    exact event counts) beside bandwidth, a pair of bars per run of the architecture and table2-*
    sweeps (else every run that has the estimate)."""
    if "instructions_total" not in runs or runs.instructions_total.isna().all():
        return skip(folder, "compute_by_kernel", "no instruction estimate (instructions_* columns: branching and "
                    "multipass runs of schema 17 on)")
    if runs.structure_type.nunique() > 1:
        return skip(folder, "compute_by_kernel", "several structures (structure_type): the structures_* charts compare them")
    chosen = runs[runs.instructions_total.notna()]
    purcell = chosen.sweep.eq("architecture") | chosen.sweep.str.startswith("table2-")
    chosen = chosen[purcell] if purcell.any() else chosen
    if len(chosen) > 24:
        return skip(folder, "compute_by_kernel", f"{len(chosen)} runs with the estimate and no architecture or table2-* "
                    "sweep to choose from: too many bars for one chart (the instructions_* columns hold them)")
    table2 = chosen.sweep.str.startswith("table2-")
    chosen = chosen.assign(view=chosen.scene.where(~table2, chosen.sweep.str.replace("table2-", "").str.replace("-", " ") +
                                                   " (Table 2)"))
    keys = [k for k in swept_keys(chosen) if k not in ("scene_source", "strategy_type", "camera_position", "camera_look_at")]
    chosen = chosen.sort_values(["view", "strategy_type"] + keys)
    labels = run_labels(chosen, ["view", "strategy_type"], keys)
    fig, (left, right) = plt.subplots(1, 2, figsize=(max(10, 1.3 * len(chosen)), 5.2))
    stacked_bars(left, labels, chosen, INSTRUCTIONS, 1e-9)
    left.set_ylabel("instructions per frame (billions, estimated)")
    left.set_title("compute by kernel")
    present = [(c, n) for c, n in BYTES if c in chosen and chosen[c].fillna(0).any()]
    stacked_bars(right, labels, chosen, present, 1e-9)
    right.set_ylabel("bytes read and written per frame (GB)")
    right.set_title("bandwidth by data type")
    for ax in (left, right):
        ax.tick_params(axis="x", labelrotation=90 if len(chosen) > 6 else 0, labelsize=7)
    fig.suptitle(f"Compute and bandwidth (Purcell Fig. 7 style), {size(chosen)}: instructions are static SPIR-V counts "
                 f"(glslang, unoptimised) x exact event counts, an estimate\n{device}")
    save(fig, folder, "compute_by_kernel", written, rect=(0, 0, 1, 0.93))


def kernel_time(runs, device, folder, written):
    if runs.structure_type.nunique() > 1:
        return skip(folder, "kernel_time", "several structures (structure_type): the structures_* charts compare them")
    multipass = runs[runs.strategy_type == "multipass"]
    chosen = multipass[multipass.sweep == "architecture"] if (multipass.sweep == "architecture").any() else multipass
    if chosen.empty:
        return skip(folder, "kernel_time", "no multipass runs (strategy_type = multipass)")
    if not all(c in chosen for c, _ in KERNELS):
        return skip(folder, "kernel_time", "no kernel_ms_setup/traverse/intersect/write columns")
    total = len(chosen)
    chosen = chosen.head(12)
    fig, ax = plt.subplots(figsize=(max(7, 1.6 * len(chosen)), 4.8))
    keys = [k for k in swept_keys(chosen) if k != "scene_source"]
    labels = run_labels(chosen, ["scene"], keys)
    if len(set(labels)) < len(labels):  # runs alike in every key: their run numbers
        labels = [f"{label}\nrun {int(r.run):03d}" for label, r in zip(labels, chosen.itertuples())]
    parts = KERNELS + ([ORACLE] if ORACLE[0] in chosen and chosen[ORACLE[0]].fillna(0).any() else [])
    stacked_bars(ax, labels, chosen, parts)
    if len(chosen) > 6:  # labels of two or three lines side by side: turned, so that they do not run together
        ax.tick_params(axis="x", labelrotation=90, labelsize=7)
    ax.set_ylabel("GPU time per frame (ms, median)")
    shown = f", the first 12 of {total} runs" if total > 12 else ""
    ax.set_title(f"Multipass GPU time by kernel, {size(chosen)}{shown}\n{device}")
    save(fig, folder, "kernel_time", written)


def method_color(method: str, among=None) -> str:
    """The method's colour (method_colors), among the methods of its chart when given."""
    return method_colors(list(among or []) + [method])[method]


def with_methods(runs):
    runs = runs.copy()
    runs["method"] = [method_name(r) for _, r in runs.iterrows()]
    runs["method_kind"] = [m.split(" (")[0] for m in runs.method]  # "auto (bvh)" -> "auto"
    return runs


def grouped_bars(ax, frame, value, scenes, methods, log=True):
    """Bars of `value` per scene (groups) and method (bars), with the method's colour; a method with
    no successful run at a scene gets a grey x where its bar would be. True if any bar is missing."""
    width = 0.8 / max(len(methods), 1)
    prefix = {"kernel_ms_median": "kernel_ms", "speed_ratio_vs_embree1": "speed_ratio"}.get(value)  # its interval's columns
    missing = []
    for i, method in enumerate(methods):
        xs, ys, lows, highs = [], [], [], []
        for j, scene in enumerate(scenes):
            row = frame[(frame.scene == scene) & (frame.method_kind == method)]
            x = j + (i - (len(methods) - 1) / 2) * width
            if row.empty or not np.isfinite(pd.to_numeric(row[value], errors="coerce").iloc[0]):
                missing.append(x)
                continue
            xs.append(x)
            ys.append(row[value].iloc[0])
            if prefix and f"{prefix}_ci_low" in row:  # the median's 95% interval, where recorded
                lows.append(row[f"{prefix}_ci_low"].iloc[0])
                highs.append(row[f"{prefix}_ci_high"].iloc[0])
        yerr = None
        if lows:
            y = np.asarray(ys, dtype=float)
            yerr = np.vstack([np.nan_to_num(np.clip(y - np.asarray(lows, dtype=float), 0, None)),
                              np.nan_to_num(np.clip(np.asarray(highs, dtype=float) - y, 0, None))])
        ax.bar(xs, ys, width, color=method_color(method, methods), yerr=yerr,
               error_kw={"elinewidth": 0.7, "capsize": 1.5, "ecolor": "0.25"})
    ax.scatter(missing, [0.03] * len(missing), marker="x", color="0.5", s=14, transform=ax.get_xaxis_transform())
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels([textwrap.fill(scene, 12) for scene in scenes], fontsize=8)
    if log:
        ax.set_yscale("log")
    return bool(missing)


def bars_figure(rows: int, height: float):
    """A figure of `rows` x 2 panels and a legend column beside them: (figure, panels, legend axes)."""
    fig = plt.figure(figsize=(16, height * rows))
    grid = plt.GridSpec(rows, 3, figure=fig, width_ratios=[1, 1, 0.3])
    panels = [[fig.add_subplot(grid[r, c]) for c in range(2)] for r in range(rows)]
    return fig, panels, fig.add_subplot(grid[:, 2])


def method_handles(methods, missing=False, extra=()):
    """The legend of a bars figure: a patch per method in its colour, then `extra` (handle, label)
    pairs, and the grey x where a bar is missing."""
    handles = [(Patch(color=method_color(m, methods)), m) for m in methods] + list(extra)
    if missing:
        handles.append((Line2D([], [], ls="none", marker="x", color="0.5"), "x: no successful run\n(runs.csv says why)"))
    return handles


def structures_comparable(runs):
    """Why the structures_* charts (one bar per scene, structure and strategy) cannot be drawn: they
    need several structures and exactly one run for each bar (not, say, a sweep of the triangle test
    as well); None when they can."""
    if runs.structure_type.nunique() < 2:
        return f"structures (structure_type) among the runs: {runs.structure_type.nunique()} (needs 2)"
    twice = with_methods(runs).duplicated(["scene", "method_kind", "strategy_type"]).sum()
    if twice:
        keys = [k for k in swept_keys(runs) if k not in ("scene_source", "structure_type", "strategy_type",
                                                             "structure_min_dim")]
        return (f"{twice} runs share a scene, structure and strategy with another (they differ in "
                f"{', '.join(keys) or 'no swept key'}): one bar each is not possible; see the by_<key> charts")
    return None


def structure_order(runs):
    return sorted(runs.method_kind.unique().tolist(), key=method_sort_key)


def structures_time(runs, device, folder, written):
    if structures_comparable(runs):
        return skip(folder, "structures_time", structures_comparable(runs))
    runs = with_methods(runs)
    scenes = runs.sort_values("scene_triangles").scene.unique().tolist()
    methods = structure_order(runs)
    strategies = [s for s in ("branching", "multipass") if (runs.strategy_type == s).any()]
    fig, axes, legend_ax = bars_figure(len(strategies), 4.2)
    missing = False
    for row, strategy in zip(axes, strategies):
        part = runs[runs.strategy_type == strategy]
        missing |= grouped_bars(row[0], part, "kernel_ms_median", scenes, methods)
        embree = part.groupby("scene").embree1_ms_median.median()  # a line across each scene's bars
        row[0].hlines(embree.values, [scenes.index(s) - 0.42 for s in embree.index],
                      [scenes.index(s) + 0.42 for s in embree.index], color="k", lw=1.6, zorder=3)
        live = strategy == "multipass" and live_headline(part)  # host control: the live loop's wall time
        row[0].set_ylabel("time per frame (ms, median, log):\nthe live pass loop's host wall time" if live
                          else "GPU time per frame (ms, median, log)")
        row[0].set_title(f"{strategy}: time per scene")
        missing |= grouped_bars(row[1], part, "speed_ratio_vs_embree1", scenes, methods)
        row[1].axhline(1.0, color="k", lw=1, ls="--")
        row[1].set_ylabel("Mrays/s / Embree rtcIntersect1's (log)")
        row[1].set_title(f"{strategy}: speed against Embree on the same rays")
    extra = [(Line2D([], [], color="k", lw=1.6), "Embree rtcIntersect1 (CPU, the same rays)"),
             (Line2D([], [], color="k", lw=1, ls="--"), "as fast as Embree")]
    legend_beside(fig, legend_ax, method_handles(methods, missing, extra))
    fig.text(0.01, 0.005, "Error bars: the 95% interval of the median (kernel_ms_ci_low/high, "
             "speed_ratio_ci_low/high) where recorded.", fontsize=7.5, color="0.2")
    fig.suptitle(f"Structures side by side, {size(runs)} primary rays; {device}")
    save(fig, folder, "structures_time", written, rect=(0, 0.02, 1, 1))


def structures_memory(runs, device, folder, written):
    if structures_comparable(runs):
        return skip(folder, "structures_memory", structures_comparable(runs))
    runs = with_methods(runs)
    runs = runs[runs.strategy_type == runs.strategy_type.iloc[0]]  # the structure is the same for both strategies
    scenes = runs.sort_values("scene_triangles").scene.unique().tolist()
    methods = [m for m in structure_order(runs) if m != "auto"]
    fig, ((left, right),), legend_ax = bars_figure(1, 4.2)
    missing = grouped_bars(left, runs, "structure_bytes_per_triangle", scenes, methods)
    left.set_ylabel("device bytes per triangle (log)")
    left.set_title("Memory: the structure's buffers, vertices included")
    missing |= grouped_bars(right, runs, "structure_build_ms", scenes, methods)
    right.set_ylabel("CPU build time (ms, log)")
    right.set_title("Build time (grid: exact cells, CGAL where filters are unsure;\nBVH: Embree rtcBuildBVH)")
    legend_beside(fig, legend_ax, method_handles(methods, missing))
    fig.suptitle(f"Memory and build time per structure; {device}")
    save(fig, folder, "structures_memory", written)


def build_times(runs, device, folder, written):
    """experiment.build_rounds: the grid's build against its cells, per scene, beside Embree's BVH
    build of the same triangles (medians of the rounds), and their ratio with its 95% interval."""
    if "build_rounds" not in runs or not (runs.build_rounds > 0).any():
        return skip(folder, "build_times", "no build rounds (experiment.build_rounds = 0)")
    grid = runs[(runs.build_rounds > 0) & (runs.structure_type == "uniform_grid")]
    if grid.empty or grid.groupby("scene").size().max() < 2:
        return skip(folder, "build_times", "no scene with grids at two resolutions or more")
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6))
    scenes = grid.sort_values("scene_triangles").scene.unique().tolist()
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, scene in enumerate(scenes):
        g = grid[grid.scene == scene].sort_values("grid_cells")
        color = colors[i % len(colors)]
        label = f"{scene} ({int(g.scene_triangles.iloc[0]):,} triangles)"
        left.plot(g.grid_cells, g.structure_build_ms_median, "o-", color=color, label=label)
        left.axhline(g.embree_build_ms_median.median(), color=color, linestyle="--", linewidth=1)
        right.plot(g.grid_cells, g.build_ratio_vs_embree, "o-", color=color, label=label)
        spans = g[g.build_ratio_ci_low.notna() & g.build_ratio_ci_high.notna()]  # a run without an interval gets no bar
        low = (spans.build_ratio_vs_embree - spans.build_ratio_ci_low).clip(lower=0)
        high = (spans.build_ratio_ci_high - spans.build_ratio_vs_embree).clip(lower=0)
        right.errorbar(spans.grid_cells, spans.build_ratio_vs_embree, yerr=[low, high], fmt="none", ecolor=color, capsize=3)
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("grid cells (log), one point per min_dim")
    left.set_ylabel("build ms, median of the rounds (log)")
    left.set_title("Grid build (solid) and Embree's BVH build of the same scene (dashed)")
    right.axhline(1.0, color="black", linewidth=1)
    right.set_ylabel("grid build / Embree build (log)")
    right.set_title("Ratio, with its 95% interval; below the line the grid builds faster")
    handles, labels = right.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    rounds = int(grid.build_rounds.max())
    fig.suptitle(f"Build times, {rounds} rounds alternating the two builds; {device}")
    save(fig, folder, "build_times", written, rect=(0, 0.1, 1, 1))


def structures_work(runs, device, folder, written):
    if structures_comparable(runs):
        return skip(folder, "structures_work", structures_comparable(runs))
    runs = with_methods(runs)
    scenes = runs.sort_values("scene_triangles").scene.unique().tolist()
    methods = [m for m in structure_order(runs) if m != "auto"]
    fig, ((left, right),), legend_ax = bars_figure(1, 4.5)
    part = runs[(runs.strategy_type == "branching") & (runs.method_kind != "auto")]
    for method in methods:
        group = part[part.method_kind == method]
        left.scatter(group.predicted_work_per_ray, group.work_per_ray_mean, color=method_color(method, methods))
    lo = max(1e-2, min(part.predicted_work_per_ray.min(), part.work_per_ray_mean.min()))
    hi = max(part.predicted_work_per_ray.max(), part.work_per_ray_mean.max())
    left.plot([lo, hi], [lo, hi], "k--", lw=1)
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_xlabel("predicted work per ray (cost model: visits + tests)")
    left.set_ylabel("measured work per ray")
    left.set_title("The cost model against the measured work (branching)")
    missing = grouped_bars(right, part, "simd_lane_utilisation", scenes, methods, log=False)
    right.set_ylim(0, 1.05)
    right.set_ylabel("active lanes / lane slots")
    right.set_title("Lane utilisation of the branching kernel (Aila & Laine)")
    extra = [(Line2D([], [], color="k", ls="--", lw=1), "measured = predicted (left)")]
    legend_beside(fig, legend_ax, method_handles(methods, missing, extra))
    fig.suptitle(f"Work per ray and lane utilisation, {size(runs)}; {device}")
    save(fig, folder, "structures_work", written)


# The by_<key> charts: one per swept key, time and rays wrong against the key's values.
MARKERS = "o^vP<>Xh*p"  # squares and diamonds are Embree's
LINESTYLES = ["-", "--", ":", "-."]
POOL_ABOVE = 8  # more settings of the other keys than this: one series per method, a dot per run
FLOAT_BITS = {"intersection_vertex_bits": 32}  # a value apart (float vertices), not joined to the others
EMBREE_BLIND = ("structure_", "strategy_", "intersection_test")  # keys Embree's runs do not depend on


def embree_traced_path(data):
    """Per row: True where Embree traced every generation of the path beside a whole-path strategy
    (results schema 19: whole_path_rays set), not only the batch the run's other methods trace."""
    if "whole_path_rays" not in data:
        return pd.Series(False, index=data.index)
    return pd.to_numeric(data.whole_path_rays, errors="coerce").fillna(0) > 0


def runs_count(n: int) -> str:
    return f"{n} run" if n == 1 else f"{n} runs"


def interval(frame, prefix):
    """Error bar ends of `<prefix>_ms_median` per row, and what they are: the 95% interval
    of the median (`<prefix>_ms_ci_low`, `_ci_high`) where a row has it, else the repetitions' range
    (`<prefix>_ms_min`, `_max`)."""
    low, high, what = pd.Series(np.nan, frame.index), pd.Series(np.nan, frame.index), []
    for lo, hi, name in ((f"{prefix}_ms_ci_low", f"{prefix}_ms_ci_high", "95% interval of the median"),
                         (f"{prefix}_ms_min", f"{prefix}_ms_max", "min-max of the repetitions")):
        if lo in frame and hi in frame:
            a, b = pd.to_numeric(frame[lo], errors="coerce"), pd.to_numeric(frame[hi], errors="coerce")
            use = low.isna() & a.notna() & b.notna()
            if use.any():
                low[use], high[use] = a[use], b[use]
                what.append(f"{name} ({lo.rsplit('_', 1)[0]}_{lo.rsplit('_', 1)[1]}/{hi.rsplit('_', 1)[1]})")
    return low, high, what


def wrong_ppm_of(frame, prefix="exact_"):
    """The runs' rays wrong per million (the `<prefix>wrong_ppm` column, or its parts), NaN without."""
    if f"{prefix}wrong_ppm" in frame:
        return pd.to_numeric(frame[f"{prefix}wrong_ppm"], errors="coerce")
    if all(f"{prefix}{c}" in frame for c in ("false_misses", "false_hits", "wrong_primitive")) and "exact_rays" in frame:
        return wrong_ppm(frame, prefix)
    return pd.Series(np.nan, frame.index)


def per_ray_scale(frame, column):
    """ms per frame -> ns per ray: 1e6 / the rays of each run (NaN where unknown)."""
    rays = pd.to_numeric(frame[column], errors="coerce")
    return 1e6 / rays.where(rays > 0)


def compact(value: str) -> str:
    """A vector label short: "[1000000 1000000 1000000]" -> "[1e6 1e6 1e6]"."""
    text = str(value)
    if not (text.startswith("[") and text.endswith("]")):
        return text
    try:
        numbers = [float(x) for x in text.strip("[]").replace(",", " ").split()]
    except ValueError:
        return text
    def short(v):
        return (f"{v:.3g}" if abs(v) >= 1e4 else f"{v:g}").replace("e+0", "e").replace("e+", "e").replace("e-0", "e-")
    return "[" + " ".join(short(v) for v in numbers) + "]"


def category_order(values):
    """Values in a reader's order: numbers and vectors by their numbers ([1 1 1] before [100 100 100]),
    words alphabetically."""
    def order(v):
        try:
            return (0, tuple(float(x) for x in str(v).strip("[]").replace(",", " ").split()), "")
        except ValueError:
            return (1, (), str(v))
    return sorted(set(values), key=order)


def series_segments(xs, ys, key):
    """(xs, ys) pieces of a line: split where a value stands apart (float vertices at 32 bits)."""
    apart = FLOAT_BITS.get(key)
    if apart is None:
        return [(xs, ys)]
    xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
    return [(xs[xs < apart], ys[xs < apart]), (xs[xs >= apart], ys[xs >= apart])]


def concat(frames):
    with warnings.catch_warnings():  # pandas 1.5 on object columns of bools and NaN: a FutureWarning
        warnings.simplefilter("ignore", FutureWarning)
        return pd.concat(frames, ignore_index=True)


def by_key_charts(runs, failed, device, folder, written):
    """One by_<key> chart per swept key (keys that go one for one with another are drawn in its chart)."""
    everything = concat([runs, failed])
    keys = swept_keys(everything)
    if not keys:
        return skip(folder, "by_<key>", "no config key takes two values over the runs (nothing swept)")
    classes = key_classes(everything, keys)
    for key, followers in classes:
        for follower in followers:
            skip(folder, f"by_{follower}", f"{follower} goes one for one with {key} over the runs: drawn in by_{key}")
        draw(f"by_{key}", folder, by_key, runs, classes, key, followers, device, folder, written, failed)


def by_key(runs, classes, key, followers, device, folder, written, failed=None):
    """GPU time (kernel median, Embree rtcIntersect1 beside it) and rays wrong against the exact
    reference against the values of `key`: a row per scene, a colour per method (structure x
    strategy), a marker and line per setting of the other swept keys, error bars said in the caption."""
    name = f"by_{key}"
    members = [key] + followers
    every_key = [k for first, rest in classes for k in [first] + rest]
    text = as_text(runs, every_key)
    have = runs[text[key] != ""]
    if have.empty:
        return skip(folder, name, f"no successful run has a value of {key}")
    if text.loc[have.index, key].nunique() < 2:
        return skip(folder, name, f"{key} = {text.loc[have.index, key].iloc[0]} in every successful run (the runs at "
                    f"its other values failed)")
    # Every run with a value, whichever sweep it is of: a series joins runs alike in every other swept
    # key, so a run another sweep holds at one value joins a series only where it is alike.
    data = have
    faceted = "scene_source" not in members
    xtext = data.scene if not faceted else text.loc[data.index, key]
    facets = list(data.groupby("scene")) if faceted else [("all scenes", data)]
    one_value = [scene for scene, group in facets if xtext[group.index].nunique() < 2]
    facets = [(scene, group) for scene, group in facets if xtext[group.index].nunique() >= 2]
    if not facets:
        return skip(folder, name, f"no scene was run at two values of {key} ("
                    + "; ".join(f"{scene}: {', '.join(sorted(xtext[data.scene == scene].unique()))}"
                                for scene in sorted(data.scene.unique())[:4]) + ")")
    # Where the key's values go on the x axis.
    numbers = pd.to_numeric(xtext, errors="coerce")
    numeric = bool(numbers.notna().all()) and faceted
    order = category_order(xtext) if not numeric else sorted(set(numbers))
    position = numbers if numeric else xtext.map({v: i for i, v in enumerate(order)})
    # Series: a colour per method, a marker and line per setting of the other swept keys.
    method_parts = [k for k in METHOD_KEYS if k not in members and k in data]
    method = data.apply(lambda r: " ".join(STRUCTURE_NAMES.get(r[k], str(r[k])) if k == "structure_type" else str(r[k])
                                           for k in method_parts) or "runs", axis=1)
    aside = {k for first, rest in classes if "scene_source" in [first] + rest or set(METHOD_KEYS) & set([first] + rest)
             for k in [first] + rest}
    vary, merged = [], []
    for first, _ in classes:
        if first in members or first in aside:
            continue
        values = text.loc[data.index, first]
        if values[values != ""].nunique() < 2:
            continue
        empty = (values == "").groupby(xtext).all()
        if empty.any() and not empty.all():
            merged.append(first)  # does not apply at some values of the key: cannot be held fixed along it
        else:
            vary.append(first)
    if not numeric:  # categories are points, never joined: a key that applies at some values is told apart too
        vary, merged = vary + merged, []
    combo = text.loc[data.index, vary].apply(tuple, axis=1) if vary else pd.Series([()] * len(data), data.index)
    frame = data.assign(_x=position, _method=method, _combo=combo, _ppm=wrong_ppm_of(data),
                        _embree_ppm=wrong_ppm_of(data, "embree_exact_"), _simplified=simplified(data),
                        _embree_path=embree_traced_path(data))
    # A line needs two values of the key; the rest are not drawn (and counted in the caption).
    counts = frame.groupby((["scene"] if faceted else []) + ["_method", "_combo"])._x.transform("nunique")
    dropped = frame[(counts < 2) & numeric]
    frame = frame[(counts >= 2) | (not numeric)]
    pooled = frame._combo.nunique() > POOL_ABOVE  # too many to tell apart: a faint line each, one style
    # Where the batch differs between the runs drawn (later bounces, reflections), a frame's time says
    # how many rays there were: time per ray traced instead (kernel: rays; Embree: embree_rays).
    per_ray = "rays" in frame and any(pd.to_numeric(group.rays, errors="coerce").nunique() > 1
                                      for _, group in (frame.groupby("scene") if faceted else [("", frame)]))
    frame = frame.assign(_kscale=per_ray_scale(frame, "rays") if per_ray else 1.0,
                         _escale=per_ray_scale(frame, "embree_rays" if "embree_rays" in frame else "rays") if per_ray else 1.0)
    facets = [(scene, frame[frame.scene == scene] if faceted else frame) for scene, _ in facets]
    facets = [(scene, group) for scene, group in facets if not group.empty]
    if not facets:
        return skip(folder, name, f"no method was run at two values of {key} with its other settings alike")
    methods = sorted(frame._method.unique(), key=method_sort_key)
    colors = method_colors(methods)
    combos = sorted(frame._combo.unique(), key=lambda c: [natural_key(str(v)) for v in c])
    # A combination's label names the keys that take two values among the drawn series (a key at one
    # value where it applies says nothing); combinations that read alike share a style.
    telling = [i for i in range(len(vary)) if len({c[i] for c in combos if c[i] != ""}) > 1]
    labels_of = {c: ", ".join(f"{short_key(vary[i])}={c[i]}" for i in telling if c[i])
                 or ", ".join(f"{short_key(vary[i])}: does not apply" for i in telling) for c in combos}
    names = sorted(set(labels_of.values()), key=natural_key)
    by_label = {n: (MARKERS[i % len(MARKERS)], LINESTYLES[i % len(LINESTYLES)]) if not pooled else ("o", "-")
                for i, n in enumerate(names)}
    styles = {c: by_label[labels_of[c]] for c in combos}
    embree_keys = [i for i, k in enumerate(vary) if not k.startswith(EMBREE_BLIND)]

    # Rays wrong: a panel where some are; where none are (or none were compared), one line of text.
    wrong = finite(list(frame._ppm) + list(frame._embree_ppm))
    accuracy = bool((wrong != 0).any())
    caption_lines = [] if accuracy else [
        "Rays wrong against the exact reference: none in any run drawn, nor in Embree's (exact_wrong_ppm 0)."
        if not wrong.empty else "Rays wrong: no exact reference in these runs (exact_wrong_ppm empty)."]
    kernel_what, embree_what = set(), set()
    embree_paths = set()  # what Embree's drawn series traced: False the batch, True whole paths
    rows = len(facets)
    caption_guess = 7
    height = 3.3 * rows + 1.0 + 0.17 * caption_guess
    width = 14.5 if accuracy else 9.5
    fig = plt.figure(figsize=(width, height))
    grid = plt.GridSpec(rows, 3 if accuracy else 2, figure=fig, width_ratios=[1, 1, 0.55] if accuracy else [1, 0.55])
    any_simplified = any_noisy = False
    for row, (scene, group) in enumerate(facets):
        left, right = fig.add_subplot(grid[row, 0]), fig.add_subplot(grid[row, 1]) if accuracy else None
        series = [(m, c) for m in methods for c in combos if ((group._method == m) & (group._combo == c)).any()]
        # Embree's own series: by the keys its runs depend on, and by what it traced (the batch, or
        # beside a whole-path strategy every generation of the path: a longer time, not comparable).
        ekey = pd.Series([tuple(c[i] for i in embree_keys) + (bool(w),) for c, w in zip(group._combo, group._embree_path)],
                         index=group.index)
        ecombos = sorted(set(ekey))
        n = len(series) + len(ecombos)
        times, ppms = [], []
        for i, (m, c) in enumerate(series):
            g = group[(group._method == m) & (group._combo == c)].sort_values("_x")
            marker, ls = styles[c]
            tr_left, tr_right = dodge(left, i, n), dodge(right, i, n) if right else None
            low, high, what = interval(g, "kernel")
            kernel_what.update(what)
            y, low, high = (v * g._kscale for v in (g.kernel_ms_median.astype(float), low, high))
            yerr = np.vstack([(y - low).clip(lower=0).fillna(0), (high - y).clip(lower=0).fillna(0)])
            alpha = 0.45 if pooled else 0.9
            left.errorbar(g._x, y, yerr=yerr, fmt=marker, ms=5 if not pooled else 3, color=colors[m], ecolor=colors[m],
                          elinewidth=0.8, capsize=2, alpha=alpha, transform=tr_left)
            noisy = timing_warned(g)
            if noisy.any():  # the noise guard flagged them: hollow, not timings of record
                any_noisy = True
                left.plot(g._x[noisy], y[noisy], ls="none", marker=marker, ms=5 if not pooled else 3, mfc="white",
                          mec=colors[m], zorder=3, transform=tr_left)
            median = y.groupby(g._x).median()  # time: a line through the medians; rays wrong: points only
            for xs, ys in series_segments(median.index, median.values, key) if numeric else []:  # (one wrong ray is
                # no trend; categories in a row are no trend either: points only)
                left.plot(xs, ys, ls=ls, color=colors[m], lw=1.3 if not pooled else 0.8, alpha=alpha, transform=tr_left)
            full, simple = g[~g._simplified], g[g._simplified]
            times += list(y) + list(low) + list(high)
            anchor(left, list(g._x) * 3, list(y) + list(low) + list(high))
            if right is None:
                continue
            any_simplified |= not simple.empty
            right.scatter(full._x, full._ppm, marker=marker, s=25 if not pooled else 9, color=colors[m], alpha=alpha,
                          transform=tr_right)
            if not simple.empty:  # half filled: the simplified scene's (wrong = hit/miss only)
                right.plot(simple._x, simple._ppm, ls="none", marker=marker, ms=5, fillstyle="left", color=colors[m],
                           transform=tr_right)
            ppms += list(g._ppm)
            anchor(right, g._x, g._ppm)
        for j, ec in enumerate(ecombos):
            g = group[ekey == ec]
            g = g.drop_duplicates(["_x", "_combo", *LOOK_AT] if "camera_look_at_x" in g else ["_x", "_combo"])
            if (numeric and g._x.nunique() < 2) or "embree1_ms_median" not in g:
                continue
            low, high, what = interval(g, "embree1")
            embree_what.update(what)
            at = g.assign(_low=low * g._escale, _high=high * g._escale, _y=g.embree1_ms_median * g._escale).groupby("_x")
            y, lo, hi = at._y.median(), at._low.min(), at._high.max()
            ls = LINESTYLES[j % len(LINESTYLES)] if not pooled else "-"
            tr_left, tr_right = dodge(left, len(series) + j, n), dodge(right, len(series) + j, n) if right else None
            emarker = "D" if ec[-1] else "s"
            embree_paths.add(ec[-1])
            left.errorbar(y.index, y, yerr=np.vstack([(y - lo).clip(lower=0).fillna(0), (hi - y).clip(lower=0).fillna(0)]),
                          fmt=emarker, ms=4, color="k", elinewidth=0.8, capsize=2, transform=tr_left)
            ppm = at._embree_ppm.median()
            for xs, ys in series_segments(y.index, y.values, key) if numeric else []:
                left.plot(xs, ys, ls=ls, color="k", lw=1.0 if not pooled else 0.7, alpha=1.0 if not pooled else 0.5,
                          transform=tr_left)
            times += list(y) + list(lo) + list(hi)
            anchor(left, list(y.index) * 3, list(y) + list(lo) + list(hi))
            if right is not None:
                right.scatter(ppm.index, ppm, marker=emarker, s=16, color="k", transform=tr_right)
                ppms += list(ppm)
                anchor(right, ppm.index, ppm)
        # Axes. strategy.type = cpu times the host's threads, not the device.
        timed = "GPU (cpu: host)" if "strategy_type" in group and (group.strategy_type == "cpu").any() else "GPU"
        unit = "ns per ray traced" if per_ray else "ms per frame"
        positive = finite(times)
        positive = positive[positive > 0]
        if not positive.empty and positive.max() / positive.min() >= 10:
            left.set_yscale("log")
            left.yaxis.set_minor_formatter(ticker.LogFormatterSciNotation(labelOnlyBase=False, minor_thresholds=(2, 0.5)))
            left.tick_params(axis="y", which="minor", labelsize=7)
            left.set_ylabel(f"{timed} {unit}\n(median; log)")
        else:
            left.set_ylim(bottom=0)
            left.set_ylabel(f"{timed} {unit}\n(median)")
        sizes = size(group)
        left.set_title(f"{scene} ({sizes}): {timed} time", fontsize=9)
        if right is not None:
            wrong_ppm_axis(right, ppms, "rays wrong per million vs\nthe exact reference (log above 1)")
            right.set_title(f"{scene} ({sizes}): rays wrong against the exact reference", fontsize=9)
        for ax in (left, right) if right else (left,):
            x_axis(ax, key, members, order, numeric, data, text, faceted)
    # The legend, beside the rows.
    legend_ax = fig.add_subplot(grid[:, 2 if accuracy else 1])
    handles = [(Line2D([], [], ls="none"), "colour: method" + (" (structure x strategy)" if len(method_parts) == 2 else ""))]
    handles += [(Line2D([], [], color=colors[m], lw=2), textwrap.fill(m, 44)) for m in methods]
    if not pooled and len(names) > 1:
        handles.append((Line2D([], [], ls="none"), "marker, line: other swept keys"))
        handles += [(Line2D([], [], color="0.3", marker=by_label[n][0], ls=by_label[n][1] if numeric else "none"), textwrap.fill(n, 44))
                    for n in names]
    if False in embree_paths or not embree_paths:
        handles.append((Line2D([], [], color="k", marker="s", ls="-" if numeric else "none"),
                        "Embree rtcIntersect1 (CPU, the same rays)"))
    if True in embree_paths:
        handles.append((Line2D([], [], color="k", marker="D", ls="-" if numeric else "none"),
                        textwrap.fill("Embree beside a whole-path strategy: every generation of the path "
                                      "(embree_rays; CPU)", 44)))
    if any_simplified:
        handles.append((Line2D([], [], color="0.3", marker="o", fillstyle="left", ls="none"),
                        "half filled: simplified scene (wrong = missed or false hit only)"))
    if any_noisy:
        handles.append((Line2D([], [], color="0.3", marker="o", mfc="white", ls="none"),
                        textwrap.fill("hollow time: a timing warning (the noise guard: not a timing of record)", 44)))
    legend_beside(fig, legend_ax, handles, fontsize=7)
    # The caption: what the bars are and what is not drawn.
    paths_note = ""
    if True in embree_paths:
        paths_note = " Diamonds: the runs of whole-path strategies, where Embree traced every generation of the path"
        paths_note += ", apart from the runs where it traced the batch alone (squares)." if False in embree_paths else "."
    embree_note = (" Embree: the median of the runs at a value (each times Embree on its rays), bars from the lowest to "
                   "the highest end of their " + "; ".join(sorted(embree_what)) + "." if embree_what else
                   " Embree: no interval columns." if embree_paths else "")
    caption_lines.append("Error bars, kernel: " + ("; ".join(sorted(kernel_what)) or "none (no interval columns)") + "."
                         + embree_note + paths_note)
    caption_lines.append("Points of one value are set side by side (a few points apart). " + (
        "Time: lines join a series' medians; rays wrong: points only (a ray or two wrong at one value is no trend "
        "between values)." if numeric else f"Values of {key} are categories: points, not joined by lines."))
    if per_ray:
        caption_lines.append("Time per ray traced: the batch differs between these runs (rays "
                             + ", ".join(f"{int(r):,}" for r in sorted(pd.to_numeric(frame.rays, errors='coerce').dropna().unique())[:6])
                             + "), so a frame's time would follow the batch: kernel ms / rays, Embree ms / embree_rays.")
    if pooled:
        caption_lines.append(f"{len(combos)} settings of {', '.join(vary)}: too many to tell apart, a faint line each "
                             f"(each joins runs alike in all of them).")
    if merged:
        caption_lines.append(f"{', '.join(merged)}: no value at some values of {key} (not set or not applicable there), "
                             f"so not held fixed along it: the runs of one series at a value may differ in it.")
    if len(dropped):
        caption_lines.append(f"Not drawn: {runs_count(len(dropped))} whose method and other settings ran at one value of {key} only.")
    if one_value:
        caption_lines.append(f"Not drawn: {', '.join(one_value)} (run at one value of {key}).")
    without = len(runs) - len(have)
    if without:
        column = "structure_type" if key.startswith("structure_") else "strategy_type" if key.startswith("strategy_") else None
        kinds = sorted(runs.loc[text[key] == "", column].map(lambda t: STRUCTURE_NAMES.get(t, t)).unique()) if column else []
        caption_lines.append(f"Not drawn: {runs_count(without)} without a value of {key}"
                             + (f" (it does not apply to {', '.join(map(str, kinds))})." if kinds else "."))
    if failed is not None and key in failed and len(failed):
        at = failed[key].map(text_value)
        at = at[at != ""]
        if len(at):
            caption_lines.append(f"Failed, not drawn: {runs_count(len(at))} at {key} = {', '.join(category_order(at.unique()))} "
                                 f"(runs.csv says why).")
    if FLOAT_BITS.get(key) is not None:
        caption_lines.append(f"{key} {FLOAT_BITS[key]}: float vertices, not joined to the packed ones.")
    caption = "\n".join(textwrap.fill(line, int(200 * width / 14.5)) for line in caption_lines)
    lines = caption.count("\n") + 1
    fig.set_size_inches(width, 3.3 * rows + 1.0 + 0.17 * lines)
    bottom = (0.17 * lines + 0.15) / fig.get_size_inches()[1]
    fig.text(0.01, 0.01, caption, fontsize=7.5, va="bottom", ha="left", color="0.2")
    follow = f" (with {', '.join(followers)})" if followers else ""
    fig.suptitle(f"Against {key}{follow}: time and rays wrong, a colour per method"
                 f"{', a row per scene' if faceted else ''}\n{device}", fontsize=10)
    save(fig, folder, name, written, rect=(0, bottom, 1, 1))


def x_axis(ax, key, members, order, numeric, data, text, faceted):
    """The key's values on the x axis; with the keys that follow it under each value."""
    def label(value):
        if not faceted:
            return str(value)
        rows = text.loc[data.index][text.loc[data.index, key] == text_value(value) if numeric else
                                    text.loc[data.index, key] == value]
        parts = [text_value(value) if numeric else compact(value)]
        parts += [rows[f].iloc[0] for f in members[1:] if not rows.empty]
        if FLOAT_BITS.get(key) is not None and numeric and value >= FLOAT_BITS[key]:
            parts[0] = "float"
        return "\n".join(p for p in parts if p != "")
    labels = [label(v) for v in order]
    if numeric:
        values = np.array(order, dtype=float)
        if values.min() > 0 and values.max() / values.min() >= 10:
            powers_of_two = all(float(v).is_integer() and int(v) & (int(v) - 1) == 0 for v in values)
            ax.set_xscale("log", base=2 if powers_of_two else 10)
        if len(order) <= 12:
            ax.set_xticks(values, labels, fontsize=7)
            ax.xaxis.set_minor_locator(ticker.NullLocator())
        lo, hi = values.min(), values.max()  # room beyond the end values for the points set side by side
        if ax.get_xscale() == "log":
            pad = max(1.3, (hi / lo) ** 0.09)  # points set side by side reach a few points beyond
            ax.set_xlim(lo / pad, hi * pad)
        else:
            ax.set_xlim(lo - 0.09 * (hi - lo), hi + 0.09 * (hi - lo))
    else:
        ax.set_xticks(range(len(order)), labels, fontsize=7)
        ax.set_xlim(-0.5, len(order) - 0.5)
        if len(order) * max(len(line) for lab in labels for line in lab.split("\n")) > 60:
            ax.tick_params(axis="x", labelrotation=25)
            for tick in ax.get_xticklabels():
                tick.set_ha("right")
    ax.set_xlabel(" / ".join(members) if faceted else "scene" + (" / " + " / ".join(members[1:]) if members[1:] else ""))


def why(error: OSError) -> str:
    return error.strerror or str(error)


def check_folder(folder: Path):
    """The folder must exist, be a folder with runs.csv and context.json, and take new files."""
    if not os.path.lexists(folder):
        raise PlotError(f"{folder}: no such folder")
    if not folder.is_dir():
        raise PlotError(f"{folder}: not a folder (expected an rtbench results folder holding runs.csv)")
    for name in ("runs.csv", "context.json"):
        if not (folder / name).is_file():
            raise PlotError(f"{folder}: no {name} (not an rtbench results folder, or no run has finished)")
    # Writable? Try it: os.access says yes to root on a read-only mount or a 0555 folder alike.
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".plot-probe.", suffix=".tmp")
        os.close(fd)
        os.unlink(probe)
    except OSError as e:
        if e.errno in (errno.EACCES, errno.EPERM, errno.EROFS):
            raise PlotError(f"{folder}: charts cannot be written there ({why(e)}: the folder is read-only)") from e
        raise PlotError(f"{folder}: charts cannot be written there ({why(e)})") from e


def missing_column(error):
    """The column a chart looked for that runs.csv lacks (a folder of an older rtbench, or a CSV cut
    down by hand), from the KeyError or AttributeError pandas raised; None for another error."""
    if isinstance(error, KeyError) and error.args and isinstance(error.args[0], str):
        return error.args[0]
    found = re.search(r"'(?:DataFrame|Series|Pandas)' object has no attribute '(\w+)'", str(error))
    return found.group(1) if found else None


def draw(name, folder, chart, *args):
    """One chart; one that needs a column the folder lacks is skipped, saying which; one that fails
    is left out with its reason (the others are still drawn). A chart that cannot be written where
    it belongs (PlotError, OSError: a link, a full disk) stops them all."""
    try:
        chart(*args)
    except (PlotError, OSError):
        raise
    except Exception as e:  # noqa: BLE001: any failure of one chart is that chart's, said and survived
        plt.close("all")
        column = missing_column(e) if isinstance(e, (KeyError, AttributeError)) else None
        if column is not None:
            return skip(folder, name, f"runs.csv has no {column} column")
        FAILED.append(name)
        reason = " ".join(str(e).split()) or "no message"
        print(f"rtbench plot: {folder}: could not draw {name}: {type(e).__name__}: {reason}", file=sys.stderr)


def run(folder: Path) -> int:
    SKIPPED.clear()
    FAILED.clear()
    check_folder(folder)
    try:
        runs, failed, _, device = load(folder)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
        raise PlotError(f"{folder / 'runs.csv'}: cannot be read as a CSV ({str(e).strip()})") from e
    except json.JSONDecodeError as e:
        raise PlotError(f"{folder / 'context.json'}: not valid JSON (line {e.lineno}: {e.msg})") from e
    except (AttributeError, KeyError) as e:
        raise PlotError(f"{folder}: runs.csv or context.json lacks what rtbench writes ({e})") from e
    except UnsafePath as e:  # a FIFO or device where a file belongs: refused, not waited on
        raise PlotError(str(e)) from e
    if runs.empty:
        raise PlotError(f"{folder}: no successful runs to chart")
    written = []
    everything = runs  # every successful run, packed and simplified scenes too
    for chart in (speed_vs_accuracy, vertex_precision, simplification):
        draw(chart.__name__, folder, chart, runs, device, folder, written)
    runs = runs[variant(runs) == ""]  # the other charts compare methods on the scene as it is
    for chart in (passes_vs_threshold, bandwidth_by_category, texture_cache, christen_grid_size, christen_gpu_cpu, unrolling, grid_resolution, kernel_time,
                  compute_by_kernel,
                  structures_time, structures_memory, structures_work, build_times):
        draw(chart.__name__, folder, chart, runs, device, folder, written)
    draw("failure_map", folder, failure_map, runs, failed, device, folder, written)
    by_key_charts(everything, failed, device, folder, written)
    if written:
        print(f"{folder}: wrote {len(written)} chart(s): {', '.join(written)} (.png, .svg)")
    if SKIPPED and not VERBOSE:
        print(f"{folder}: {len(SKIPPED)} chart(s) not called for by these runs (-v names them)")
    if FAILED:
        print(f"{folder}: {len(FAILED)} chart(s) could not be drawn: {', '.join(FAILED)} (reasons above)", file=sys.stderr)
    if not written:
        raise PlotError(f"{folder}: no chart could be drawn from these runs" + ("" if VERBOSE else " (-v says why of each)"))
    return 0


def main() -> int:
    return main_with(sys.argv[1:])


def main_with(args) -> int:
    global VERBOSE
    VERBOSE = bool(args) and args[0] in ("-v", "--verbose")
    args = args[VERBOSE:]
    if len(args) != 1 or args[0].startswith("-"):
        print(__doc__)
        return 2
    folder = Path(args[0])
    try:
        return run(folder)
    except PlotError as e:
        print(f"rtbench plot: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # a chart that could not be written (full disk, folder removed meanwhile)
        print(f"rtbench plot: {e.filename or folder}: {why(e)}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
