#!/usr/bin/python3
"""Markdown tables for a purcell2002 results folder (Purcell et al. 2002, Table 2 style).

usage: scripts/purcell_tables.py RESULTS_DIR   (reads runs.csv and context.json, writes tables.md)
Uses Debian's python3-pandas only.
"""
import sys
from pathlib import Path

import pandas as pd

from rtbench_results import load


def mb(value) -> str:
    return f"{value / 1e6:,.1f}"


def table(frame: pd.DataFrame, columns: dict) -> str:
    """Markdown table of the given columns (csv name -> (header, formatter))."""
    header = "| " + " | ".join(h for h, _ in columns.values()) + " |"
    rule = "|" + "|".join("---" for _ in columns) + "|"
    rows = []
    for _, r in frame.iterrows():
        rows.append("| " + " | ".join(fmt(r[c]) if pd.notna(r[c]) else "" for c, (_, fmt) in columns.items()) + " |")
    return "\n".join([header, rule] + rows)


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    folder = Path(sys.argv[1])
    runs, failed, context, device = load(folder)
    out = [f"# Results: {folder.name}", "",
           f"Device: {device}; CPU: {context['cpu']} ({context['cpu_threads']} threads); "
           f"Embree {context['embree_version']}; commit {context['git_commit']}; {context['date_utc']}.",
           f"Command: `{context['command']}`. {len(runs)} runs ok, {len(failed)} failed.", ""]

    integer = lambda v: f"{int(v):,}"
    pct = lambda v: f"{100 * v:.1f}%"
    fixed = lambda digits: (lambda v: f"{v:,.{digits}f}")
    size = lambda frame: f"{int(frame.camera_width.iloc[0])}x{int(frame.camera_height.iloc[0])}" if len(frame) else "-"

    arch = runs[runs.sweep == "architecture"].sort_values(["scene", "strategy_type"])
    out += [f"## Passes and SIMD efficiency (Purcell Table 2), {size(arch)}", "",
            "Multipass: K = 4 traversal steps and M = 2 intersections per pass, oracle threshold 0.2. "
            "Passes counted over the traverse and intersect kernels (plus one setup and one write pass); "
            "the lower bound is max steps / K + max tests / M over the rays. Branching: one pass; its SIMD "
            "efficiency is subgroup lane utilisation.", "",
            table(arch, {"scene": ("scene", str), "strategy_type": ("architecture", str),
                         "passes_total": ("passes", integer), "passes_traverse": ("traverse", integer),
                         "passes_intersect": ("intersect", integer), "passes_lower_bound": ("lower bound", integer),
                         "traversal_steps_per_ray_max": ("max steps/ray", integer),
                         "triangles_per_ray_max": ("max tests/ray", integer),
                         "simd_efficiency": ("SIMD eff.", pct), "kernel_mrays_s": ("Mrays/s", fixed(3)),
                         "speed_ratio_vs_embree1": ("vs Embree", fixed(4)),
                         "hit_miss_agreement": ("hit/miss agr.", pct)}), ""]

    out += [f"## Bandwidth by data type (Purcell Fig. 8), MB per {size(arch)} frame", "",
            table(arch, {"scene": ("scene", str), "strategy_type": ("architecture", str),
                         "bytes_stencil": ("stencil", mb), "bytes_state": ("state", mb), "bytes_voxel": ("voxels", mb),
                         "bytes_triangle_list": ("tri lists", mb), "bytes_vertices": ("vertices", mb),
                         "bytes_output": ("output", mb), "bytes_total": ("total", mb),
                         "bytes_per_ray": ("bytes/ray", fixed(0))}), ""]

    oracle = runs[runs.sweep.isin(["oracle", "naive"]) | ((runs.sweep == "architecture") & (runs.strategy_type == "multipass"))].copy()
    oracle["schedule"] = oracle.apply(lambda r: "naive" if r.strategy_scheduling == "naive"
                                      else f"oracle {r.strategy_oracle_threshold:g}", axis=1)
    oracle = oracle.sort_values(["scene", "strategy_scheduling", "strategy_oracle_threshold"])
    out += [f"## Oracle threshold (K = 4, M = 2, {size(oracle)})", "",
            table(oracle, {"scene": ("scene", str), "schedule": ("schedule", str), "passes_total": ("passes", integer),
                           "passes_traverse": ("traverse", integer), "passes_intersect": ("intersect", integer),
                           "passes_lower_bound": ("lower bound", integer), "simd_efficiency": ("SIMD eff.", pct),
                           "bytes_per_ray": ("bytes/ray", fixed(0)), "kernel_ms_median": ("GPU ms", fixed(0))}), ""]

    unroll = runs[runs.sweep.str.startswith("unroll")].sort_values(
        ["strategy_suppress_finished_reads", "strategy_traverse_steps_per_pass", "strategy_intersections_per_pass"])
    out += [f"## Loop unrolling on the bunny (oracle 0.2, {size(unroll)})", "",
            table(unroll, {"strategy_traverse_steps_per_pass": ("K", integer),
                           "strategy_intersections_per_pass": ("M", integer),
                           "strategy_suppress_finished_reads": ("suppress", str), "passes_total": ("passes", integer),
                           "passes_lower_bound": ("lower bound", integer), "simd_efficiency": ("SIMD eff.", pct),
                           "bytes_voxel": ("voxel MB", mb), "bytes_vertices": ("vertex MB", mb),
                           "bytes_per_ray": ("bytes/ray", fixed(0)), "kernel_ms_median": ("GPU ms", fixed(0))}), ""]

    grid = runs[runs.sweep == "grid"].sort_values(["strategy_type", "structure_min_dim"])
    out += [f"## Grid resolution on the bunny (min_dim heuristic, {size(grid)})", "",
            table(grid, {"strategy_type": ("architecture", str), "structure_min_dim": ("min_dim", integer),
                         "grid_cells": ("cells", integer), "grid_empty_fraction": ("empty", pct),
                         "grid_refs_per_triangle": ("refs/tri", fixed(2)),
                         "voxels_per_ray_mean": ("voxels/ray", fixed(2)),
                         "triangles_per_ray_mean": ("tests/ray", fixed(2)), "passes_total": ("passes", integer),
                         "simd_efficiency": ("SIMD eff.", pct), "kernel_mrays_s": ("Mrays/s", fixed(3)),
                         "grid_build_ms": ("build ms", fixed(0))}), ""]

    checks = runs[["cpu_reference_mismatches", "cpu_counts_match", "hit_miss_agreement"]]
    out += ["## Checks", "",
            f"- CPU functional simulator: hit records identical on every ray in {int((checks.cpu_reference_mismatches == 0).sum())} "
            f"of {len(runs)} runs; pass/bandwidth/lane counts identical in {int(checks.cpu_counts_match.sum())} of {len(runs)}.",
            f"- Multipass against branching: identical hit records on every ray in "
            f"{int((runs[runs.strategy_type == 'multipass'].branching_mismatches == 0).sum())} of "
            f"{int((runs.strategy_type == 'multipass').sum())} multipass runs.",
            f"- Hit/miss agreement with Embree: min {100 * checks.hit_miss_agreement.min():.4f}% over all runs.",
            f"- Total wall time of the runs: {runs.wall_s.sum() / 60:.1f} min.", ""]
    (folder / "tables.md").write_text("\n".join(out))
    print(f"wrote {folder / 'tables.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
