#!/usr/bin/python3
"""Tables for a trees results folder (configs/trees.toml): three BVHs of one layout (Embree's binned
SAH, its Morton build, the median split) traced by the branching kernel and by multipass, per scene
and ray type: the tree's SAH cost, size and build time, nodes visited per ray, multipass's passes,
lane utilisation and speed against Embree; the counts also as multiples of the SAH tree's (does a
worse tree cost multipass more than branching?). Writes tables.md next to runs.csv.

usage: scripts/trees_tables.py RESULTS_DIR
Uses Debian's python3-pandas only.
"""
import sys

from rtbench_results import (against_sah, command_text, embree_speed_caption, failed_rows, fmt, interval_of, interval_text, values_text,
                             open_results, write_tables)

TREE_ORDER = {"SAH": 0, "Morton": 1, "median split": 2}



def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    runs = against_sah(runs)
    lines = [f"# Tree quality against the strategy — {device}, {context.get('cpu', '?')}", "",
             command_text(context) + f" {len(runs)} runs ok, {len(failed)} failed.",
             "tree: Embree's binned SAH (`structure.type = \"bvh\"`, `quality = \"medium\"`), its Morton build "
             "(`quality = \"low\"`) or the median split (`median_bvh`), leaf size " + values_text(runs.structure_leaf_size) +
             ", one layout and one set of kernels; build ms: the two runs' median; "
             "SAH cost: the tree's (`bvh_sah_cost`, node and test cost 1); nodes/ray: inner nodes visited per ray "
             "(mean); passes: multipass's (K = " + values_text(runs.strategy_traverse_steps_per_pass) + ", M = " +
             values_text(runs.strategy_intersections_per_pass) + "); lanes: the branching kernel's SIMD lane "
             "utilisation; × SAH: the count over the SAH tree's on the same rays; " + embree_speed_caption(runs) +
             " In the same run, with its 95% interval. Counts are deterministic; times are this machine's.", "",
             "| scene | rays | tree | SAH cost | inner nodes | depth | build ms | nodes/ray | × SAH | lanes | "
             "branching × Embree [95%] | passes | × SAH | multipass × Embree [95%] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    runs["order"] = runs.tree.map(TREE_ORDER).fillna(len(TREE_ORDER))
    for (triangles, scene, rays, order, tree), g in runs.groupby(["scene_triangles", "scene", "rays_type", "order", "tree"]):
        branching = g[g.strategy_type == "branching"]
        multipass = g[g.strategy_type == "multipass"]
        b = branching.iloc[0] if len(branching) else None
        m = multipass.iloc[0] if len(multipass) else None
        first = g.iloc[0]  # the tree's counts, the same in either strategy's run; its build time, the two runs' median
        build_ms = g.structure_build_ms.median()
        speed = lambda r: "" if r is None else f"{r.speed_ratio_vs_embree1:.3g} {interval_text(interval_of(r, 'speed_ratio'))}"
        lines.append(f"| {scene} | {rays} | {tree} | {fmt(first.bvh_sah_cost, 2)} | {int(first.bvh_inner_nodes):,} | "
                     f"{int(first.bvh_depth)} | {fmt(build_ms, 1)} | {fmt(first.nodes_per_ray_mean, 2)} | "
                     f"{fmt(first.nodes_per_ray_mean_x, 2)} | {'' if b is None else fmt(b.simd_lane_utilisation)} | "
                     f"{speed(b)} | {'' if m is None else f'{int(m.passes_total):,}'} | "
                     f"{'' if m is None else fmt(m.passes_total_x, 2)} | {speed(m)} |")
    return write_tables(folder, lines + failed_rows(failed, "tree", lambda r: r.label))


if __name__ == "__main__":
    sys.exit(main())
