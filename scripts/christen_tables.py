#!/usr/bin/python3
"""Tables for a christen2005 results folder (configs/christen2005.toml): Christen 2005 §6.2's
benchmarks at his settings, his scenes A, B and C at 256 x 256 over a uniform grid.
  Fig. 6.8    render time per scene at a 20 x 20 x 20 grid (sweep fig6_8);
  Fig. 6.9    render time against grid size (sweeps fig6_9 and fig6_8);
  Figs. 6.10-6.11  his GPU against his CPU, here the Vulkan kernels on the device (lavapipe: on the
              host's own cores) against host C++ running the same grid traversal, by iteration
              (sweeps fig6_8 for the camera rays and fig6_11 for the reflections).
His figures are bitmaps the thesis text lacks: there are no numbers of his to put beside ours.

usage: scripts/christen_tables.py RESULTS_DIR
  writes tables.md
Uses Debian's python3-pandas only.
"""
import sys

import pandas as pd

from rtbench_results import (CHRISTEN_SCENES, christen_iterations, command_text, embree_speed_caption, failed_rows, fmt,
                             host_against_device, interval_of, interval_text, live_headline, masking_share, open_results,
                             passes_gpu_ms, scene_name, write_tables, wrong_rays)

STRATEGIES = ["multipass", "branching", "cpu"]


