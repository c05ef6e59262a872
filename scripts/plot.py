#!/usr/bin/python3
"""Charts for an rtbench results folder: PNG and SVG next to runs.csv.

usage: scripts/plot.py RESULTS_DIR      (or: build/rtbench plot RESULTS_DIR)
Charts whose runs are absent from the folder are skipped. Uses Debian's python3-matplotlib and
python3-pandas only.
"""
import errno
import json
import os
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402
from rtbench_results import load, method_name, scene_name  # noqa: E402
COLORS = {"branching": "tab:blue", "multipass": "tab:orange", "Embree rtcIntersect1": "tab:green"}
BYTES = [("bytes_stencil", "stencil"), ("bytes_state", "state variables"), ("bytes_stack", "node stack"),
         ("bytes_voxel", "voxel data"), ("bytes_node", "BVH nodes"), ("bytes_triangle_list", "triangle lists"),
         ("bytes_vertices", "triangle vertices"), ("bytes_output", "output")]
KERNELS = [("kernel_ms_setup", "setup"), ("kernel_ms_traverse", "traverse"), ("kernel_ms_intersect", "intersect"),
           ("kernel_ms_write", "write")]


class PlotError(Exception):
    """What stops the charts, said in one line: "<path>: <why>"."""


def umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def write_atomically(fig, target: Path, ext: str):
    """fig as `ext` into `target`: a new temporary file in the same folder (O_EXCL, O_NOFOLLOW:
    mkstemp), then os.replace over the target, which replaces a name and never writes through a
    link. A target that exists as a symbolic link is refused; a failed write leaves the old chart."""
    if target.is_symlink():
        raise PlotError(f"{target}: is a symbolic link; refusing to write a chart through it")
    if target.exists() and not target.is_file():
        raise PlotError(f"{target}: exists and is not a regular file; cannot write a chart there")
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        os.fchmod(fd, 0o666 & ~umask())  # as a plain open() would create it, not mkstemp's 0600
        with os.fdopen(fd, "wb") as out:
            fig.savefig(out, format=ext, dpi=110)
            out.flush()
            os.fsync(out.fileno())
        os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise


def save(fig, folder: Path, name: str, written: list):
    fig.tight_layout()
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
    ax.legend(fontsize=8)


def size(frame) -> str:
    return f"{int(frame.camera_width.iloc[0])}x{int(frame.camera_height.iloc[0])}"


def pareto(points):
    """Points (speed, error) no other point beats in both (faster and at most as wrong), by speed."""
    front, best = [], float("inf")
    for x, y in sorted(points, key=lambda p: (-p[0], p[1])):
        if y < best:
            front.append((x, y))
            best = y
    return sorted(front)


def wrong_ppm(frame, prefix="exact_"):
    """Rays wrong against the exact reference per million: false misses + false hits + wrong triangle
    (a simplified scene has other triangles: no wrong triangle counted)."""
    wrong = frame[prefix + "false_misses"] + frame[prefix + "false_hits"] + frame[prefix + "wrong_primitive"].fillna(0)
    return 1e6 * wrong / frame.exact_rays


def wrong_ppm_axis(ax, label=None):
    """A y axis of rays wrong per million: 0 sits on the axis, 1 ppm and up are logarithmic."""
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set_ylim(bottom=-0.1)
    if label:
        ax.set_ylabel(label)


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


# Markers per scene variant, (Moller-Trumbore, watertight).
VARIANT_MARKERS = {"": ("o", "^"), "packed": ("D", "d"), "simplified": ("v", "<")}
KIND_COLORS = {"grid": "tab:blue", "grid conservative": "tab:cyan", "bvh": "tab:red", "brute": "tab:gray",
               "auto": "tab:purple"}


