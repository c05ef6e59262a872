#!/usr/bin/python3
"""Table for a division results folder (configs/division.toml): what rtbench's bit-exact division
costs, as the branching kernel dividing exactly each way (intersection.division: integer or double)
against its plain twin (the same kernel dividing as the device does), each against Embree
rtcIntersect1 on the same rays in the same run (a ratio of ratios), and how time per ray grows with
the stream (issue 18 §2).

usage: scripts/division_tables.py RESULTS_DIR
  writes tables.md
Uses Debian's python3-pandas only.
"""
import sys

import pandas as pd

from rtbench_results import (command_text, division_names, embree_speed_caption, failed_rows, fmt, interval_of, interval_text, open_results,
                             structure_names, write_tables, wrong_rays)


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    runs["structure"] = structure_names(runs.structure_type)
    runs["size"] = [f"{int(w)}x{int(h)}" for w, h in zip(runs.camera_width, runs.camera_height)]
    runs["ns_per_ray"] = runs.kernel_ms_median * 1e6 / runs.rays
    runs["wrong"] = wrong_rays(runs)
    runs["kernel"] = [t if t != "branching" else f"branching, {d}" for t, d in zip(runs.strategy_type, division_names(runs))]
    lines = [f"# What bit-exact division costs — {device}, {context.get('cpu', '?')}", "",
             command_text(context) + " "
             f"{len(runs)} runs ok, {len(failed)} failed.",
             "kernel: the branching kernel dividing exactly, through 32-bit integer products (`integer`) or a double "
             "quotient (`double`; `intersection.division`), or its plain twin dividing as the device does; " +
             embree_speed_caption(runs) + " In the same run (`speed_ratio_vs_embree1`, its 95% bootstrap interval); "
             "exact / plain: an exact kernel's ratio over the plain twin's, a ratio of ratios, "
             "so drift that hits Embree and the kernel alike cancels; integer / double: the same between the two exact "
             "kernels; ns/ray: GPU time per ray (median); 2048² / 1024²: that time per ray at 2048² over 1024²'s; "
             "differing: rays whose plain hit differs from the exactly dividing CPU reference's; wrong: rays the exact "
             "reference contradicts.", "",
             "| structure | rays | kernel | × Embree | 95% interval | exact / plain | integer / double | ns/ray | "
             "2048² / 1024² | differing | wrong |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    key = runs.set_index(["structure", "size", "kernel"])

    def ratio_over(r, kernel):
        return r.speed_ratio_vs_embree1 / key.speed_ratio_vs_embree1.get((r.structure, r.size, kernel), float("nan"))

    for r in runs.sort_values(["structure", "rays", "kernel"]).itertuples():
        over_plain = ratio_over(r, "plain") if r.kernel != "plain" else float("nan")
        over_double = ratio_over(r, "branching, double") if r.kernel == "branching, integer" else float("nan")
        small = key.ns_per_ray.get((r.structure, "1024x1024", r.kernel), float("nan"))
        growth = r.ns_per_ray / small if r.size == "2048x2048" else float("nan")
        differing = getattr(r, "plain_cpu_differing", float("nan"))
        lines.append(f"| {r.structure} | {int(r.rays):,} | {r.kernel} | {fmt(r.speed_ratio_vs_embree1)} | "
                     f"{interval_text(interval_of(r, 'speed_ratio'))} | {fmt(over_plain)} | "
                     f"{fmt(over_double)} | {fmt(r.ns_per_ray, 1)} | "
                     f"{fmt(growth, 2)} | {'' if pd.isna(differing) else int(differing)} | {int(r.wrong)} |")
    return write_tables(folder, lines + failed_rows(failed, "structure", lambda r: r.structure_type))


if __name__ == "__main__":
    sys.exit(main())