def grid_text(r) -> str:
    return f"{int(r.grid_res_x)}×{int(r.grid_res_y)}×{int(r.grid_res_z)}"


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    runs["scene_label"] = [f"{scene_name(s)}, {int(t):,} triangles" for s, t in zip(runs.scene_source, runs.scene_triangles)]
    runs["grid"] = [grid_text(r) for r in runs.itertuples()]
    runs["wrong"] = wrong_rays(runs)
    runs["iteration"] = christen_iterations(runs)
    versus = host_against_device(runs, device)
    lines = [f"# Christen 2005's benchmarks — {device}, {context.get('cpu', '?')}", "",
             command_text(context) + " "
             f"{len(runs)} runs ok, {len(failed)} failed. {CHRISTEN_SCENES}", "",
             "All at 256×256 (his size), uniform grid. multipass: Christen's architecture (K = M = 1, oracle 20%, the host "
             "in control, every pass over the whole stream; our stencil test stands for his early-z); branching: one "
             "kernel; cpu: host C++, the same grid traversal (the kernels' source compiled as C++) on the host's "
             f"{'/'.join(sorted({str(int(t)) for t in runs.get('host_threads', pd.Series(dtype=float)).dropna()})) or '?'} "
             f"TBB threads. Figs. 6.10-6.11 set {versus}. ms: median time of a frame (the device's "
             "timestamps; cpu: wall time" + ("; multipass: the live loop's wall time, the oracle's read-back after "
             "every pass" if live_headline(runs) else "; multipass: its passes replayed without the oracle's read-backs") +
             "); " + embree_speed_caption(runs) + " In the same run, with the 95% interval of "
             "the ratio; wrong: rays the exact reference contradicts. Christen's figures are bitmaps missing from the "
             "thesis text: compare shapes, not numbers.", ""]

    first = runs[runs.sweep == "fig6_8"].copy()
    first["order"] = first.strategy_type.map(STRATEGIES.index)
    lines += ["## Fig. 6.8: render time per scene, grid 20×20×20", "",
              "| scene | strategy | ms | Mrays/s | × Embree | 95% interval | passes | wrong |", "|---|---|---|---|---|---|---|---|"]
    for r in first.sort_values(["scene_triangles", "order"]).itertuples():
        lines.append(f"| {r.scene_label} | {r.strategy_type} | {fmt(r.kernel_ms_median)} | {fmt(r.kernel_mrays_s)} | "
                     f"{fmt(r.speed_ratio_vs_embree1)} | {interval_text(interval_of(r, 'speed_ratio'))} | "
                     f"{int(r.passes_total):,} | {int(r.wrong)} |")

    sizes = runs[runs.sweep.isin(["fig6_8", "fig6_9"]) & runs.strategy_type.isin(["multipass", "branching"])]
    lines += ["", "## Fig. 6.9: render time against grid size", "",
              "ms of each architecture; voxels and tests: per ray, mean (the same for both).", "",
              "| scene | grid | voxels/ray | tests/ray | multipass ms | passes | branching ms |", "|---|---|---|---|---|---|---|"]
    rows = []
    for (label, cells), g in sizes.groupby(["scene_label", "grid_cells"]):
        m, b = g[g.strategy_type == "multipass"], g[g.strategy_type == "branching"]
        r = g.iloc[0]
        rows.append(((r.scene_triangles, cells),
                     f"| {label} | {r.grid} | {fmt(r.voxels_per_ray_mean)} | {fmt(r.triangles_per_ray_mean)} | "
                     f"{fmt(m.kernel_ms_median.iloc[0]) if len(m) else ''} | {int(m.passes_total.iloc[0]) if len(m) else ''} | "
                     f"{fmt(b.kernel_ms_median.iloc[0]) if len(b) else ''} |"))
    lines += [text for _, text in sorted(rows)]

    gens = runs[runs.sweep.isin(["fig6_8", "fig6_11"]) & (runs.scene_source != "procedural:christen_a")]
    lines += ["", f"## Figs. 6.10-6.11: {versus}, on the same grid, by iteration", "",
              "Iteration 1: the camera rays; 2-4: mirror reflections 1-3 of every surface (our reading of his iterations). "
              "cpu / multipass, cpu / branching: host C++'s median time over the kernel's, two runs timed round by round "
              "together (experiment.order = interleaved); no interval.", "",
              "| scene | iteration | rays | multipass ms | branching ms | cpu ms | cpu / multipass | cpu / branching |",
              "|---|---|---|---|---|---|---|---|"]
    for (label, it), g in gens.sort_values(["scene_triangles", "iteration"]).groupby(["scene_label", "iteration"], sort=False):
        ms = {s: g[g.strategy_type == s].kernel_ms_median.iloc[0] for s in STRATEGIES if (g.strategy_type == s).any()}
        nan = float("nan")
        lines.append(f"| {label} | {it} | {int(g.rays.iloc[0]):,} | {fmt(ms.get('multipass', nan))} | "
                     f"{fmt(ms.get('branching', nan))} | {fmt(ms.get('cpu', nan))} | "
                     f"{fmt(ms.get('cpu', nan) / ms.get('multipass', nan), 2)} | {fmt(ms.get('cpu', nan) / ms.get('branching', nan), 2)} |")

    stencil = runs[(runs.strategy_type == "multipass") & runs.sweep.isin(["fig6_8", "fig6_11"])]
    if "kernel_ms_stencil_pass" in stencil and stencil.kernel_ms_stencil_pass.notna().any():
        stencil = stencil[stencil.kernel_ms_stencil_pass.notna()].sort_values(["scene_triangles", "iteration"])
        lines += ["", "## §5.5: what masking the rays by state costs", "",
                  "Christen's kernels could not test a ray's state: early-z culling skipped the fragments of rays in "
                  "other states after \"an additional pass which sets the depth-values of those rays that don't need "
                  "processing\", one before each traverse and each intersect pass, so his GPU ran two passes for each of "
                  "ours. Our kernels test the ray's state byte themselves (its reads and writes: `bytes_stencil`); "
                  "`passes_total` counts no masking pass. Measured here: one traverse pass more over the stream once "
                  "every ray is done (`kernel_ms_stencil_pass`, outside the frame's time): what the state test alone "
                  "costs a pass; × loop passes, the frame's share of it, an upper bound (a served ray's test is part of "
                  "its work).", "",
                  "| scene | iteration | loop passes | his passes with masking | state-test pass ms | × loop passes, ms | frame's passes, GPU ms | share |",
                  "|---|---|---|---|---|---|---|---|"]
        for r, share, gpu in zip(stencil.itertuples(), masking_share(stencil), passes_gpu_ms(stencil)):
            loop = int(r.passes_traverse + r.passes_intersect)
            lines.append(f"| {r.scene_label} | {r.iteration} | {loop:,} | {int(r.passes_total) + loop:,} | "
                         f"{fmt(r.kernel_ms_stencil_pass)} | {fmt(r.kernel_ms_stencil_pass * loop)} | "
                         f"{fmt(gpu)} | {100 * share:.0f}% |")
    return write_tables(folder, lines + failed_rows(failed, "scene", lambda r: scene_name(r.scene_source)))


if __name__ == "__main__":
    sys.exit(main())