def speed_vs_accuracy(runs, device, folder, written):
    """Per scene: rays wrong against the exact reference (log above 1 per million) and mean distance
    error against speed, one point per run, Embree beside them, the kernels' Pareto front."""
    if "exact_rays" not in runs:  # a folder from before the exact reference
        return
    scenes = sorted(runs.scene.unique())
    fig, axes = plt.subplots(len(scenes), 2, figsize=(15, 4.4 * len(scenes)), squeeze=False)
    for (left, right), scene in zip(axes, scenes):
        of_scene = runs[runs.scene == scene]
        points = []
        of_scene = of_scene.assign(kind=[method_name(r).split(" ")[0] + (" conservative" if "conservative" in method_name(r)
                                                                          else "") for _, r in of_scene.iterrows()],
                                   test=of_scene.get("intersection_test", "moller_trumbore"), variant=variant(of_scene))
        for (kind, strategy, test, how), group in of_scene.groupby(["kind", "strategy_type", "test", "variant"]):
            marker = VARIANT_MARKERS[how][test == "watertight"]
            name = f"{kind} {strategy}, {'watertight' if test == 'watertight' else 'Moller-Trumbore'}" + (f", {how}" if how else "")
            color = KIND_COLORS.get(kind, COLORS.get(strategy))
            fill = color if strategy == "branching" else "none"  # multipass: hollow
            ppm = wrong_ppm(group)
            left.scatter(group.kernel_mrays_s, ppm, label=name, edgecolors=color, c=fill, marker=marker, alpha=0.8)
            right.scatter(group.kernel_mrays_s, group.exact_distance_error_mean, label=name, edgecolors=color, c=fill,
                          marker=marker, alpha=0.8)
            if how:  # which precision or simplification each point is
                tags = [f"{int(b)} b" for b in vertex_bits(group)] if how == "packed" else \
                    [f"{100 * t / f:.3g}%" for t, f in zip(group.scene_triangles, group.scene_full_triangles)]
                for x, y, tag in zip(group.kernel_mrays_s, ppm, tags):
                    left.annotate(tag, (x, y), fontsize=6, xytext=(3, 2), textcoords="offset points", color=color)
            points += list(zip(group.kernel_mrays_s, ppm))
        embree = of_scene[of_scene.variant == ""].drop_duplicates(["camera_width", "camera_height", "camera_look_at"])
        left.scatter(embree.embree1_mrays_s, wrong_ppm(embree, "embree_exact_"), marker="s",
                     color=COLORS["Embree rtcIntersect1"], label="Embree rtcIntersect1 (CPU, same rays)")
        right.scatter(embree.embree1_mrays_s, embree.embree_exact_distance_error_mean, marker="s",
                      color=COLORS["Embree rtcIntersect1"], label="Embree rtcIntersect1 (CPU, same rays)")
        front = pareto(points)  # among the kernels' runs
        left.plot([p[0] for p in front], [p[1] for p in front], "k--", marker="x", lw=1, label="Pareto front of the kernels")
        wrong_ppm_axis(left, "rays wrong vs exact (per million; log above 1)")
        right.set_yscale("log")
        right.set_ylabel("mean |t - t_exact| / t_exact (log)")
        for ax in (left, right):
            ax.set_xscale("log")
            ax.set_xlabel("speed (Mrays/s, log scale)")
            ax.set_title(f"{scene}, {size(of_scene)}", fontsize=9)
        right.legend(*left.get_legend_handles_labels(), fontsize=7, loc="upper left",
                     bbox_to_anchor=(1.02, 1.0))  # one legend (the left panel's, with the front), beside the points
    fig.suptitle(f"Speed against accuracy (the exact reference), one point per run\n{device}", fontsize=10)
    save(fig, folder, "speed_vs_accuracy", written)


def reduced_lines(runs, how):
    """Per scene and method (structure, strategy, test): the runs of variant `how` with the same
    method's run on the scene as it is, for lines from the full scene down."""
    runs = runs.assign(variant=variant(runs), method=[method_label(r) for _, r in runs.iterrows()])
    for scene in sorted(runs.scene.unique()):
        of_scene = runs[runs.scene == scene]
        reduced = of_scene[of_scene.variant == how]
        for method in sorted(reduced.method.unique()):
            yield scene, method, of_scene[(of_scene.method == method) & of_scene.variant.isin(["", how])]


