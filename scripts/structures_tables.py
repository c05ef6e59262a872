#!/usr/bin/python3
"""Tables for a structures results folder (configs/structures.toml): per scene and strategy, each
structure's GPU time, memory, predicted and measured work, and whether `auto` picked the fastest
of the candidates it weighs (the grid at min_dim 64, the BVH, brute force, each at its default
keys), the fastest only where the 95% intervals separate. Writes tables.md next to runs.csv and
prints it.

usage: scripts/structures_tables.py RESULTS_DIR
"""
import sys

from rtbench_results import (auto_summary, auto_verdicts, command_text, embree_speed_caption, interval_of, method_name,
                             open_results, ranked_text, with_interval, write_text_atomically)


def fmt(value, digits=3):
    if value != value:  # NaN
        return "-"
    return f"{value:.{digits}g}"


def timed(run) -> str:
    """A candidate's name and GPU time with its interval: "bvh 20.3 [20.2, 20.7]"."""
    return f"{method_name(run)} {with_interval(run.kernel_ms_median, interval_of(run), fmt)}"


def auto_table(runs) -> list:
    """auto against the fastest of its candidates, measured in the same sweep: the fastest only where
    the candidates' 95% intervals of GPU time separate."""
    verdicts = auto_verdicts(runs)
    lines = ["", "## Did `auto` pick the fastest?", "",
             "Fastest: the candidate whose 95% interval of GPU time lies wholly below every other candidate's; where "
             "intervals overlap the fastest's, the overlapping ones tie (each with its interval); a candidate without "
             "an interval is not ranked.", "",
             "| scene | strategy | candidates: GPU ms [95% interval] | fastest | auto chose | predictions (work per ray) | right? |",
             "|---|---|---|---|---|---|---|"]
    for auto, pool, leading, verdict in sorted(verdicts, key=lambda v: (v[0].scene, v[0].strategy_type)):
        candidates = "; ".join(timed(r) for _, r in pool.sort_values("kernel_ms_median").iterrows())
        lines.append(f"| {auto.scene} | {auto.strategy_type} | {candidates} | {ranked_text(leading, method_name, fmt)} | "
                     f"{auto.auto_choice} | {auto.auto_predictions} | {verdict} |")
    return lines + ["", auto_summary(verdicts)]


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    runs["method"] = [method_name(r) for _, r in runs.iterrows()]
    lines = [f"# Structures side by side — {device}, {context.get('cpu', '?')}",
             "",
             command_text(context),
             "GPU time is the median of the timed repetitions; " + embree_speed_caption(runs) + " Each with its 95% "
             "interval (`speed_ratio_ci_low`, `_high`).",
             ""]
    lines += ["| scene | triangles | strategy | structure | GPU ms | × Embree [95% interval] | bytes/triangle | build ms | predicted work/ray | measured work/ray |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    ordered = runs.sort_values(["scene_triangles", "strategy_type", "kernel_ms_median"])
    for r in ordered.itertuples():
        lines.append(f"| {r.scene} | {int(r.scene_triangles)} | {r.strategy_type} | {r.method} | {fmt(r.kernel_ms_median)} | "
                     f"{with_interval(r.speed_ratio_vs_embree1, interval_of(r, 'speed_ratio'), fmt)} | "
                     f"{fmt(r.structure_bytes_per_triangle)} | {fmt(r.structure_build_ms)} | "
                     f"{fmt(r.predicted_work_per_ray)} | {fmt(r.work_per_ray_mean)} |")
    lines += auto_table(runs)
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
