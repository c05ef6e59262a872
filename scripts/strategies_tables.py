#!/usr/bin/python3
"""Table and chart for a strategies results folder (configs/strategies.toml): each execution
strategy (branching, multipass, the scheduled megakernel under each schedule, persistent threads)
over each structure, against the branching kernel on the same structure and against Embree on the
same rays: time, SIMD efficiency, passes or state executions, bytes, and the failed runs with why.

usage: scripts/strategies_tables.py RESULTS_DIR
  writes tables.md, strategies.png/.svg (GPU time against SIMD efficiency, one point per run)
Uses Debian's python3-pandas and python3-matplotlib only.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd

from rtbench_results import (commit_text, embree_on, embree_speed_caption, fmt, interval_of, interval_text, open_results, read_samples,
                             round_ratios, save_figure, structure_names, with_interval, write_text_atomically, wrong_rays)


def strategy(run) -> str:
    """"branching", "multipass K=4 M=2", "multipass on device K=4 M=2", "megakernel switch", "persistent"."""
    if run.strategy_type == "multipass":
        where = " on device" if getattr(run, "strategy_control", "host") == "device" else ""
        return (f"multipass{where} K={int(run.strategy_traverse_steps_per_pass)} "
                f"M={int(run.strategy_intersections_per_pass)}")
    if run.strategy_type == "megakernel":
        return f"megakernel {run.strategy_schedule}"
    return run.strategy_type


def main() -> int:
    folder, runs, failed, context, device = open_results(__doc__)
    for frame in (runs, failed):
        for column in ["strategy_schedule", "strategy_control", "strategy_traverse_steps_per_pass", "strategy_intersections_per_pass",
                       "megakernel_runs_traverse", "megakernel_runs_intersect", "passes_total"]:
            if column not in frame:
                frame[column] = float("nan")
    runs = runs.copy()
    runs["structure"] = structure_names(runs.structure_type)
    runs["strategy"] = [strategy(r) for r in runs.itertuples()]
    runs["wrong"] = wrong_rays(runs)
    # x branching: round by round where the runs were timed in interleaved rounds (samples.csv has
    # both runs' rounds), else the ratio of medians.
    interleaved = "experiment_order" in runs and (runs.experiment_order == "interleaved").all()
    samples = read_samples(folder)
    branching = runs[runs.strategy_type == "branching"].set_index(["scene", "structure"])
    runs["vs_branching"], runs["vs_branching_low"], runs["vs_branching_high"] = float("nan"), float("nan"), float("nan")
    for i, r in runs.iterrows():
        if (r.scene, r.structure) not in branching.index:
            continue
        base = branching.loc[(r.scene, r.structure)]
        ratios = round_ratios(samples, r.run, base.run) if interleaved else pd.Series(dtype=float)
        if len(ratios):
            runs.loc[i, ["vs_branching", "vs_branching_low", "vs_branching_high"]] = \
                [ratios.median(), ratios.min(), ratios.max()]
        else:
            runs.loc[i, "vs_branching"] = r.kernel_ms_median / base.kernel_ms_median
    by_round = runs.vs_branching_low.notna().any()
    size = f"{int(runs.camera_width.iloc[0])}x{int(runs.camera_height.iloc[0])}" if len(runs) else "-"

    lines = [f"# Execution strategies — {device}, {context.get('cpu', '?')}", "",
             f"Command: `{context.get('command', '?')}` at commit {commit_text(context)}, "
             f"{context.get('date_utc', '?')}; {size} rays per run. {len(runs)} runs ok, {len(failed)} failed.",
             "GPU ms: the kernel's median over the timed repetitions (its 95% interval); × branching: " +
             ("the kernel's time over the branching kernel's on the same scene and structure, round by round (one "
              "repetition of each run per round in interleaved rounds, so round r of both saw the same machine): the "
              "median of the rounds' ratios and their range; " if by_round else
              "that median over the branching kernel's on the same scene and structure (two runs of one sweep, so no "
              "interval: read it to a first digit when either run has a timing warning); ") +
             embree_speed_caption(runs) + " In the same run, with its 95% interval. SIMD eff. (Purcell): Purcell 2002 Table 2's "
             "measure on one definition for every strategy, the stream's rays doing useful work per step, misses included "
             "(multipass: rays served over rays × traverse and intersect passes, whatever the control; a whole-traversal "
             "kernel: its stream run in lock step one traversal step or triangle test at a time). Lane util.: branching, "
             "persistent and megakernel: lanes that take a step over subgroup size × steps (the ballots). Multipass on device: the oracle "
             "runs on the device and each pass serves a compacted list (strategy.control = device). Executions: the megakernel's subgroup state executions (traverse + intersect; OptiX Fig. 6's "
             "measure, summed over subgroups); passes: multipass dispatches. Wrong: rays the exact reference "
             "contradicts.", ""]
    lines += ["| scene | structure | strategy | GPU ms | 95% interval | × branching | its range | × Embree [95% interval] | SIMD eff. (Purcell) | "
              "lane util. | executions (trav + isect) | passes | bytes/ray | wrong | timing warning |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in runs.sort_values(["scene", "structure", "strategy_type", "strategy"]).itertuples():
        executions = "" if pd.isna(r.megakernel_runs_traverse) else \
            f"{int(r.megakernel_runs_traverse):,} + {int(r.megakernel_runs_intersect):,}"
        passes = "" if r.strategy_type != "multipass" else f"{int(r.passes_total):,}"
        lines.append(f"| {r.scene} | {r.structure} | {r.strategy} | {fmt(r.kernel_ms_median, 1)} | "
                     f"{interval_text(interval_of(r), 1)} | {fmt(r.vs_branching, 2)} | "
                     f"{'' if pd.isna(r.vs_branching_low) or r.strategy_type == 'branching' else f'{fmt(r.vs_branching_low, 2)}–{fmt(r.vs_branching_high, 2)}'} | "
                     f"{with_interval(r.speed_ratio_vs_embree1, interval_of(r, 'speed_ratio'))} | {fmt(r.simd_efficiency_purcell)} | "
                     f"{fmt(r.simd_lane_utilisation)} | {executions} | "
                     f"{passes} | {fmt(r.bytes_per_ray, 0)} | {int(r.wrong)} | "
                     f"{'yes' if isinstance(r.timing_warning, str) and r.timing_warning else ''} |")
    if len(failed):
        lines += ["", "Failed runs (a run that cannot be trusted is a failed row with the reason):", "",
                  "| run | structure | strategy | why |", "|---|---|---|---|"]
        for r in failed.itertuples():
            lines.append(f"| {r.run} | {r.structure_type} | {r.strategy_type} | {str(r.error).replace('|', '/')} |")
    write_text_atomically(folder / "tables.md", "\n".join(lines) + "\n")

    if len(runs):
        structures = sorted(runs.structure.unique())
        names = sorted(runs.strategy.unique())
        markers = "osD^v<>Xph"
        style = {n: (f"C{i % 10}", markers[i % len(markers)]) for i, n in enumerate(names)}
        fig, axes = plt.subplots(1, len(structures), figsize=(5.5 * len(structures), 4.4), squeeze=False)
        for ax, structure in zip(axes[0], structures):
            g = runs[runs.structure == structure]
            for r in g.itertuples():
                colour, marker = style[r.strategy]
                if pd.isna(r.simd_efficiency_purcell):
                    continue  # a method that counts no work (the driver's ray query)
                ax.errorbar(r.simd_efficiency_purcell, r.kernel_ms_median,
                            yerr=[[r.kernel_ms_median - r.kernel_ms_ci_low], [r.kernel_ms_ci_high - r.kernel_ms_median]],
                            fmt=marker, color=colour, capsize=3, label=r.strategy)
            embree = g.embree1_ms_median.median()
            ax.axhline(embree, color="grey", linestyle="--", linewidth=0.8)
            ax.annotate(embree_on(g), (0.02, embree), xycoords=("axes fraction", "data"), fontsize=7,
                        xytext=(0, 3), textcoords="offset points", color="grey")
            ax.set_yscale("log")
            ax.set_xlim(0, 1.05)
            ax.set_xlabel("SIMD efficiency (Purcell):\nthe stream's rays doing useful work per step")
            ax.set_ylabel("GPU ms (median, 95% interval)")
            ax.set_title(f"{', '.join(sorted(g.scene.unique()))}, {structure}, {size}", fontsize=9)
        # Beside the last panel, not over it: the points crowd the low SIMD efficiencies.
        axes[0][-1].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
        fig.suptitle(f"Execution strategies on {device} ({commit_text(context)})", fontsize=9)
        fig.tight_layout()
        for ext in ("png", "svg"):
            save_figure(fig, folder / f"strategies.{ext}", dpi=110, bbox_inches="tight")
        plt.close(fig)
    print(folder / "tables.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