def vertex_precision(runs, device, folder, written):
    """Packed vertices: rays wrong against the exact reference and vertex bytes per ray against the
    bits per axis, 32 being float vertices."""
    lines = list(reduced_lines(runs, "packed"))
    if not lines:
        return
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.4))
    for scene, method, group in lines:
        group = group.assign(bits=vertex_bits(group)).sort_values("bits")
        left.plot(group.bits, wrong_ppm(group), marker="o", label=f"{scene}: {method}")
        right.plot(group.bits, group.bytes_vertices / group.rays, marker="o", label=f"{scene}: {method}")
    wrong_ppm_axis(left, "rays wrong vs exact (per million; log above 1)")
    right.set_ylabel("triangle vertex bytes read per ray")
    for ax in (left, right):
        ax.set_xlabel("vertex bits per axis (32: float)")
        ax.set_xscale("log", base=2)
        bits = sorted(vertex_bits(runs).unique())
        ax.set_xticks(bits, [str(int(b)) if b < 32 else "float" for b in bits])
        ax.minorticks_off()
        ax.legend(fontsize=7)
    fig.suptitle(f"Reduced vertex precision: accuracy against bandwidth ({size(runs)})\n{device}", fontsize=10)
    save(fig, folder, "vertex_precision", written)


def simplification(runs, device, folder, written):
    """Simplified scenes judged against the full one: rays wrong and speed against the triangles kept."""
    lines = list(reduced_lines(runs, "simplified"))
    if not lines:
        return
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.4))
    for scene, method, group in lines:
        group = group.sort_values("scene_triangles")
        left.plot(group.scene_triangles, wrong_ppm(group), marker="o", label=f"{scene}: {method}")
        line, = right.plot(group.scene_triangles, group.kernel_mrays_s, marker="o", label=f"{scene}: {method}")
        right.plot(group.scene_triangles, group.embree1_mrays_s, ls=":", marker=".", color=line.get_color(),
                   label=f"{scene}: Embree rtcIntersect1 on the same scene")
    left.axhline(1000, color="gray", lw=1, ls="--", label="0.1% of the rays")
    wrong_ppm_axis(left, "rays wrong vs exact, full scene (per million)")
    right.set_yscale("log")
    right.set_ylabel("Mrays/s (log)")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_xlabel("triangles traced (log; the rightmost point is the full scene)")
        ax.legend(fontsize=7)
    fig.suptitle(f"Simplified scenes (CGAL edge collapse): accuracy and speed ({size(runs)})\n{device}", fontsize=10)
    save(fig, folder, "simplification", written)


def first_number(text) -> float:
    """The first number of a 3-vector as the CSV writes it: "[100 100 100]" -> 100."""
    return float(str(text).strip("[]").split()[0])


def failure_map(runs, failed, device, folder, written):
    """Rays wrong against the exact reference as a scene moves (scene.translate) or scales (scene.scale):
    one panel per swept axis and scene, one line per method, Embree dashed, refused runs marked."""
    if "exact_rays" not in runs or "scene_translate" not in runs:
        return
    everything = pd.concat([runs, failed.assign(scene=failed.scene_source.map(scene_name))], ignore_index=True)
    everything["ok"] = everything.status == "ok"
    everything["offset"] = everything.scene_translate.map(first_number)
    panels = []
    for scene, group in everything.groupby("scene"):
        if group.offset.nunique() > 1:
            panels.append((f"{scene} moved by (d, d, d)", "offset d", group[group.scene_scale == 1.0], "offset"))
        if group.scene_scale.nunique() > 1:
            panels.append((f"{scene} scaled", "scale", group[group.offset == 0.0], "scene_scale"))
    if not panels:
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.6), squeeze=False)
    for ax, (title, xlabel, group, x) in zip(axes[0], panels):
        ok = group[group.ok].copy()
        ok["method"] = [method_label(r) for _, r in ok.iterrows()]
        # Sum over the views of a point (e.g. the closed meshes' three look-at directions).
        for method, runs_of in ok.groupby("method"):
            ppm = wrong_ppm_summed(runs_of, x)
            style = ":^" if method.endswith("watertight") else "-o"  # the tests often coincide: dotted on solid
            ax.plot(ppm.index, ppm, style, label=method, color=method_color(method),
                    alpha=0.45 if "multipass" in method else 0.9, ms=4)
        embree = ok.drop_duplicates([x, "camera_look_at", "scene_source"] if "camera_look_at" in ok else [x, "scene_source"])
        ppm = wrong_ppm_summed(embree, x, "embree_exact_")
        ax.plot(ppm.index, ppm, "k--s", label="Embree (CPU)", ms=4)
        refused = sorted(set(group[~group.ok][x]))
        for v in refused:
            ax.axvline(v, color="tab:red", lw=6, alpha=0.15)
        if refused:
            ax.plot([], [], color="tab:red", lw=6, alpha=0.3, label="refused: outside the methods' range")
        ax.set_xscale("symlog" if x == "offset" else "log", **({"linthresh": 1.0} if x == "offset" else {}))
        xs = sorted(set(group[x]))  # refused runs too (axvline does not widen the axis)
        ax.set_xlim(-0.5 if x == "offset" else xs[0] / 3, xs[-1] * 3)
        wrong_ppm_axis(ax, "rays wrong vs exact (per million; log above 1)")
        ax.set_xlabel(xlabel + " (log)")
        ax.set_title(title, fontsize=9)
        ax.legend(fontsize=6)
    fig.suptitle(f"Failure map: leaks, false hits and wrong triangles against the exact reference\n{device}", fontsize=10)
    save(fig, folder, "failure_map", written)


