#!/usr/bin/python3
"""Tables and chart for a wavefront results folder (configs/wavefront.toml): whole paths traced on
the device from the camera rays, by the wavefront (a kernel per stage over compacted queues) and by
the path megakernel (one kernel), against the branching kernel tracing each generation as a batch
of its own (the host making the generations between), and against Embree on the same rays.

usage: scripts/wavefront_tables.py RESULTS_DIR
  writes tables.md, wavefront.png/.svg (GPU time per ray traced against the generations traced)
Uses Debian's python3-pandas and python3-matplotlib only.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd

from rtbench_results import (commit_text, embree_on, embree_speed_caption, failed_rows, faster_of, fmt, interval_of,
                             open_results, save_figure, structure_names, with_interval, wrong_rays, write_tables)


def generation(run) -> int:
    """The batch's generation: 0 for the camera rays, k for reflection iteration or path bounce k."""
    if run.rays_type == "reflection":
        return int(run.reflection_iteration)
    if run.rays_type == "path":
        return int(run.path_bounce)
    return 0


def host_paths(runs: pd.DataFrame) -> pd.DataFrame:
    """Branching's host-driven path to each batch: its runs of the camera rays and of every generation
    up to the batch's, summed (the same rays as the whole-path strategies trace; no shading timed).
    Kept only where every generation's run is there. Columns: scene, structure, rays_type, generation,
    rays, ms, embree_ms."""
    rows = []
    branching = runs[runs.strategy_type == "branching"]
    for (scene, structure), g in branching.groupby(["scene", "structure"]):
        camera = g[g.rays_type == "primary"]
        if len(camera) != 1:
            continue
        for kind in sorted(set(g.rays_type) - {"primary"}):
            of = g[g.rays_type == kind]
            for k in sorted(of.generation.unique()):
                upto = of[of.generation <= k]
                if len(upto) != k:
                    continue
                rows.append({"scene": scene, "structure": structure, "rays_type": kind, "generation": k,
                             "rays": int(upto.rays.sum() + camera.rays.iloc[0]),
                             "ms": upto.kernel_ms_median.sum() + camera.kernel_ms_median.iloc[0],
                             "embree_ms": upto.embree1_ms_median.sum() + camera.embree1_ms_median.iloc[0]})
    return pd.DataFrame(rows, columns=["scene", "structure", "rays_type", "generation", "rays", "ms", "embree_ms"])


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    for column in ["reflection_iteration", "path_bounce", "whole_path_rays", "kernel_ms_trace", "kernel_ms_shade",
                   "kernel_ms_queue"]:
        if column not in runs:
            runs[column] = float("nan")
    runs["structure"] = structure_names(runs.structure_type)
    runs["generation"] = [generation(r) for r in runs.itertuples()]
    runs["wrong"] = wrong_rays(runs)
    host = host_paths(runs).set_index(["scene", "structure", "rays_type", "generation"])
    whole = runs[runs.strategy_type.isin(["wavefront", "path_megakernel"])]
    size = f"{int(runs.camera_width.iloc[0])}x{int(runs.camera_height.iloc[0])}" if len(runs) else "-"

    lines = [f"# Whole paths on the device — {device}, {context.get('cpu', '?')}", "",
             f"Command: `{context.get('command', '?')}` at commit {commit_text(context)}, "
             f"{context.get('date_utc', '?')}; {size} camera rays per run. {len(runs)} runs ok, {len(failed)} failed.",
             "Each row is a path from the camera rays to its batch (generation k: reflection iteration or path bounce k; "
             "0: the camera rays alone). Rays: every generation's, what the whole-path strategies and Embree traced. "
             "Wavefront and megakernel ms: the median GPU time of the whole path (the wavefront's split into its trace, "
             "shade and queue stages: setup, scans, compactions). Host: branching's runs of the camera rays and of every "
             "generation up to the batch, each a batch of its own, their medians summed: the same rays traced, the trace "
             "alone (the shading passes that made each generation are timed apart, `shading_ms`, and not added; the host's "
             "round trips are not timed). Megakernel ÷ wavefront: the two medians of two runs of one sweep (no interval); "
             "ranked: by the two runs' 95% intervals of GPU time, a tie where they overlap. " + embree_speed_caption(runs) +
             " The same rays: those of every generation, in the same run, with its 95% interval. Lane util.: lanes that take a step over subgroup "
             "size × steps (ballots): the wavefront's of the batch's trace, the megakernel's over its whole path. Wrong: "
             "batch rays the exact reference contradicts.", "",
             "| scene | rays | k | structure | rays traced | host ms (trace only: no shading, no round trips) | "
             "wavefront ms (trace + shade + queue) | megakernel ms | megakernel ÷ wavefront | ranked | "
             "wavefront × Embree [95% interval] | megakernel × Embree [95% interval] | lane util. "
             "(wavefront batch / megakernel) | wrong |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    keys = whole[["scene", "rays_type", "generation", "structure"]].drop_duplicates().sort_values(
        ["scene", "rays_type", "generation", "structure"])
    for key in keys.itertuples(index=False):
        g = whole[(whole.scene == key.scene) & (whole.rays_type == key.rays_type) & (whole.generation == key.generation) &
                  (whole.structure == key.structure)]
        wf = g[g.strategy_type == "wavefront"]
        mk = g[g.strategy_type == "path_megakernel"]
        w = wf.iloc[0] if len(wf) else None
        m = mk.iloc[0] if len(mk) else None
        traced = (w if w is not None else m).whole_path_rays
        h = host.loc[(key.scene, key.structure, key.rays_type, key.generation)] \
            if (key.scene, key.structure, key.rays_type, key.generation) in host.index else None
        if key.rays_type == "primary":
            hb = runs[(runs.strategy_type == "branching") & (runs.scene == key.scene) & (runs.structure == key.structure) &
                      (runs.rays_type == "primary")]
            host_ms = hb.kernel_ms_median.iloc[0] if len(hb) else float("nan")
        else:
            host_ms = h.ms if h is not None else float("nan")
        wave = "" if w is None else (f"{fmt(w.kernel_ms_median, 1)} ({fmt(w.kernel_ms_trace, 1)} + {fmt(w.kernel_ms_shade, 1)} + "
                                     f"{fmt(w.kernel_ms_queue, 1)})")
        lines.append(f"| {key.scene} | {key.rays_type} | {key.generation} | {key.structure} | {int(traced):,} | "
                     f"{fmt(host_ms, 1)} | {wave} | {'' if m is None else fmt(m.kernel_ms_median, 1)} | "
                     f"{fmt(m.kernel_ms_median / w.kernel_ms_median, 2) if w is not None and m is not None else ''} | "
                     f"{faster_of(w, m, ('wavefront', 'megakernel')) if w is not None and m is not None else ''} | "
                     f"{'' if w is None else with_interval(w.speed_ratio_vs_embree1, interval_of(w, 'speed_ratio'))} | "
                     f"{'' if m is None else with_interval(m.speed_ratio_vs_embree1, interval_of(m, 'speed_ratio'))} | "
                     f"{'' if w is None else fmt(w.simd_lane_utilisation)} / {'' if m is None else fmt(m.simd_lane_utilisation)} | "
                     f"{int(g.wrong.sum())} |")
    lines += failed_rows(failed, "structure", lambda r: r.structure_type)
    write_tables(folder, lines)

    panels = sorted({(r.scene, r.rays_type, r.structure) for r in whole.itertuples() if r.rays_type != "primary"})
    if panels:
        cols = min(3, len(panels))
        rows = (len(panels) + cols - 1) // cols
        fig, axes = plt.subplots(rows, cols, figsize=(4.4 * cols, 3.4 * rows), squeeze=False)
        for ax in axes.flat[len(panels):]:
            ax.axis("off")
        hp_all = host_paths(runs)
        for ax, (scene, kind, structure) in zip(axes.flat, panels):
            of = whole[(whole.scene == scene) & (whole.structure == structure) &
                       ((whole.rays_type == kind) | (whole.rays_type == "primary"))]
            for strategy, colour, marker in (("wavefront", "C0", "o"), ("path_megakernel", "C1", "s")):
                s = of[of.strategy_type == strategy].sort_values("generation")
                ax.plot(s.generation, 1e6 * s.kernel_ms_median / s.whole_path_rays, marker=marker, color=colour,
                        label=strategy.replace("_", " "))
            # The host's path: the camera rays' branching run, then the sums up to each generation.
            camera = runs[(runs.strategy_type == "branching") & (runs.scene == scene) & (runs.structure == structure) &
                          (runs.rays_type == "primary")]
            hp = hp_all[(hp_all.scene == scene) & (hp_all.structure == structure) & (hp_all.rays_type == kind)]
            hp = pd.concat([pd.DataFrame({"generation": [0], "rays": camera.rays.values[:1], "ms": camera.kernel_ms_median.values[:1],
                                          "embree_ms": camera.embree1_ms_median.values[:1]}), hp]).sort_values("generation")
            ax.plot(hp.generation, 1e6 * hp.ms / hp.rays, marker="^", color="C2", label="host: branching per generation (trace only)")
            ax.plot(hp.generation, 1e6 * hp.embree_ms / hp.rays, linestyle="--", color="grey", label=embree_on(runs))
            ax.set_xlabel(f"{kind} generation k (0: camera rays)")
            ax.set_ylabel("ns per ray traced")
            ax.set_ylim(bottom=0)
            ax.set_title(f"{scene}, {kind}, {structure}", fontsize=9)
            ax.set_xticks(sorted(of.generation.unique()))
        axes.flat[0].legend(fontsize=7)
        fig.suptitle(f"Whole paths on {device}, {size} camera rays: GPU time of the path over the rays it traced "
                     f"({commit_text(context)})", fontsize=9)
        fig.tight_layout()
        for ext in ("png", "svg"):
            save_figure(fig, folder / f"wavefront.{ext}", dpi=110)
        plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
