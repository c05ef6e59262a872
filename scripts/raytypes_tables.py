#!/usr/bin/python3
"""Tables and charts for a raytypes results folder (configs/raytypes.toml): what rays after the
first hit cost against camera rays (Purcell et al. 2002 Table 3), time against the number of
reflection iterations (Christen 2005 Fig. 6.11), and SIMD efficiency by reflection iteration and
by path-tracing bounce.

usage: scripts/raytypes_tables.py RESULTS_DIR
  writes tables.md, raytypes_cost.png/.svg, raytypes_iterations.png/.svg
Uses Debian's python3-pandas and python3-matplotlib only.
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.ticker
import pandas as pd

from rtbench_results import (commit_text, embree_on, embree_speed_caption, fmt, interval_of, open_results, save_figure,
                             structure_names, whitted_frames, with_interval, write_text_atomically, wrong_rays)

# Purcell et al. 2002, Table 3: relative instructions / bandwidth of a frame, against ray casting
# (his shadow caster finds the eye rays' hits by rasterization, so its frame is the shadow rays').
PURCELL_TABLE3 = {"shadow": (0.85, 1.15), "whitted": (2.62, 3.00), "path": (3.24, 4.06)}


def workload(run) -> str:
    """The batch a run traced: "primary", "shadow (any)", "shadow (closest)", "reflection 2",
    "path bounce 1", "ao (any)", "whitted 2 secondary", "whitted 0 shadow"."""
    if run.rays_type == "reflection":
        return f"reflection {int(run.reflection_iteration)}"
    if run.rays_type == "refraction":
        return f"refraction {int(run.refraction_iteration)}"
    if run.rays_type == "path":
        return f"path bounce {int(run.path_bounce)}"
    if run.rays_type == "whitted":
        return f"whitted {int(run.whitted_depth)} {run.whitted_rays}"
    if run.rays_type in ("shadow", "ao"):
        return f"{run.rays_type} ({run.query})"
    return run.rays_type


def legend_first(axes_row, fontsize):
    """A legend on the first chart of a row that has labelled lines or bars."""
    for ax in axes_row:
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=fontsize)
            return


def percent(value) -> str:
    """A fraction as a table's percentage, "—" where the run has no such measure."""
    return "—" if pd.isna(value) else f"{fmt(100 * value, 1)}%"