def passes_vs_threshold(runs, device, folder, written):
    oracle = runs[(runs.strategy_type == "multipass") & (runs.strategy_scheduling == "oracle")]
    if oracle.sweep.isin(["oracle"]).any():  # the threshold sweep and the runs at the base threshold
        oracle = oracle[oracle.sweep.isin(["oracle", "architecture"])]
    if oracle.strategy_oracle_threshold.nunique() < 3:
        return
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
        ax.legend(fontsize=7)
    fig.suptitle(f"Passes against oracle threshold, K = {int(k)}, M = {int(m)}; {device}")
    save(fig, folder, "passes_vs_threshold", written)


def bandwidth_by_category(runs, device, folder, written):
    if runs.structure_type.nunique() > 1:
        return  # structures_* charts compare structures
    chosen = runs[runs.sweep == "architecture"] if (runs.sweep == "architecture").any() else runs
    chosen = chosen.drop_duplicates(["scene", "strategy_type"]).sort_values(["scene", "strategy_type"])
    fig, ax = plt.subplots(figsize=(max(7, 1.4 * len(chosen)), 4.8))
    present = [(c, n) for c, n in BYTES if c in chosen and chosen[c].fillna(0).any()]
    stacked_bars(ax, [f"{r.scene}\n{r.strategy_type}" for r in chosen.itertuples()], chosen, present, 1e-6)
    ax.set_ylabel("bytes read and written per frame (MB)")
    ax.set_title(f"Bandwidth by data type (Purcell Fig. 8 style), {size(chosen)}\n{device}")
    save(fig, folder, "bandwidth_by_category", written)


def unrolling(runs, device, folder, written):
    unroll = runs[runs.sweep.str.startswith("unroll")]
    if unroll.empty:
        return
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
        ax.legend(fontsize=7)
    fig.suptitle(f"Loop unrolling: K steps by M intersections per pass — {unroll.scene.iloc[0]}, {size(unroll)}; {device}")
    save(fig, folder, "unrolling", written)


def grid_resolution(runs, device, folder, written):
    if runs.structure_type.nunique() > 1:
        return  # structures_* charts compare structures
    grid = runs[runs.sweep == "grid"] if (runs.sweep == "grid").any() else runs
    grid = grid[grid.structure_min_dim.notna()]
    if grid.structure_min_dim.nunique() < 3:
        return
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
        right.plot(group.structure_min_dim, group.kernel_mrays_s, "o-", label=method, color=COLORS.get(method))
    right.set_xscale("log", base=2)
    right.set_yscale("log")
    right.set_xlabel("min_dim (log2)")
    right.set_ylabel("speed (Mrays/s, log scale)")
    right.legend(fontsize=8)
    fig.suptitle(f"Traversal against intersection by grid resolution — {data.scene.iloc[0]}, {size(data)}; {device}")
    save(fig, folder, "grid_resolution", written)


