#!/usr/bin/python3
"""Tables for a structures results folder (configs/structures.toml): per scene and strategy, each
structure's GPU time, memory, predicted and measured work, and whether `auto` picked the fastest
of the candidates it weighs (the grid at min_dim 64, the BVH, brute force, each at its default
keys). Writes tables.md next to runs.csv and prints it.

usage: scripts/structures_tables.py RESULTS_DIR
"""
import sys

from rtbench_results import command_text, method_name, open_results, write_text_atomically


def fmt(value, digits=3):
    if value != value:  # NaN
        return "-"
    return f"{value:.{digits}g}"


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    runs["method"] = [method_name(r) for _, r in runs.iterrows()]
    lines = [f"# Structures side by side — {device}, {context.get('cpu', '?')}",
             "",
             command_text(context),
             "GPU time is the median of the timed repetitions; Embree is rtcIntersect1 on the same rays in the same run.",
             ""]
    lines += ["| scene | triangles | strategy | structure | GPU ms | × Embree | bytes/triangle | build ms | predicted work/ray | measured work/ray |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    ordered = runs.sort_values(["scene_triangles", "strategy_type", "kernel_ms_median"])
    for r in ordered.itertuples():
        lines.append(f"| {r.scene} | {int(r.scene_triangles)} | {r.strategy_type} | {r.method} | {fmt(r.kernel_ms_median)} | "
                     f"{fmt(r.speed_ratio_vs_embree1)} | {fmt(r.structure_bytes_per_triangle)} | {fmt(r.structure_build_ms)} | "
                     f"{fmt(r.predicted_work_per_ray)} | {fmt(r.work_per_ray_mean)} |")
    # auto against the fastest of its candidates, measured in the same sweep
    candidates = runs[(runs.structure_type.isin(["bvh", "brute_force"])) |
                      ((runs.structure_type == "uniform_grid") & (runs.structure_min_dim == 64))]
    lines += ["", "## Did `auto` pick the fastest?", "",
              "| scene | strategy | fastest candidate (GPU ms) | auto chose | predictions (work per ray) | right? |",
              "|---|---|---|---|---|---|"]
    right = total = 0
    for (scene, strategy), group in runs[runs.structure_type == "auto"].groupby(["scene", "strategy_type"]):
        pool = candidates[(candidates.scene == scene) & (candidates.strategy_type == strategy)]
        if pool.empty:
            continue
        fastest = pool.sort_values("kernel_ms_median").iloc[0]
        choice = group.auto_choice.iloc[0]
        ok = fastest.structure_type == choice
        right += ok
        total += 1
        lines.append(f"| {scene} | {strategy} | {method_name(fastest)} ({fmt(fastest.kernel_ms_median)}) | {choice} | "
                     f"{group.auto_predictions.iloc[0]} | {'yes' if ok else 'no'} |")
    lines += ["", f"`auto` picked the fastest candidate in {right} of {total} cases."]
    if not failed.empty:
        lines += ["", "## Failed runs", "", "| run | parameters | why |", "|---|---|---|"]
        for r in failed.itertuples():
            lines.append(f"| {int(r.run):03d} | {r.label} | {r.error} |")
    text = "\n".join(lines) + "\n"
    write_text_atomically(folder / "tables.md", text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