def save(fig, folder: Path, name: str):
    fig.tight_layout()
    for ext in ("png", "svg"):
        save_figure(fig, folder / f"{name}.{ext}", dpi=110)
    plt.close(fig)


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    runs["method"] = structure_names(runs.structure_type) + \
        " / " + runs.strategy_type
    runs["workload"] = [workload(r) for r in runs.itertuples()]
    runs["wrong"] = wrong_rays(runs)
    primary = runs[runs.rays_type == "primary"].set_index(["scene", "method"])
    def relative(r, column):
        base = primary[column].get((r.scene, r.method))
        return r[column] / base if base else float("nan")
    runs["time_vs_primary"] = [relative(r, "kernel_ms_median") for _, r in runs.iterrows()]
    runs["bytes_vs_primary"] = [relative(r, "bytes_total") for _, r in runs.iterrows()]
    runs["embree_vs_primary"] = [relative(r, "embree1_ms_median") for _, r in runs.iterrows()]
    size = f"{int(runs.camera_width.iloc[0])}x{int(runs.camera_height.iloc[0])}" if len(runs) else "-"

    lines = [f"# Ray types — {device}, {context.get('cpu', '?')}", "",
             f"Command: `{context.get('command', '?')}` at commit {commit_text(context)}, "
             f"{context.get('date_utc', '?')}; {size} pixels. {len(runs)} runs ok, {len(failed)} failed.",
             "GPU ms is the kernel's median over the timed repetitions, Embree's rtcIntersect1/rtcOccluded1 on the "
             "identical rays in the same run; " + embree_speed_caption(runs) + " With its 95% interval; for any-hit rays "
             "(query any) Embree's is rtcOccluded1. \"× primary\" "
             "is the frame's cost (the whole batch, not per ray) "
             "against the camera rays' on the same scene, structure and strategy. Wrong: rays whose answer the "
             "exact reference contradicts; parent wrong: rays that left from a hit the exact reference does not "
             "confirm (counted, each still judged as the ray it is).", ""]
    lines += ["| scene | method | rays | rays traced | hits | GPU ms | × primary (time) | × primary (bytes) | "
              "Embree ms | × Embree [95% interval] | × primary (Embree) | work/ray | SIMD eff. (Purcell) | lane util. | "
              "wrong | parent wrong |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    order = {w: i for i, w in enumerate(["primary", "shadow (any)", "shadow (closest)", "ao (any)", "ao (closest)"] +
                                        [f"reflection {k}" for k in range(1, 65)] +
                                        [f"refraction {k}" for k in range(1, 65)] +
                                        [f"path bounce {k}" for k in range(1, 65)] +
                                        [f"whitted {k} {b}" for k in range(0, 33) for b in ("secondary", "shadow")])}
    runs["order"] = runs.workload.map(order)
    for r in runs.sort_values(["scene", "method", "order"]).itertuples():
        lines.append(f"| {r.scene} | {r.method} | {r.workload} | {int(r.rays):,} | {int(r.hits):,} | "
                     f"{fmt(r.kernel_ms_median)} | {fmt(r.time_vs_primary, 2)} | {fmt(r.bytes_vs_primary, 2)} | "
                     f"{fmt(r.embree1_ms_median)} | {with_interval(r.speed_ratio_vs_embree1, interval_of(r, 'speed_ratio'))} | "
                     f"{fmt(r.embree_vs_primary, 2)} | {fmt(r.work_per_ray_mean, 2)} | "
                     f"{percent(r.simd_efficiency_purcell)} | {percent(r.simd_lane_utilisation)} | {int(r.wrong)} | "
                     f"{'' if pd.isna(getattr(r, 'exact_parent_wrong', None)) else int(r.exact_parent_wrong)} |")

    shadow = runs[runs.rays_type == "shadow"]
    lines += ["", "## Early termination: shadow rays as any-hit against closest-hit queries", "",
              "The same shadow rays, the same run configuration; the ratio of GPU medians (closest / any).", "",
              "| scene | method | any ms | closest ms | closest / any | work/ray any | work/ray closest |",
              "|---|---|---|---|---|---|---|"]
    for (scene, method), g in shadow.groupby(["scene", "method"]):
        a, c = g[g["query"] == "any"], g[g["query"] == "closest"]
        if a.empty or c.empty:
            continue
        a, c = a.iloc[0], c.iloc[0]
        lines.append(f"| {scene} | {method} | {fmt(a.kernel_ms_median)} | {fmt(c.kernel_ms_median)} | "
                     f"{fmt(c.kernel_ms_median / a.kernel_ms_median, 2)} | {fmt(a.work_per_ray_mean, 2)} | "
                     f"{fmt(c.work_per_ray_mean, 2)} |")
    frames = whitted_frames(runs)
    if not frames.empty:
        lines += ["", "## Whitted ray tracing: a frame to depth D against ray casting", "",
                  "A frame to depth D: the camera rays, generations 1..D of reflections and refractions and the shadow "
                  "rays of generations 0..D (every light), each batch a run of its own; its cost is the sum of the "
                  "batches' against the camera rays' alone (same scene, structure and strategy); × time (Embree's): the "
                  f"same for {embree_on(runs)} (rtcOccluded1 for the shadow rays) on the same rays.", "",
                  "| scene | method | depth | rays | × rays | × time | × bytes | × time (Embree's) | SIMD eff. (Purcell; secondary) | wrong |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for f in frames.itertuples():
            lines.append(f"| {f.scene} | {f.method} | {f.depth} | {f.rays:,} | {fmt(f.rays_x, 2)} | {fmt(f.time_x, 2)} | "
                         f"{fmt(f.bytes_x, 2)} | {fmt(f.embree_x, 2)} | {percent(f.secondary_simd)} | {f.wrong} |")
    lines += ["", "## Beside Purcell et al. 2002, Table 3", "",
              f"Purcell's shadow caster costs {PURCELL_TABLE3['shadow'][0]} × ray casting's instructions and "
              f"{PURCELL_TABLE3['shadow'][1]} × its bandwidth (simulated, his branching kernels); his Whitted "
              f"ray tracer {PURCELL_TABLE3['whitted'][0]} / {PURCELL_TABLE3['whitted'][1]} and path tracer "
              f"{PURCELL_TABLE3['path'][0]} / {PURCELL_TABLE3['path'][1]}. Ours, the shadow batch's frame against "
              "the camera rays' (time; bytes as rtbench counts them): the table above, rows \"shadow (any)\". "
              "His path tracer follows one diffuse ray a bounce, 2 bounces, 64 samples per pixel at 256 x 256 "
              "against a ray caster at 1024 x 1024; ours traces one bounce a run (rows \"path bounce k\", "
              "path.samples paths per pixel), so a frame of his is the camera rays plus bounces 1 and 2. His "
              "Whitted ray tracer makes L + 2 rays a hit (L shadow rays, a reflection, a refraction) on the bunny; "
              "the paper gives neither its depth nor its materials. Ours: the Whitted table above, a frame to depth "
              "D in a room of mirrors and glass (scenes/whitted_room.toml), beside his 2.62 × instructions and "
              "3.00 × bandwidth.", ""]
    if not failed.empty:
        lines += ["## Failed runs", "", "| run | parameters | why |", "|---|---|---|"]
        for r in failed.itertuples():
            lines.append(f"| {int(r.run):03d} | {r.label} | {r.error} |")
    text = "\n".join(lines) + "\n"
    write_text_atomically(folder / "tables.md", text)

    # Chart 1: a frame's cost by ray type against the camera rays', per scene (time and bytes).
    scenes = sorted(runs.scene.unique())
    methods = sorted(runs.method.unique())
    fig, axes = plt.subplots(2, len(scenes), figsize=(4.6 * len(scenes), 7), squeeze=False)
    for col, scene in enumerate(scenes):
        kinds = [w for w in order if w in set(runs[runs.scene == scene].workload) and w != "primary"]
        for row_i, (column, title) in enumerate([("time_vs_primary", "GPU time"), ("bytes_vs_primary", "bytes")]):
            ax = axes[row_i][col]
            width = 0.8 / max(len(methods), 1)
            for m_i, method in enumerate(methods):
                g = runs[(runs.scene == scene) & (runs.method == method)].set_index("workload")
                values = [g[column].get(k, float("nan")) for k in kinds]
                ax.bar([x + m_i * width for x in range(len(kinds))], values, width, label=method)
            if row_i == 0 and "shadow (any)" in kinds:
                ax.axhline(PURCELL_TABLE3["shadow"][0], color="black", ls=":", lw=1, label="Purcell shadow, instructions")
            if row_i == 1 and "shadow (any)" in kinds:
                ax.axhline(PURCELL_TABLE3["shadow"][1], color="black", ls="--", lw=1, label="Purcell shadow, bandwidth")
            ax.axhline(1.0, color="grey", lw=0.8)
            ax.set_xticks([x + 0.4 - width / 2 for x in range(len(kinds))])
            ax.set_xticklabels(kinds, rotation=35, ha="right", fontsize=8)
            ax.set_title(f"{scene}: frame {title} / camera rays'", fontsize=9)
            if col == 0:
                ax.set_ylabel("× primary")
    legend_first(axes[0], 7)
    legend_first(axes[1], 7)
    fig.suptitle(f"Cost of a frame by ray type, against ray casting (Purcell Table 3)\n{device}, {size}", fontsize=10)
    save(fig, folder, "raytypes_cost")

    # Chart 2: Christen Fig. 6.11: time of a frame with k reflection iterations (camera rays plus
    # iterations 1..k), strategies against Embree; and SIMD efficiency by iteration.
    fig, axes = plt.subplots(2, len(scenes), figsize=(4.6 * len(scenes), 7), squeeze=False)
    for col, scene in enumerate(scenes):
        ax, lanes = axes[0][col], axes[1][col]
        for m_i, method in enumerate(methods):
            color = f"C{m_i}"
            mine = runs[(runs.scene == scene) & (runs.method == method)]
            g = mine[mine.rays_type.isin(["primary", "reflection"])]
            g = g.assign(k=g.reflection_iteration.fillna(0).where(g.rays_type == "reflection", 0)).sort_values("k")
            if (g.rays_type == "reflection").any():
                ax.plot(g.k, g.kernel_ms_median.cumsum(), marker="o", color=color, label=method)
                if method.endswith("branching"):  # Embree on the same rays as this structure's
                    ax.plot(g.k, g.embree1_ms_median.cumsum(), marker="x", ls=":", color=color,
                            label=f"Embree rtcIntersect1 (rays of {method.split(' /')[0]})")
                lanes.plot(g.k, 100 * g.simd_efficiency_purcell, marker="o", color=color, label=f"{method}, reflection")
            # Whitted: a frame to depth D (every batch up to it), and generation k's SIMD efficiency.
            wf = frames[(frames.scene == scene) & (frames.method == method)] if not frames.empty else frames
            if not wf.empty:
                base = mine[mine.rays_type == "primary"]
                ax.plot(wf.depth, wf.time_x * base.kernel_ms_median.iloc[0], marker="D", color=color, label=f"{method}, Whitted")
                if method.endswith("branching"):
                    ax.plot(wf.depth, wf.embree_x * base.embree1_ms_median.iloc[0], marker="x", ls=":", color=color,
                            label=f"Embree rtcIntersect1 (rays of {method.split(' /')[0]})")
                w = mine[(mine.rays_type == "primary") | ((mine.rays_type == "whitted") & (mine.whitted_rays == "secondary"))]
                w = w.assign(k=w.whitted_depth.where(w.rays_type == "whitted", 0)).sort_values("k")
                lanes.plot(w.k, 100 * w.simd_efficiency_purcell, marker="D", ls="-.", color=color, label=f"{method}, Whitted generation")
            p = mine[mine.rays_type.isin(["primary", "path"])]
            if (p.rays_type == "path").any():
                p = p.assign(k=p.path_bounce.where(p.rays_type == "path", 0)).sort_values("k")
                lanes.plot(p.k, 100 * p.simd_efficiency_purcell, marker="s", ls="--", color=color, label=f"{method}, path bounce")
        for a in (ax, lanes):
            a.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
        ax.set_yscale("log")
        whitted_scene = not frames.empty and scene in set(frames.scene)
        ax.set_title(f"{scene}: frame time " + ("to Whitted depth k" if whitted_scene else "with k reflection iterations"),
                     fontsize=9)
        ax.set_xlabel("Whitted depth k (0: camera rays and their shadow rays)" if whitted_scene
                      else "reflection iterations k (0: camera rays only)")
        ax.set_ylabel("ms, cumulative (log)")
        lanes.set_title(f"{scene}: SIMD efficiency (Purcell) of " + ("Whitted generation k's reflections\nand refractions"
                        if whitted_scene else "reflection\niteration k's and path bounce k's rays") +
                        "\n(Purcell's measure for every strategy: the stream's rays doing useful work)", fontsize=8)
        lanes.set_xlabel("iteration or bounce k (0: camera rays)")
        lanes.set_ylabel("%")
        lanes.set_ylim(0, 100)
    legend_first(axes[0], 6)
    for a in axes[1]:  # each scene's own kinds of lines
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=5)
    fig.suptitle(f"Reflection iterations (Christen 2005 Fig. 6.11), path bounces and Whitted depth\n{device}, {size}",
                 fontsize=10)
    save(fig, folder, "raytypes_iterations")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