def kernel_time(runs, device, folder, written):
    if runs.structure_type.nunique() > 1:
        return  # structures_* charts compare structures
    multipass = runs[runs.strategy_type == "multipass"]
    chosen = multipass[multipass.sweep == "architecture"] if (multipass.sweep == "architecture").any() else multipass
    if chosen.empty:
        return
    chosen = chosen.head(12)
    fig, ax = plt.subplots(figsize=(max(7, 1.6 * len(chosen)), 4.5))
    unique = chosen.scene.nunique() == len(chosen)
    labels = [r.scene if unique else f"{r.scene}\nrun {int(r.run):03d}" for r in chosen.itertuples()]
    stacked_bars(ax, labels, chosen, KERNELS)
    ax.set_ylabel("GPU time per frame (ms, median)")
    ax.set_title(f"Multipass GPU time by kernel, {size(chosen)}\n{device}")
    save(fig, folder, "kernel_time", written)


STRUCTURE_COLORS = {"grid": "tab:blue", "bvh": "tab:red", "brute force": "tab:gray", "auto": "tab:purple"}


def method_color(method: str) -> str:
    return STRUCTURE_COLORS.get(method.split(" ")[0] if not method.startswith("brute") else "brute force", "k")


def with_methods(runs):
    runs = runs.copy()
    runs["method"] = [method_name(r) for _, r in runs.iterrows()]
    runs["method_kind"] = [m.split(" (")[0] for m in runs.method]  # "auto (bvh)" -> "auto"
    return runs


def grouped_bars(ax, frame, value, scenes, methods, log=True):
    """Bars of `value` per scene (groups) and method (bars), with the method's colour."""
    width = 0.8 / max(len(methods), 1)
    for i, method in enumerate(methods):
        xs, ys = [], []
        for j, scene in enumerate(scenes):
            row = frame[(frame.scene == scene) & (frame.method_kind == method)]
            if not row.empty:
                xs.append(j + (i - (len(methods) - 1) / 2) * width)
                ys.append(row[value].iloc[0])
        shade = 0.35 + 0.65 * (i + 1) / len(methods) if method.startswith("grid") else 1.0
        ax.bar(xs, ys, width, label=method, color=method_color(method), alpha=shade)
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels(scenes, fontsize=8)
    if log:
        ax.set_yscale("log")


def structures_comparable(runs) -> bool:
    """The structures_* charts draw one bar per scene, structure and strategy: they need several
    structures and exactly one run for each bar (not, say, a sweep of the triangle test as well)."""
    if runs.structure_type.nunique() < 2:
        return False
    return not with_methods(runs).duplicated(["scene", "method_kind", "strategy_type"]).any()


def structure_order(runs):
    kinds = runs.method_kind.unique().tolist()
    order = ["grid 32", "grid 64", "grid 128", "bvh", "brute force", "auto"]
    return [k for k in order if k in kinds] + sorted(k for k in kinds if k not in order)


def structures_time(runs, device, folder, written):
    if not structures_comparable(runs):
        return
    runs = with_methods(runs)
    scenes = runs.sort_values("scene_triangles").scene.unique().tolist()
    methods = structure_order(runs)
    strategies = [s for s in ("branching", "multipass") if (runs.strategy_type == s).any()]
    fig, axes = plt.subplots(len(strategies), 2, figsize=(15, 4.2 * len(strategies)), squeeze=False)
    for row, strategy in zip(axes, strategies):
        part = runs[runs.strategy_type == strategy]
        grouped_bars(row[0], part, "kernel_ms_median", scenes, methods)
        embree = part.groupby("scene").embree1_ms_median.median()
        row[0].scatter([scenes.index(s) for s in embree.index], embree.values, marker="_", s=400, color="k",
                       label="Embree rtcIntersect1", zorder=3)
        row[0].set_ylabel("GPU time per frame (ms, median, log)")
        row[0].set_title(f"{strategy}: time per scene")
        grouped_bars(row[1], part, "speed_ratio_vs_embree1", scenes, methods)
        row[1].axhline(1.0, color="k", lw=1, ls="--")
        row[1].set_ylabel("Mrays/s / Embree rtcIntersect1's (log)")
        row[1].set_title(f"{strategy}: speed against Embree on the same rays")
    axes[0][0].legend(fontsize=7, ncol=2)
    fig.suptitle(f"Structures side by side, {size(runs)} primary rays; {device}")
    save(fig, folder, "structures_time", written)


def structures_memory(runs, device, folder, written):
    if not structures_comparable(runs):
        return
    runs = with_methods(runs)
    runs = runs[runs.strategy_type == runs.strategy_type.iloc[0]]  # the structure is the same for both strategies
    scenes = runs.sort_values("scene_triangles").scene.unique().tolist()
    methods = [m for m in structure_order(runs) if m != "auto"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(15, 4.2))
    grouped_bars(left, runs, "structure_bytes_per_triangle", scenes, methods)
    left.set_ylabel("device bytes per triangle (log)")
    left.set_title("Memory: the structure's buffers, vertices included")
    grouped_bars(right, runs, "structure_build_ms", scenes, methods)
    right.set_ylabel("CPU build time (ms, log)")
    right.set_title("Build time (grid: CGAL exact triangle-box tests; BVH: Embree rtcBuildBVH)")
    left.legend(fontsize=7)
    fig.suptitle(f"Memory and build time per structure; {device}")
    save(fig, folder, "structures_memory", written)


def structures_work(runs, device, folder, written):
    if not structures_comparable(runs):
        return
    runs = with_methods(runs)
    scenes = runs.sort_values("scene_triangles").scene.unique().tolist()
    methods = [m for m in structure_order(runs) if m != "auto"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(15, 4.5))
    part = runs[(runs.strategy_type == "branching") & (runs.method_kind != "auto")]
    for method in methods:
        group = part[part.method_kind == method]
        left.scatter(group.predicted_work_per_ray, group.work_per_ray_mean, label=method, color=method_color(method))
    lo = max(1e-2, min(part.predicted_work_per_ray.min(), part.work_per_ray_mean.min()))
    hi = max(part.predicted_work_per_ray.max(), part.work_per_ray_mean.max())
    left.plot([lo, hi], [lo, hi], "k--", lw=1, label="measured = predicted")
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_xlabel("predicted work per ray (cost model: visits + tests)")
    left.set_ylabel("measured work per ray")
    left.set_title("The cost model against the measured work (branching)")
    left.legend(fontsize=7)
    grouped_bars(right, part, "simd_efficiency", scenes, methods, log=False)
    right.set_ylim(0, 1.05)
    right.set_ylabel("active lanes / lane slots")
    right.set_title("Lane utilisation of the branching kernel (Aila & Laine)")
    fig.suptitle(f"Work per ray and lane utilisation, {size(runs)}; {device}")
    save(fig, folder, "structures_work", written)


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


def run(folder: Path) -> int:
    check_folder(folder)
    try:
        runs, failed, _, device = load(folder)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
        raise PlotError(f"{folder / 'runs.csv'}: cannot be read as a CSV ({str(e).strip()})") from e
    except json.JSONDecodeError as e:
        raise PlotError(f"{folder / 'context.json'}: not valid JSON (line {e.lineno}: {e.msg})") from e
    except (AttributeError, KeyError) as e:
        raise PlotError(f"{folder}: runs.csv or context.json lacks what rtbench writes ({e})") from e
    if runs.empty:
        raise PlotError(f"{folder}: no successful runs to chart")
    written = []
    for chart in (speed_vs_accuracy, vertex_precision, simplification):
        chart(runs, device, folder, written)
    runs = runs[variant(runs) == ""]  # the other charts compare methods on the scene as it is
    for chart in (passes_vs_threshold, bandwidth_by_category, unrolling, grid_resolution, kernel_time,
                  structures_time, structures_memory, structures_work):
        chart(runs, device, folder, written)
    failure_map(runs, failed, device, folder, written)
    print(f"{folder}: wrote {', '.join(written)} (.png, .svg)")
    return 0


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    folder = Path(sys.argv[1])
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
