#!/usr/bin/python3
"""The results of record, written from results/ (never typed): results/README.md whole (each
folder's machine, device and command from its context.json, its tables and findings from its
runs.csv, its charts) and the README's table of headline results (between the two markers below
in README.md), a row per folder, declared by its section where its figures are computed.

usage: /usr/bin/python3 scripts/readme_figures.py            rewrite results/README.md and the README's table
       /usr/bin/python3 scripts/readme_figures.py --check    exit 1 (with a diff) when either differs, or
                                                             when the README's first config is not
                                                             configs/first.toml
       /usr/bin/python3 scripts/readme_figures.py --print    print results/README.md
       --readme PATH, --results PATH                         other files (the test's altered copies)
"""
import difflib
import json
import re
import sys
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rtbench_results import (CHRISTEN_SCENES, EMBREE_SPEED, against_sah, auto_summary, auto_verdicts, commit_text, division_names,  # noqa: E402
                             embree_on, embree_speed_caption, faster_of, host_against_device, interval_of, leaders,
                             live_headline, masking_share, method_name, passes_gpu_ms, ranked_text, read_runs, read_samples, round_ratios, round_times,
                             scene_name, sorted_beside_branching, speed_verdict, structure_names, verdict_counts, whitted_frames,
                             values_text, with_interval, wrong_rays)
from purcell_tables import PURCELL_TABLE_2  # noqa: E402  (his Table 2, the paper's numbers)

ROOT = Path(__file__).resolve().parent.parent
BEGIN = "<!-- headline results: begin (scripts/readme_figures.py writes this table from results/; do not edit) -->"
END = "<!-- headline results: end -->"


def num(value, digits=3) -> str:
    """A value to `digits` significant digits, thousands separated: 1,759 / 0.0105 / 5.72."""
    if value is None or pd.isna(value):
        return "—"
    value = float(value)
    if value == float("inf"):
        return "inf"
    if abs(value) >= 10 ** digits:
        return f"{value:,.0f}"
    text = f"{value:.{digits}g}"
    if "e" in text:
        return f"{value:.{digits - 1}e}"
    if abs(value) >= 1000:
        return f"{value:,.0f}"
    return text


def count(value) -> str:
    return "—" if pd.isna(value) else f"{int(value):,}"


def reasons(errors) -> str:
    """Failure reasons, counted: each error's first clause with its numbers as N."""
    clauses = errors.fillna("").str.replace(r" ?\([^)]*\)", "", regex=True) \
        .str.replace(r"(?<!\w)[-+]?\d[\d,.]*(?:e[-+]?\d+)?", "N", regex=True) \
        .str.replace(",", "").str.split(r" with |: the |; ", regex=True).str[0]
    return "; ".join(f"{n}× \"{why.strip()}\"" for why, n in clauses.value_counts().items())


def plural(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def size(row) -> str:
    return f"{int(row.camera_width)}×{int(row.camera_height)}"


def span(low, high) -> str:
    """low–high, or one value when they are equal."""
    return num(low) if num(low) == num(high) else f"{num(low)}–{num(high)}"


def interval(low, high, digits=3) -> str:
    return f"[{num(low, digits)}, {num(high, digits)}]"


def folder_of(name: str) -> Path:
    return ROOT / "results" / name


def load(name: str):
    folder = folder_of(name)
    runs = read_runs(folder)
    context = json.loads((folder / "context.json").read_text())
    runs["scene"] = runs.scene_source.map(scene_name)
    runs["method"] = [method_name(r) for _, r in runs.iterrows()]
    return runs, context


def provenance(name: str, runs, context) -> str:
    """Who, where and how: the machine, device, command, commit and date of a folder, and what the
    noise guard said of its runs."""
    devices = context.get("devices") or [{}]
    ok = runs[runs.status == "ok"]
    failed = len(runs) - len(ok)
    flagged = int((ok.timing_warning.fillna("") != "").sum()) if "timing_warning" in ok else None
    reps = sorted(set(int(r) for r in ok.timing_repetitions.dropna())) if "timing_repetitions" in ok else []
    lines = [f"Machine: {context.get('cpu', '?')}, {context.get('cpu_threads', '?')} hardware threads "
             f"(host `{context.get('host', '?')}`). {'Devices' if len(devices) > 1 else 'Device'}: " +
             "; ".join(f"{d.get('name', '?')} ({d.get('driver', '?')}, subgroup size {d.get('subgroup_size', '?')})"
                       for d in devices) + f". Embree {context.get('embree_version', '?')}.",
             f"Command: `{context.get('command', '?')}` at commit "
             f"`{commit_text(context)}`, {str(context.get('date_utc', '?'))[:10]}. "
             f"{plural(len(runs), 'run')}: {len(ok)} ok, {failed} failed with their reason in `error`."]
    if flagged is not None:
        wall = runs.wall_s.sum()
        timing = "one timed repetition of each method per run (no spread, no interval)" if reps == [1] else \
            f"{reps_text(reps)} timed repetitions of each method per run, in rounds"
        lines.append(f"Timing: {timing}; the noise guard flagged {flagged} of the {len(ok)} ok runs (`timing_warning`: "
                     f"{guard_criterion(ok)} or "
                     f"other processes over {num(100 * ok.experiment_noise_other_cpu.iloc[0]) if len(ok) else '?'}% of "
                     f"the CPU; they took at most {num(100 * ok.other_cpu_fraction.max(), 2)}%); "
                     f"{num(wall, 2) + ' s' if wall < 120 else num(wall / 60, 2) + ' min'} of wall time in all.")
    return " ".join(lines)


def reps_text(reps):
    """The runs' repetition counts: each of a few (10/15), or the range of many (10–30: adaptive
    rounds, experiment.target_ci, stop where each run's medians settle)."""
    if not reps:
        return "?"
    if len(reps) <= 3:
        return "/".join(map(str, reps))
    return f"{reps[0]}–{reps[-1]} (adaptive: `timing_stop` says why each run stopped)"


def guard_criterion(ok):
    """What the noise guard judged a method's spread by, as the folder's schema had it: the median's
    interval from results schema 28 (experiment.noise_ci; the CV below 6 repetitions), the CV before."""
    if not len(ok):
        return "a spread over ?"
    cv = num(ok.experiment_noise_cv.iloc[0])
    if "experiment_noise_ci" in ok and ok.experiment_noise_ci.notna().any():
        return (f"a median's 95% interval wider than ±{num(100 * ok.experiment_noise_ci.iloc[0])}% of it, or below 6 "
                f"repetitions a coefficient of variation over {cv},")
    return f"a coefficient of variation over {cv}"


# The README's headline table, a row per folder: declared by each section where its figures are
# computed (headline()), in the order the sections run.
HEADLINES = {}


def headline(name: str, question: str, text: str, context):
    """The README's row of results/<name>/: the question it answers, its headline figures, and where
    they were recorded (device, date)."""
    device = context["devices"][0].get("name", "?") if context.get("devices") else "?"
    HEADLINES[name] = (question, text, f"{device.split(' (')[0]} on {context.get('cpu', '?')}, "
                                       f"{str(context.get('date_utc', '?'))[:10]}")


def charts(name: str, captions: dict) -> list:
    """Markdown images of the charts that exist, in the order given."""
    return [f"![{caption}](results/{name}/{chart}.png)" for chart, caption in captions.items()
            if (folder_of(name) / f"{chart}.png").exists()]


def bunny() -> list:
    runs, context = load("bunny")
    r = runs.iloc[0]
    out = ["### `results/bunny/`: the default experiment", "", provenance("bunny", runs, context), ""]
    if r.status != "ok":
        return out + [f"The run failed: {r.error}", ""]
    out += [f"{scene_name(r.scene_source)} ({count(r.scene_triangles)} triangles), {size(r)} primary rays ({count(r.hits)} hit), {r.method} "
            f"({count(r.grid_res_x)}×{count(r.grid_res_y)}×{count(r.grid_res_z)} voxels), {r.strategy_type} kernel, "
            f"{r.intersection_test}.", "",
            "| | median ms [95% interval] | CV | Mrays/s |", "|---|---|---|---|"]
    for label, m, rate in [("kernel (GPU timestamps)", "kernel", "kernel_mrays_s"),
                           ("Embree `rtcIntersect1`", "embree1", "embree1_mrays_s"),
                           ("Embree `rtcIntersect16`", "embree16", "embree16_mrays_s")]:
        out.append(f"| {label} | {num(r[m + '_ms_median'])} {interval(r[m + '_ms_ci_low'], r[m + '_ms_ci_high'])} | "
                   f"{num(r[m + '_ms_cv'], 2)} | {num(r[rate])} |")
    headline("bunny", "How fast and how exact is the default experiment?",
             f"{r.strategy_type} kernel, {r.method}, {size(r)}: **{num(r.speed_ratio_vs_embree1)}×** the speed of {embree_on(runs)} "
             f"{interval(r.speed_ratio_ci_low, r.speed_ratio_ci_high)}; {num(r.exact_wrong_ppm)} rays wrong per million "
             f"(Embree {num(r.embree_exact_wrong_ppm)})", context)
    out += ["",
            f"- {EMBREE_SPEED}, in the same run ({embree_on(runs)}): **{num(r.speed_ratio_vs_embree1)}** "
            f"(95% interval {interval(r.speed_ratio_ci_low, r.speed_ratio_ci_high)}).",
            f"- Against the exact reference on {count(r.exact_rays)} rays: the kernel gets {count(r.exact_false_misses)} "
            f"false misses, {count(r.exact_false_hits)} false hits and {count(r.exact_wrong_primitive)} wrong triangles "
            f"({num(r.exact_wrong_ppm)} per million); Embree {count(r.embree_exact_false_misses)}, "
            f"{count(r.embree_exact_false_hits)} and {count(r.embree_exact_wrong_primitive)} "
            f"({num(r.embree_exact_wrong_ppm)} per million). In the shaded image {count(r.image_pixels_differ)} pixels "
            f"differ from the exact render (PSNR {num(r.image_psnr_db)} dB).",
            f"- The GPU's hit records and counts against its CPU reference: {count(r.cpu_reference_mismatches)} rays differ; "
            f"counts match: {'yes' if r.cpu_counts_match == 1 else 'no'}.",
            f"- Work per ray: {num(r.voxels_per_ray_mean)} voxels and {num(r.triangles_per_ray_mean)} triangle tests "
            f"(predicted {num(r.predicted_work_per_ray)} operations, measured {num(r.work_per_ray_mean)}); subgroup lane "
            f"utilisation {num(100 * r.simd_lane_utilisation)}%; {num(r.bytes_per_ray)} bytes per ray.",
            f"- Grid: {num(100 * r.grid_empty_fraction)}% of {count(r.grid_cells)} voxels empty, "
            f"{num(r.grid_refs_per_triangle)} references per triangle, {num(r.grid_bytes / 1e6)} MB, built in "
            f"{num(r.grid_build_ms)} ms; Embree's BVH in {num(r.embree_build_ms)} ms. The whole run: {num(r.wall_s)} s.", ""]
    for png, caption in [("run-000-shaded", "bunny, shaded"),
                         ("run-000-diff", "bunny, against Embree (yellow: another triangle; red/blue: hit/miss differs)")]:
        if (folder_of("bunny") / f"{png}.png").exists():
            out.append(f"![{caption}](results/bunny/{png}.png)")
    return out + [""]


# Counts that say two runs did the same work (structures: auto against its chosen candidate).
SAME_WORK = ("hits", "passes_total", "bytes_total", "work_per_ray_mean", "simd_efficiency", "exact_wrong_ppm")


def auto_lines(ok) -> list:
    """auto against the run of the structure it chose (the same work, timed apart), and whether it
    picked the fastest of its candidates (rtbench_results.auto_verdicts: ranked only where the 95%
    intervals separate)."""
    pairs = []
    verdicts = auto_verdicts(ok)
    for auto, pool, _, _ in verdicts:
        chosen = pool[pool.structure_type == auto.auto_choice]
        if chosen.empty:
            continue
        c = chosen.iloc[0]
        overlap = auto.kernel_ms_ci_low <= c.kernel_ms_ci_high and c.kernel_ms_ci_low <= auto.kernel_ms_ci_high
        same = all(auto[k] == c[k] for k in SAME_WORK)
        pairs.append((auto.kernel_ms_median / c.kernel_ms_median, overlap, auto.scene, auto.strategy_type, same))
    if not pairs:
        return []
    ratios = [max(p[0], 1 / p[0]) for p in pairs]
    worst = pairs[ratios.index(max(ratios))]
    within = sum(r <= 1.05 for r in ratios)
    same = sum(p[4] for p in pairs)
    return [f"- **`auto` and the run of the structure it chose** trace the same rays through the same structure "
            f"({same} of {len(pairs)} pairs equal in {', '.join(f'`{k}`' for k in SAME_WORK)}) and were timed "
            f"apart: their medians differ by at most {num(100 * (max(ratios) - 1), 2)}% (worst: {worst[2]}, "
            f"{worst[3]}, auto / candidate {num(worst[0])}), {within} of {len(pairs)} pairs within 5%, and "
            f"{sum(p[1] for p in pairs)} of {len(pairs)} pairs have overlapping 95% intervals.",
            "- **Did `auto` pick the fastest of its candidates** (grid at min_dim 64, BVH, brute force)? "
            + auto_summary(verdicts)]


def structure_row(group, columns, failed_of) -> tuple:
    """A scene's cells (GPU ms [95% interval], the separated fastest in bold) and its fastest: one
    structure (with its × Embree), a tie, or no interval."""
    plain = group[group.structure_type != "auto"]
    leading = leaders(plain)
    cells = []
    for column in columns:
        row = plain[plain.method == column]
        if row.empty:
            cells.append("failed" if failed_of(column) else "—")
            continue
        row = row.iloc[0]
        text = f"{num(row.kernel_ms_median)} {interval(row.kernel_ms_ci_low, row.kernel_ms_ci_high)}"
        cells.append(f"**{num(row.kernel_ms_median)}** {interval(row.kernel_ms_ci_low, row.kernel_ms_ci_high)}"
                     if leading and len(leading) == 1 and leading[0].method == column else text)
    fastest = ranked_text(leading, lambda r: r.method, num)
    if leading and len(leading) == 1:
        w = leading[0]
        fastest += f"; × Embree {with_interval(w.speed_ratio_vs_embree1, interval_of(w, 'speed_ratio'), lambda v: num(v, 2))}"
    return cells, fastest, leading


def structures() -> list:
    runs, context = load("structures")
    ok = runs[runs.status == "ok"].copy()
    out = ["### `results/structures/`: which structure does a scene need?", "", provenance("structures", runs, context), "",
           f"Full tables: [`results/structures/tables.md`](results/structures/tables.md). GPU ms per frame at "
           f"{size(ok.iloc[0])} (median [95% interval]). Fastest: the structure whose interval lies wholly below every "
           f"other's, in bold; where intervals overlap the fastest's, a tie (each with its interval). Beside the fastest, "
           f"{EMBREE_SPEED}, in the same run ({embree_on(ok)}), with its 95% interval.", ""]
    columns = ["grid 32", "grid 64", "grid 128", "bvh", "brute force"]
    fastest = {}  # strategy -> the fastest structure, "tied" or "not ranked" -> scenes
    for strategy in ["branching", "multipass"]:
        part = ok[ok.strategy_type == strategy]
        out += [f"{strategy}:", "", "| scene (triangles) | " + " | ".join(columns) + " | fastest | auto's choice |",
                "|---|" + "---|" * (len(columns) + 2)]
        for scene, group in sorted(part.groupby("scene"), key=lambda g: g[1].scene_triangles.iloc[0]):
            failed = runs[(runs.status != "ok") & (runs.scene_source == group.scene_source.iloc[0]) &
                          (runs.strategy_type == strategy)]
            cells, best, leading = structure_row(group, columns, lambda column: (failed.method == column).any())
            key = leading[0].method if leading and len(leading) == 1 else \
                "tied" if leading else "not ranked"
            fastest.setdefault(strategy, {}).setdefault(key, []).append(scene)
            auto = group[group.structure_type == "auto"]
            choice = auto.auto_choice.iloc[0] if not auto.empty else "—"
            out.append(f"| {scene} ({count(group.scene_triangles.iloc[0])}) | " + " | ".join(cells) + f" | {best} | {choice} |")
        out.append("")
    headline("structures", "Which acceleration structure does a scene need?",
             "the fastest by GPU time at " + size(ok.iloc[0]) + ", where the 95% intervals separate: " + "; ".join(
                 f"{strategy}: " + ", ".join(f"{structure} ({', '.join(scenes)})" for structure, scenes in by.items())
                 for strategy, by in fastest.items()), context)
    out += auto_lines(ok)
    failed = runs[runs.status != "ok"]
    if not failed.empty:
        out.append(f"- {len(failed)} runs failed, each naming why: {reasons(failed.error)}.")
    agree = ok.hit_miss_agreement.min()
    wrong = int(wrong_rays(ok).sum())
    out += [f"- Against the exact reference the ok runs get {wrong:,} of {count(ok.exact_rays.sum())} rays wrong; "
            f"hit/miss agreement with Embree is at least {num(100 * agree, 4)}%; CPU-reference mismatches in all: "
            f"{count(ok.cpu_reference_mismatches.sum())}.", ""]
    out += charts("structures", {"structures_time": "time per scene and speed against Embree, per structure",
                                 "structures_memory": "memory and build time per structure",
                                 "structures_work": "work per ray: the cost model against the measurement"})
    return out + [""]


def purcell2002() -> list:
    runs, context = load("purcell2002")
    ok = runs[runs.status == "ok"].copy()
    arch = ok[ok.sweep == "architecture"].sort_values(["scene_triangles", "strategy_type"])
    mp = arch[arch.strategy_type == "multipass"]
    k = ", ".join(sorted({f"K = {count(a)}, M = {count(b)}" for a, b in zip(mp.strategy_traverse_steps_per_pass,
                                                                            mp.strategy_intersections_per_pass)}))
    table_2 = k == "K = 1, M = 1"
    out = ["### `results/purcell2002/`: multipass against branching (Purcell et al. 2002)", "",
           provenance("purcell2002", runs, context), "",
           "Full tables, with Purcell's Table 2 numbers beside ours: "
           "[`results/purcell2002/tables.md`](results/purcell2002/tables.md). Multipass in the table below: "
           f"{k} (traversal steps, intersections per pass; " +
           ("Purcell's Table 2 setting, one step or one test a pass" if table_2 else "not Purcell's Table 2 setting, K = M = 1") +
           "), oracle threshold 0.2. SIMD efficiency: Purcell's (the stream's rays doing useful work per pass, misses "
           "included; branching run in lock step one step or test at a time); lane utilisation: the branching "
           "kernel's subgroup ballots. " + embree_speed_caption(ok) + " " + CHRISTEN_SCENES, ""]
    if not arch.empty:
        live = live_headline(arch)  # multipass's ms: its live loop (results schema 25 on) or its replayed passes
        out += [f"| {size(arch.iloc[0])} | passes (traverse+intersect) | lower bound | SIMD efficiency (Purcell) | lane utilisation | MB moved | {'ms (multipass: live loop)' if live else 'GPU ms'} | × Embree [95% interval] |",
                "|---|---|---|---|---|---|---|---|"]
        for _, r in arch.iterrows():
            passes = "1" if r.strategy_type == "branching" else \
                f"{count(r.passes_total)} ({count(r.passes_traverse)}+{count(r.passes_intersect)})"
            percent = lambda v: "" if pd.isna(v) else f"{num(100 * v)}%"
            out.append(f"| {r.scene}, {r.strategy_type} | {passes} | {count(r.get('passes_lower_bound'))} | "
                       f"{percent(r.simd_efficiency_purcell)} | {percent(r.simd_lane_utilisation)} | "
                       f"{num(r.bytes_total / 1e6)} | {num(r.kernel_ms_median)} | "
                       f"{with_interval(r.speed_ratio_vs_embree1, interval_of(r, 'speed_ratio'), num)} |")
        slow, ranked = [], []
        for scene, g in arch.groupby("scene"):
            b, m = g[g.strategy_type == "branching"], g[g.strategy_type == "multipass"]
            if len(b) and len(m):
                ranked.append(faster_of(m.iloc[0], b.iloc[0], ("multipass", "branching")))
                slow.append((m.kernel_ms_median.iloc[0] / b.kernel_ms_median.iloc[0],
                             m.bytes_total.iloc[0] / b.bytes_total.iloc[0],
                             m.passes_total.iloc[0] - 2, m.passes_lower_bound.iloc[0],
                             (m.kernel_ms_median.iloc[0] if live else m.multipass_live_ms_median.iloc[0]) /
                             passes_gpu_ms(m).iloc[0]))
        if slow:
            headline("purcell2002", "Multipass or branching (Purcell et al. 2002)?",
                     f"multipass takes {num(min(x[0] for x in slow), 2)}–{num(max(x[0] for x in slow), 2)}× branching's GPU "
                     f"time at {size(arch.iloc[0])} ({verdict_counts(ranked, 'scenes')}), with {num(min(x[2] / x[3] for x in slow), 2)}–{num(max(x[2] / x[3] for x in slow), 2)}× "
                     f"Purcell's lower bound in passes and {num(min(x[1] for x in slow), 2)}–{num(max(x[1] for x in slow), 2)}× "
                     "the bytes", context)
            out += ["",
                    f"- Multipass needs {num(min(s[2] / s[3] for s in slow), 2)}–{num(max(s[2] / s[3] for s in slow), 2)}× "
                    f"Purcell's lower bound in traverse + intersect passes, moves {num(min(s[1] for s in slow), 2)}–"
                    f"{num(max(s[1] for s in slow), 2)}× the branching kernel's bytes, and takes {num(min(s[0] for s in slow), 2)}–"
                    f"{num(max(s[0] for s in slow), 2)}× its GPU time on this device (" +
                    ("multipass's live loop, the oracle's read-back after every pass; " if live else "the replayed passes'; ") +
                    f"{verdict_counts(ranked, 'scenes')}). " +
                    ("The live loop takes " if live else
                     "The live loop, with the oracle's read-back after every pass (`multipass_live_ms_median`), takes ") +
                    f"{num(min(s[4] for s in slow), 2)}–{num(max(s[4] for s in slow), 2)}× " +
                    ("its passes' GPU time replayed without them (`kernel_ms_replay`)." if live else "that GPU time.")]
    oracle = ok[ok.sweep.isin(["oracle", "architecture"]) & (ok.strategy_type == "multipass") &
                (ok.strategy_scheduling.fillna("oracle") != "naive")]
    if not oracle.empty:
        parts = []
        for scene, g in oracle.groupby("scene"):
            g = g.sort_values("strategy_oracle_threshold")
            best = g.passes_total.min()
            parts.append(f"{scene} " + ", ".join(f"{count(p)} ({num(t)})" for t, p in zip(g.strategy_oracle_threshold,
                                                                                          g.passes_total))
                         + f": fewest at threshold {num(g[g.passes_total == best].strategy_oracle_threshold.iloc[0])}")
        out.append("- **The oracle**, passes (threshold): " + "; ".join(parts) + ".")
    unroll = ok[ok.sweep == "unroll"]
    if not unroll.empty:
        lo, hi = unroll.loc[unroll.passes_total.idxmin()], unroll.loc[unroll.passes_total.idxmax()]
        out.append(f"- **Loop unrolling** ({scene_name(unroll.scene_source.iloc[0])}, {size(unroll.iloc[0])}): "
                   f"passes from {count(hi.passes_total)} (K = {count(hi.strategy_traverse_steps_per_pass)}, M = "
                   f"{count(hi.strategy_intersections_per_pass)}) to {count(lo.passes_total)} (K = "
                   f"{count(lo.strategy_traverse_steps_per_pass)}, M = {count(lo.strategy_intersections_per_pass)}); bytes per "
                   f"ray from {num(hi.bytes_per_ray)} to {num(lo.bytes_per_ray)}.")
    grid = ok[(ok.sweep == "grid") & (ok.strategy_type == "branching")]
    if not grid.empty:
        fastest = grid.loc[grid.kernel_ms_median.idxmin()]
        leading = leaders(grid)
        ranked = "the 95% intervals separate" if leading and len(leading) == 1 else \
            ranked_text(leading, lambda r: f"min_dim {count(r.structure_min_dim)}", num)
        out.append(f"- **Grid resolution** (branching): the highest median speed at min_dim {count(fastest.structure_min_dim)} "
                   f"({num(fastest.kernel_mrays_s)} Mrays/s; {ranked}); triangle tests per ray from "
                   f"{num(grid.triangles_per_ray_mean.max())} to {num(grid.triangles_per_ray_mean.min())} and voxels per ray "
                   f"from {num(grid.voxels_per_ray_mean.min())} to {num(grid.voxels_per_ray_mean.max())} over min_dim "
                   f"{count(grid.structure_min_dim.min())}–{count(grid.structure_min_dim.max())}.")
    cache = ok[ok.cache_ratio_total.notna() & (ok.sweep != "tiling")] if "cache_ratio_total" in ok else ok.iloc[0:0]
    if not cache.empty:
        cache = cache.sort_values(["rays_type", "strategy_type"])
        ratios = "; ".join(f"{r.strategy_type}, {r.rays_type} rays: {num(r.cache_ratio_total, 2)}" for _, r in cache.iterrows())
        r = cache.iloc[0]
        out.append(f"- **Texture cache** (Purcell Fig. 9: {count(r.cache_capacity_bytes)} bytes, {count(r.cache_line_bytes)}-byte "
                   f"lines, {count(r.cache_ways)}-way, the references replayed on the CPU one at a time; "
                   f"{scene_name(r.scene_source)}, {size(r)}): traffic with the cache over without, {ratios}. Triangle "
                   f"vertices are found in the cache on {num(100 * cache.cache_hit_rate_vertices.min())}–"
                   f"{num(100 * cache.cache_hit_rate_vertices.max())}% of line lookups (Purcell: 96–99%).")
    tiling = ok[ok.sweep == "tiling"]
    if not tiling.empty:
        def order(r):
            tile = f"{count(r.camera_tile)}×{count(r.camera_tile)} tiles" if r.camera_tile > 0 else "rows"
            if r.strategy_type == "branching":
                return tile
            return "the whole stream" if r.multipass_batch_rays >= r.rays else \
                f"{count(r.multipass_batch_rays)} rays a batch in {tile}"
        parts = []
        for arch_name, g in tiling.sort_values(["camera_tile", "multipass_batch_rays"], ascending=[True, False]).groupby("strategy_type"):
            runs_of = ", ".join(f"{order(r)} {num(100 * r.cache_hit_rate_vertices)}% (ratio {num(r.cache_ratio_total, 2)})"
                                for _, r in g.iterrows())
            parts.append(f"{arch_name}: {runs_of}")
        r = tiling.iloc[0]
        out.append(f"- **Tiled rendering** (Purcell §5.3; his preliminary experiments gave no numbers; the bunny's Table 2 "
                   f"view, {size(r)}, the cache above): vertex lookups found in the cache (traffic with the cache over "
                   "without), " + "; ".join(parts) + ".")
    views = ok[ok.sweep.str.startswith("table2-") & (ok.strategy_type == "multipass")]
    if not views.empty:
        parts = []
        for view, paper in PURCELL_TABLE_2.items():
            for _, r in views[views.sweep == "table2-" + view].iterrows():
                parts.append(f"{view.replace('-', ' ')} {count(r.passes_total)} ({count(r.passes_traverse)}+"
                             f"{count(r.passes_intersect)}) against his {count(paper['passes_total'])} "
                             f"({count(paper['passes_traverse'])}+{count(paper['passes_intersect'])})")
        bunny = views[views.sweep == "table2-bunny"]
        bunny_note = "" if bunny.empty else (
            f" The bunny's: a {count(bunny.grid_res_x.iloc[0])} × {count(bunny.grid_res_y.iloc[0])} × "
            f"{count(bunny.grid_res_z.iloc[0])} grid, {num(100 * bunny.hits.iloc[0] / bunny.rays.iloc[0])}% of the rays hit, "
            f"SIMD efficiency {num(100 * bunny.simd_efficiency_purcell.iloc[0])}% (his {num(100 * PURCELL_TABLE_2['bunny']['simd_efficiency_purcell'])}%).")
        out.append(f"- **Purcell's Table 2 scenes, rebuilt** ({size(views.iloc[0])}, K = M = 1; the bunny on a floor that "
                   "makes his grid, Soda Hall and the forest invented to his description, `scene/procedural.h`), "
                   "passes (traverse+intersect): " + "; ".join(parts) + "." + bunny_note)
    compute = arch[arch.instructions_total.notna()] if "instructions_total" in arch else arch.iloc[0:0]
    if not compute.empty:
        ratios = []
        for scene, g in compute.groupby("scene"):
            b, m = g[g.strategy_type == "branching"], g[g.strategy_type == "multipass"]
            if len(b) and len(m):
                ratios.append(m.instructions_total.iloc[0] / b.instructions_total.iloc[0])
        if ratios:
            out.append(f"- **Compute** (Purcell Table 1, Fig. 7; an estimate: static SPIR-V instructions × exact events): "
                       f"multipass takes {num(min(ratios), 2)}–{num(max(ratios), 2)}× the branching kernel's instructions "
                       f"(saving and restoring state each pass); instructions per byte moved "
                       f"{num(compute.instructions_per_byte.min(), 2)}–{num(compute.instructions_per_byte.max(), 2)}.")
    multipass = ok[ok.strategy_type == "multipass"]
    out += [f"- Exactness: in {int((ok.cpu_reference_mismatches == 0).sum())} of the {len(ok)} ok runs the GPU's hit "
            f"records equal the CPU simulator's on every ray, and in {int((ok.cpu_counts_match == 1).sum())} its pass, "
            f"event and lane counts; in {int((multipass.branching_mismatches == 0).sum())} of the {len(multipass)} "
            f"multipass runs the hit records equal the branching caster's on every ray.", ""]
    out += charts("purcell2002", {"passes_vs_threshold": "passes against oracle threshold",
                                  "bandwidth_by_category": "bandwidth by data type",
                                  "texture_cache": "texture cache (Purcell Fig. 9)", "unrolling": "loop unrolling",
                                  "grid_resolution": "grid resolution", "kernel_time": "multipass GPU time by kernel",
                                  "compute_by_kernel": "compute and bandwidth by kernel (Purcell Fig. 7)"})
    return out + [""]


def stability() -> list:
    runs, context = load("stability")
    ok = runs[runs.status == "ok"].copy()
    ok["wrong"] = wrong_rays(ok)
    ok["embree_wrong"] = wrong_rays(ok, "embree_exact_")
    out = ["### `results/stability/`: where methods fail", "", provenance("stability", runs, context), "",
           "Every ray of every run is judged against the exact reference. Most rays wrong in one run "
           "(of its rays), by scene, ray-triangle test and sweep, over every structure and offset or scale:", "",
           "| scene | sweep | rays per run | Möller–Trumbore | watertight | Embree |", "|---|---|---|---|---|---|"]
    for (scene, sweep), g in ok.groupby(["scene", "sweep"]):
        mt = g[g.intersection_test == "moller_trumbore"].wrong.max()
        wt = g[g.intersection_test == "watertight"].wrong.max()
        out.append(f"| {scene} | {sweep} | {count(g.exact_rays.max())} | {count(mt)} | {count(wt)} | "
                   f"{count(g.embree_wrong.max())} |")
    failed = runs[runs.status != "ok"]
    headline("stability", "Where do methods fail (scenes moved and scaled)?",
             f"most rays wrong in one run: Möller–Trumbore {count(ok[ok.intersection_test == 'moller_trumbore'].wrong.max())}, "
             f"watertight {count(ok[ok.intersection_test == 'watertight'].wrong.max())}, Embree {count(ok.embree_wrong.max())}; "
             f"{len(failed)} runs refused, each saying why", context)
    if len(failed):
        out += ["", f"- {len(failed)} runs were refused, each naming why: {reasons(failed.error)}."]
    out.append("")
    out += charts("stability", {"failure_map": "rays wrong against offset and scale"})
    return out + [""]


def speed_interval(run):
    """A run's 95% interval of Mrays/s, from its GPU time's; None where it has none."""
    span = interval_of(run)
    rays = run.kernel_mrays_s * run.kernel_ms_median
    return None if span is None else (rays / span[1], rays / span[0])


def pareto(g) -> list:
    """The runs no other run beats, each with the run it ties (or None): another run beats one when it
    is at most as wrong and its speed interval lies wholly above; one at most as wrong with a higher
    median whose interval overlaps is a tie (a run without an interval stays, not ranked)."""
    rows = [r for _, r in g.sort_values(["exact_wrong_ppm", "kernel_mrays_s"], ascending=[True, False]).iterrows()]
    spans = [speed_interval(r) for r in rows]
    front = []
    for r, mine in zip(rows, spans):
        better = [(o, theirs) for o, theirs in zip(rows, spans)
                  if o.exact_wrong_ppm <= r.exact_wrong_ppm and o.kernel_mrays_s > r.kernel_mrays_s]
        if not any(mine and theirs and theirs[0] > mine[1] for _, theirs in better):
            front.append((r, better[0][0] if better else None))
    return front


def run_text(r) -> str:
    """An accuracy run in a few words: method, test, vertex bits, triangles kept."""
    bits = "float" if r.intersection_vertex_bits == 32 else f"{count(r.intersection_vertex_bits)} bits"
    kept = "all" if pd.isna(r.scene_simplify_ratio) else f"{num(100 * r.scene_simplify_ratio)}%"
    return f"{r.method} | {r.intersection_test} | {bits} | {kept}"


def accuracy() -> list:
    runs, context = load("accuracy")
    ok = runs[runs.status == "ok"].copy()
    out = ["### `results/accuracy/`: speed against accuracy", "", provenance("accuracy", runs, context), "",
           "Every ray judged against the exact reference on the full scene. The Pareto front of each scene: the runs "
           "that no other run beats, one at most as wrong whose 95% interval of speed lies wholly above theirs (runs "
           "whose intervals overlap tie and both stay: tie names the one with the higher median). " +
           embree_speed_caption(ok), "",
           "| scene | method | test | vertices | triangles kept | Mrays/s [95% interval] | × Embree [95% interval] | "
           "wrong per million | tie |",
           "|---|---|---|---|---|---|---|---|---|"]
    for scene, g in ok.groupby("scene"):
        for r, tied in pareto(g):
            tie = "" if tied is None else \
                f"with {run_text(tied).replace(' |', ',')}: {with_interval(tied.kernel_mrays_s, speed_interval(tied), num)}"
            out.append(f"| {scene} | {run_text(r)} | {with_interval(r.kernel_mrays_s, speed_interval(r), num)} | "
                       f"{with_interval(r.speed_ratio_vs_embree1, interval_of(r, 'speed_ratio'), lambda v: num(v, 2))} | "
                       f"{num(r.exact_wrong_ppm)} | {tie} |")
    out.append("")
    summary = []
    for scene, g in ok.groupby("scene"):
        full = g[g.scene_simplify_ratio.isna() & (g.intersection_vertex_bits == 32)]
        summary.append(f"{scene}: " + ", ".join(f"{test} {span(t.exact_wrong_ppm.min(), t.exact_wrong_ppm.max())}"
                                                for test, t in full.groupby("intersection_test")) +
                       f", Embree {span(full.embree_exact_wrong_ppm.min(), full.embree_exact_wrong_ppm.max())}")
        line = f"- {scene}, float vertices, all triangles: " + "; ".join(
            f"{test} {span(t.exact_wrong_ppm.min(), t.exact_wrong_ppm.max())} wrong per million"
            for test, t in full.groupby("intersection_test")) + \
            f"; Embree {span(full.embree_exact_wrong_ppm.min(), full.embree_exact_wrong_ppm.max())} (over " \
            f"{plural(len(full), 'run')}: structures and resolutions)."
        out.append(line)
        simplified = g[g.scene_simplify_ratio.notna()]
        if not simplified.empty:
            enough = simplified[simplified.exact_wrong_ppm <= 1000]
            if not enough.empty:
                r = enough.loc[enough.scene_triangles.idxmin()]
                out.append(f"- {scene} simplified: {count(r.scene_triangles)} triangles "
                           f"({num(100 * r.scene_simplify_ratio)}% kept) are the fewest with at most 0.1% wrong pixels "
                           f"({num(r.exact_wrong_ppm)} per million).")
    out.append("")
    headline("accuracy", "How exact is each ray–triangle test?", "rays wrong per million, full scenes: " + "; ".join(summary),
             context)
    out += charts("accuracy", {"speed_vs_accuracy": "speed against accuracy, per scene",
                               "vertex_precision": "accuracy against vertex bandwidth",
                               "simplification": "accuracy and speed against triangles kept"})
    return out + [""]


def raytypes() -> list:
    runs, context = load("raytypes")
    ok = runs[runs.status == "ok"].copy()
    ok["method"] = structure_names(ok.structure_type) + " / " + ok.strategy_type
    out = ["### `results/raytypes/`: rays after the first hit (Purcell Table 3, Christen Fig. 6.11)", "",
           provenance("raytypes", runs, context), "",
           "Full tables: [`results/raytypes/tables.md`](results/raytypes/tables.md). A frame's GPU time for shadow rays "
           "(any hit) and for the first and last reflection iteration, against the camera rays' on the same scene and "
           "method; early termination as the same shadow rays' closest-hit time over their any-hit time; SIMD "
           "efficiency of the camera rays and of the last iteration's (Purcell's measure for every strategy: the "
           "stream's rays doing useful work per step or pass, misses included). Each ratio is of two runs' medians (separate runs of one sweep, so no interval; "
           "`timing_warning` flags most of them as noisy on this machine): read them to a first digit. Purcell's "
           "shadow caster: 0.85 × ray casting's instructions, 1.15 × its bandwidth.", "",
           "| scene | method | shadow × primary | closest / any | reflection 1 × primary | last iteration | its × primary | "
           "SIMD eff. (Purcell) primary → last |", "|---|---|---|---|---|---|---|---|"]
    for (scene, method), g in ok.groupby(["scene", "method"]):
        primary = g[g.rays_type == "primary"]
        shadow_any = g[(g.rays_type == "shadow") & (g["query"] == "any")]
        shadow_closest = g[(g.rays_type == "shadow") & (g["query"] == "closest")]
        reflection = g[g.rays_type == "reflection"].sort_values("reflection_iteration")
        if primary.empty or shadow_any.empty or shadow_closest.empty or reflection.empty:
            continue
        base = primary.kernel_ms_median.iloc[0]
        last = reflection.iloc[-1]
        out.append(f"| {scene} | {method} | {num(shadow_any.kernel_ms_median.iloc[0] / base, 2)} | "
                   f"{num(shadow_closest.kernel_ms_median.iloc[0] / shadow_any.kernel_ms_median.iloc[0], 2)} | "
                   f"{num(reflection.kernel_ms_median.iloc[0] / base, 2)} | {count(last.reflection_iteration)} | "
                   f"{num(last.kernel_ms_median / base, 2)} | {num(100 * primary.simd_efficiency_purcell.iloc[0], 3)}% → "
                   f"{num(100 * last.simd_efficiency_purcell, 3)}% |")
    out.append("")
    diffuse = []
    for (scene, method), g in ok.groupby(["scene", "method"]):
        primary = g[g.rays_type == "primary"]
        path = g[g.rays_type == "path"].sort_values("path_bounce") if "path_bounce" in g else g.iloc[0:0]
        ao = g[g.rays_type == "ao"]
        if primary.empty or path.empty or ao.empty:
            continue
        base = primary.kernel_ms_median.iloc[0]
        last = path.iloc[-1]
        lanes = " → ".join(f"{num(100 * v, 3)}%" for v in [primary.simd_efficiency_purcell.iloc[0]] + list(path.simd_efficiency_purcell))
        diffuse.append(f"| {scene} | {method} | {num(path.kernel_ms_median.iloc[0] / base, 2)} | {count(last.path_bounce)} | "
                       f"{num(last.kernel_ms_median / base, 2)} | {lanes} | {num(ao.kernel_ms_median.iloc[0] / base, 2)} | "
                       f"{count(ao.rays.iloc[0])} | {count(sum(ok.shading_device_mismatches.fillna(0)))} |")
    if diffuse:
        out += ["Diffuse rays, in the same frame of reference: path-tracing bounce 1 and the last bounce against the camera "
                "rays (one path per pixel), SIMD efficiency from the camera rays through each bounce, ambient occlusion "
                "(4 any-hit rays per camera hit) against the camera rays; the last column counts the rays, over every run "
                "of the folder, that the device's shading passes made other than the CPU's.", "",
                "| scene | method | path bounce 1 × primary | last bounce | its × primary | SIMD eff. (Purcell) primary → bounces | "
                "ao × primary | ao rays | shading mismatches (all runs) |", "|---|---|---|---|---|---|---|---|---|"] + diffuse + [""]
    frames = whitted_frames(ok)
    if not frames.empty:
        out += ["Whitted ray tracing in `scenes/whitted_room.toml` (scene B as a half-silvered mirror, three glass spheres, "
                "a diffuse cow, two lights): a frame to depth D (the camera rays, generations 1..D of reflections and "
                "refractions and the shadow rays of generations 0..D, each batch a run) against the camera rays' alone "
                f"(× time (Embree's): the same for {embree_on(ok)}, rtcOccluded1 for the shadow rays, on the same rays); "
                "Purcell's Whitted ray tracer on the bunny, depth not given: 2.62 × ray casting's instructions, 3.00 × "
                "its bandwidth.", "",
                "| method | depth | rays | × rays | × time | × bytes | × time (Embree's) | SIMD eff. (Purcell) of the reflections and "
                "refractions | rays wrong |", "|---|---|---|---|---|---|---|---|---|"]
        out += [f"| {f.method} | {f.depth} | {count(f.rays)} | {num(f.rays_x, 2)} | {num(f.time_x, 2)} | "
                f"{num(f.bytes_x, 2)} | {num(f.embree_x, 2)} | "
                f"{'—' if pd.isna(f.secondary_simd) else num(100 * f.secondary_simd, 3) + '%'} | {count(f.wrong)} |"
                for f in frames.itertuples()] + [""]
    out += charts("raytypes", {"raytypes_cost": "a frame's cost by ray type against the camera rays'",
                               "raytypes_iterations": "time against reflection iterations, and SIMD efficiency by iteration and bounce"})
    return out + [""]


def strategies() -> list:
    runs, context = load("strategies")
    ok = runs[runs.status == "ok"].copy()
    ok["structure"] = structure_names(ok.structure_type)
    if "strategy_control" not in ok:
        ok["strategy_control"] = "host"
    ok["strategy"] = [r.strategy_type + (f" {r.strategy_schedule}" if r.strategy_type == "megakernel" else
                                         (" on device" if r.strategy_control == "device" else "") +
                                         f" K={count(r.strategy_traverse_steps_per_pass)} M={count(r.strategy_intersections_per_pass)}"
                                         if r.strategy_type == "multipass" else "") for r in ok.itertuples()]
    branching = ok[ok.strategy_type == "branching"].set_index("structure").run
    samples = read_samples(folder_of("strategies"))
    ratios = {r.run: round_ratios(samples, r.run, branching.get(r.structure)) for r in ok.itertuples()}
    failed = runs[runs.status != "ok"]
    out = ["### `results/strategies/`: execution strategies", "", provenance("strategies", runs, context), "",
           "Full table: [`results/strategies/tables.md`](results/strategies/tables.md). The bunny at "
           f"{size(ok.iloc[0]) if len(ok) else '?'}; the runs were timed in interleaved rounds, one repetition of each per "
           "round: × branching is each round's ratio of the strategy's time to branching's, their median and range. "
           "SIMD eff.: Purcell's "
           "measure for every strategy (the stream's rays doing useful work per step, misses included; a whole-traversal "
           "kernel run in lock step one step or test at a time); lane util.: lanes that take a step over lanes (ballots).", "",
           "| structure | strategy | GPU ms | × branching | its range | SIMD eff. (Purcell) | lane util. | "
           "state executions (megakernel) |", "|---|---|---|---|---|---|---|---|"]
    per_structure = {}
    for r in ok[ok.strategy_type != "branching"].itertuples():
        if len(ratios[r.run]):
            per_structure.setdefault(r.structure, []).append((ratios[r.run].median(), r.strategy))
    headline("strategies", "Which execution strategy, against one branching kernel?",
             "time × branching's, round by round (median): " + "; ".join(
                 f"{structure}: {min(v)[1]} {num(min(v)[0], 2)} to {max(v)[1]} {num(max(v)[0], 2)}"
                 for structure, v in sorted(per_structure.items())), context)
    for r in ok.sort_values(["structure", "strategy"]).itertuples():
        executions = "" if r.strategy_type != "megakernel" else \
            f"{count(r.megakernel_runs_traverse)} + {count(r.megakernel_runs_intersect)}"
        out.append(f"| {r.structure} | {r.strategy} | {num(r.kernel_ms_median)} | "
                   f"{num(ratios[r.run].median(), 2)} | "
                   f"{'' if r.strategy_type == 'branching' else span(ratios[r.run].min(), ratios[r.run].max())} | "
                   f"{'' if pd.isna(r.simd_efficiency_purcell) else num(r.simd_efficiency_purcell)} | "
                   f"{'' if pd.isna(r.simd_lane_utilisation) else num(r.simd_lane_utilisation)} | {executions} |")
    if len(failed):
        out += ["", "Failed (each a row with its reason in `error`): " + "; ".join(
            f"{r.structure_type} {r.strategy_type}: {str(r.error).split(' (first:')[0]}" for r in failed.itertuples()) + "."]
    out += [""] + charts("strategies", {"strategies": "GPU time against SIMD efficiency, every strategy"})
    return out + [""]


def multipass_device() -> list:
    """Multipass within 2x of branching (the aim, issue 47 §3), as the ratio of each round's two times: the
    runs were timed in interleaved rounds, so round r of every run saw the same machine."""
    name = "multipass_device"
    if not (folder_of(name) / "samples.csv").exists():
        return []
    runs, context = load(name)
    ok = runs[runs.status == "ok"].copy()
    branching, multipass = ok[ok.strategy_type == "branching"], ok[ok.strategy_type == "multipass"]
    if branching.empty:
        return []
    base = branching.iloc[0].run
    samples = read_samples(folder_of(name))
    rounds = len(round_times(samples, base))
    if not rounds:
        return []
    out = [f"### `results/{name}/`: GPU-resident multipass against branching", "", provenance(name, runs, context),
           "", f"The bunny at {size(ok.iloc[0])}, grid min_dim {count(ok.iloc[0].structure_min_dim)}; multipass with K = "
           f"{count(multipass.strategy_traverse_steps_per_pass.max())}, M = "
           f"{count(multipass.strategy_intersections_per_pass.max())} and its oracle on the "
           "device (compacted ray lists). The runs were timed in interleaved rounds, one repetition of each per round: "
           "× branching is each round's ratio of the two times, its median and range over the "
           f"{rounds} rounds. The aim: multipass within 2× of branching's time (issue 47 §3; within 4× before).", "",
           "| run | list partitions | GPU ms (median of rounds) | × branching: median | range |", "|---|---|---|---|---|"]
    device_ratios = [round_ratios(samples, r.run, base).median() for r in multipass.itertuples()]
    device_ratios = [x for x in device_ratios if pd.notna(x)]
    if device_ratios:
        headline(name, "Multipass with its oracle on the device: how close to branching?",
                 f"{span(min(device_ratios), max(device_ratios))}× branching's time (median of {rounds} interleaved rounds)",
                 context)
    for r in ok.itertuples():
        ratio = round_ratios(samples, r.run, base)
        if not len(ratio):
            continue
        partitions = "" if r.strategy_type != "multipass" else "1" if pd.isna(getattr(r, "strategy_list_partitions", None)) \
            else count(r.strategy_list_partitions)  # before schema 20: one list per state
        out.append(f"| {r.sweep} | {partitions} | {num(round_times(samples, r.run).median())} | "
                   f"{num(ratio.median(), 3) if r.strategy_type != 'branching' else ''} | "
                   f"{span(ratio.min(), ratio.max()) if r.strategy_type != 'branching' else ''} |")
    if "strategy_list_partitions" in multipass and multipass.strategy_list_partitions.nunique() == 2:
        one, more = (multipass.sort_values("strategy_list_partitions").iloc[i] for i in (0, 1))
        ratio = round_ratios(samples, more.run, one.run)
        out += ["", f"Multipass with {count(more.strategy_list_partitions)} list partitions over {count(one.strategy_list_partitions)}, "
                f"round by round: median {num(ratio.median(), 3)}, range {span(ratio.min(), ratio.max())}."]
    out += [""] + charts(name, {"kernel_time": "multipass GPU time by kernel",
                                "bandwidth_by_category": "bytes by data type, the ray lists included"})
    return out + [""]


def wavefront() -> list:
    runs, context = load("wavefront")
    ok = runs[runs.status == "ok"].copy()
    ok["structure"] = structure_names(ok.structure_type)
    ok["k"] = [int(r.reflection_iteration) if r.rays_type == "reflection" else int(r.path_bounce) if r.rays_type == "path"
               else 0 for r in ok.itertuples()]
    out = ["### `results/wavefront/`: whole paths on the device", "", provenance("wavefront", runs, context), "",
           "Full table: [`results/wavefront/tables.md`](results/wavefront/tables.md). A path from the camera rays to its "
           "deepest generation k (reflection iteration or path bounce), every generation traced on the device with no "
           "host round trip: the wavefront (a kernel per stage over stable, compacted queues) and the path megakernel "
           "(one invocation per camera ray's whole path); host: branching's runs of each generation as a batch of its "
           "own, their medians summed: the trace alone (the shading passes that made each generation are timed apart, "
           "`shading_ms`, and not added; the host's round trips are not timed). Megakernel ÷ wavefront: the ratio of two "
           "runs' medians (no interval); ranked: by the two runs' 95% intervals of GPU time, a tie where they overlap. "
           + embree_speed_caption(ok) + " The same rays: those of every generation.", "",
           "| scene | rays | k | structure | rays traced | host ms (trace only: no shading, no round trips) | wavefront ms | "
           "megakernel ms | megakernel ÷ wavefront | ranked | wavefront × Embree [95% interval] | "
           "lane util. (wavefront batch / megakernel) |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    whole = ok[ok.strategy_type.isin(["wavefront", "path_megakernel"]) & (ok.rays_type != "primary")]
    over, ranked = [], []  # megakernel / wavefront, and the intervals' verdict, per row
    for (scene, kind, structure), g in whole.groupby(["scene", "rays_type", "structure"]):
        k = g.k.max()
        w = g[(g.k == k) & (g.strategy_type == "wavefront")]
        m = g[(g.k == k) & (g.strategy_type == "path_megakernel")]
        b = ok[(ok.strategy_type == "branching") & (ok.scene == scene) & (ok.structure == structure) &
               (((ok.rays_type == kind) & (ok.k <= k)) | (ok.rays_type == "primary"))]
        if w.empty or m.empty or len(b) != k + 1:
            continue
        w, m = w.iloc[0], m.iloc[0]
        over.append(m.kernel_ms_median / w.kernel_ms_median)
        ranked.append(faster_of(w, m, ("wavefront", "megakernel")))
        out.append(f"| {scene} | {kind} | {k} | {structure} | {count(w.whole_path_rays)} | {num(b.kernel_ms_median.sum())} | "
                   f"{num(w.kernel_ms_median)} | {num(m.kernel_ms_median)} | {num(m.kernel_ms_median / w.kernel_ms_median, 2)} | "
                   f"{ranked[-1]} | {with_interval(w.speed_ratio_vs_embree1, interval_of(w, 'speed_ratio'), lambda v: num(v, 2))} | "
                   f"{num(w.simd_lane_utilisation)} / "
                   f"{num(m.simd_lane_utilisation)} |")
    if over:
        headline("wavefront", "Whole paths on the device: wavefront or one megakernel?",
                 f"the path megakernel takes {span(min(over), max(over))}× the wavefront's time (two runs' medians; "
                 f"ranked by their 95% intervals: {verdict_counts(ranked, 'paths')})", context)
    out += [""] + charts("wavefront", {"wavefront": "GPU time per ray traced against the generations of the path"})
    return out + [""]


def ratio_cell(by_key, key) -> str:
    """A × Embree cell of the run at `key` of `by_key`: its speed_ratio_vs_embree1 and 95% interval, † where
    the noise guard flagged it (`timing_warning`); "—" where no run has that key."""
    if key not in by_key.index:
        return "—"
    r = by_key.loc[key]
    flagged = " †" if isinstance(r.get("timing_warning"), str) and r.timing_warning else ""
    return f"{num(r.speed_ratio_vs_embree1)} {interval(r.speed_ratio_ci_low, r.speed_ratio_ci_high)}{flagged}"


def division() -> list:
    runs, context = load("division")
    ok = runs[runs.status == "ok"].copy()
    ok["structure"] = structure_names(ok.structure_type)
    ok["kernel"] = ["plain" if t == "plain" else d for t, d in zip(ok.strategy_type, division_names(ok))]
    by_kernel = ok.set_index(["structure", "rays", "kernel"])
    ratio = by_kernel.speed_ratio_vs_embree1
    out = ["### `results/division/`: what bit-exact division costs", "", provenance("division", runs, context),
           "", "Full table: [`results/division/tables.md`](results/division/tables.md). The bunny, the branching kernel "
           "dividing exactly through 32-bit integer products (`intersection.division = \"integer\"`: no double on the "
           "common path) or a double quotient (`\"double\"`, the default), and its plain twin dividing as the device does "
           "(`OpFDiv`); each is its speed over Embree rtcIntersect1's on the same rays in the same run, so a ratio "
           "between two of them is a ratio of ratios. Each cell: the median ratio and its 95% interval (order statistics "
           "from results schema 23 on, a percentile bootstrap before); † a "
           "run the noise guard flagged (`timing_warning`). " + embree_speed_caption(ok), "",
           "| structure | rays | × Embree: integer | double | plain | integer / double | integer / plain |",
           "|---|---|---|---|---|---|---|"]

    over_plain = [ratio.get((st, n, "integer"), float("nan")) / ratio.get((st, n, "plain"), float("nan"))
                  for (st, n), _ in ok.groupby(["structure", "rays"])]
    over_plain = [x for x in over_plain if pd.notna(x)]
    if over_plain:
        headline("division", "What does bit-exact division cost?",
                 f"exact integer division runs at {span(min(over_plain), max(over_plain))}× the speed of its plain twin "
                 "(device division; ratios of Embree ratios)", context)
    for (structure, rays), _ in ok.groupby(["structure", "rays"]):
        get = lambda kernel: ratio.get((structure, rays, kernel), float("nan"))
        out.append(f"| {structure} | {count(rays)} | {ratio_cell(by_kernel, (structure, rays, 'integer'))} | {ratio_cell(by_kernel, (structure, rays, 'double'))} | "
                   f"{ratio_cell(by_kernel, (structure, rays, 'plain'))} | {num(get('integer') / get('double'), 3)} | "
                   f"{num(get('integer') / get('plain'), 3)} |")
    return out + [""]


def control() -> list:
    if not (folder_of("control") / "runs.csv").exists():
        return []
    runs, context = load("control")
    ok = runs[runs.status == "ok"].copy()
    ok["structure"] = structure_names(ok.structure_type)
    tiled = ok.camera_tile.fillna(0) > 0 if "camera_tile" in ok else pd.Series(False, index=ok.index)
    ok["kernel"] = [f"{t} tiles" if tile else t for t, tile in zip(ok.strategy_type, tiled)]
    by_kernel = ok.set_index(["structure", "rays", "kernel"])
    ratio = by_kernel.speed_ratio_vs_embree1
    kernels = ["branching", "branching tiles", "plain", "control"]
    out = ["### `results/control/`: what the branching kernel's generality costs", "", provenance("control", runs, context),
           "", "The bunny at Purcell's min_dim 64 (grid) and over the BVH. The control (`strategy.type = \"control\"`) is a "
           "plain grid ray caster of the branching kernel's walk and test that makes its camera rays itself in 8×8 pixel "
           "tiles, writes 8 bytes a ray, divides as the device does and counts nothing; \"branching tiles\" is the "
           "branching kernel fed its rays in 8×8 tiles (`camera.tile = 8`), \"plain\" its twin dividing as the device "
           "does. Each cell: the speed over Embree rtcIntersect1's on the same rays in the same run, the median and its "
           "95% interval; † a run the noise guard flagged (`timing_warning`); a ratio between two columns is a ratio of "
           "ratios. " + embree_speed_caption(ok), "",
           "| structure | rays | × Embree: " + " | ".join(kernels) + " | branching / control |",
           "|---|---|" + "---|" * (len(kernels) + 1)]

    over_control = []
    for (structure, rays), _ in ok.groupby(["structure", "rays"]):
        share = ratio.get((structure, rays, "branching"), float("nan")) / ratio.get((structure, rays, "control"), float("nan"))
        if pd.notna(share):
            over_control.append(share)
        out.append(f"| {structure} | {count(rays)} | " + " | ".join(ratio_cell(by_kernel, (structure, rays, k)) for k in kernels) +
                   f" | {num(share, 3)} |")
    if over_control:
        headline("control", "Is the branching kernel as fast as a plain one?",
                 f"over the grid it runs at {span(min(over_control), max(over_control))}× the speed of the control, a "
                 "plain ray caster of the same walk (ratios of Embree ratios, 512²–2048²)", context)
    return out + [""]


RAY_TYPES = {"primary": "camera", "shadow": "shadow", "path": "diffuse (path's first bounce)"}


def ray_type_header(types) -> list:
    """The head of a driver table: a row per scene and kernel, a column per ray type."""
    return ["| scene | kernel | " + " | ".join(RAY_TYPES[t] for t in types) + " |", "|---|---|" + "---|" * len(types)]


def driver_kernels(runs):
    """results/driver's ok runs, each named by its kernel ("driver's ray query", "grid 64, branching") and
    its lavapipe's Mesa ("25.0.7", from the driver text)."""
    ok = runs[runs.status == "ok"].copy()
    ok["kernel"] = ["driver's ray query" if r.structure_type == "driver" else f"{method_name(r)}, {r.strategy_type}"
                    for _, r in ok.iterrows()]
    ok["mesa"] = ok.driver.str.extract(r"Mesa (\d+\.\d+\.\d+)", expand=False)
    return ok


def driver_table(ok) -> tuple:
    """The newer Mesa's table (a row per scene and kernel, a × Embree cell per ray type, then the driver's ray
    query over the fastest rtbench kernel's median) and those quotients."""
    by_key = ok.set_index(["scene", "kernel", "rays_type"])
    types = [t for t in RAY_TYPES if t in set(ok.rays_type)]
    out = ray_type_header(types)
    quotients = []
    for scene, g in ok.groupby("scene", sort=False):
        for kernel in dict.fromkeys(g.kernel):
            out.append(f"| {scene} | {kernel} | " + " | ".join(ratio_cell(by_key, (scene, kernel, t)) for t in types) + " |")
        cells = []
        for t in types:
            theirs = g[(g.rays_type == t) & (g.structure_type == "driver")].speed_ratio_vs_embree1
            ours = g[(g.rays_type == t) & (g.structure_type != "driver")]
            if theirs.empty or ours.empty:
                cells.append("—")
                continue
            best = ours.loc[ours.speed_ratio_vs_embree1.idxmax()]
            quotients.append(theirs.iloc[0] / best.speed_ratio_vs_embree1)
            cells.append(f"{num(quotients[-1], 3)} (of {best.kernel})")
        out.append(f"| {scene} | driver / fastest rtbench kernel | " + " | ".join(cells) + " |")
    return out, quotients


def driver_builds(ok) -> list:
    """Build times per scene: the driver's acceleration structure (on the device), rtbench's grid and BVH
    and Embree's BVH (on the CPU); medians over the scene's runs."""
    out = ["| scene | driver's structure (device) ms | grid 64 ms | rtbench BVH ms | Embree BVH ms |", "|---|---|---|---|---|"]
    for scene, g in ok.groupby("scene", sort=False):
        build = lambda kind: g[g.structure_type == kind].structure_build_ms.median()
        out.append(f"| {scene} | {num(build('driver'), 3)} | {num(build('uniform_grid'), 3)} | {num(build('bvh'), 3)} | "
                   f"{num(g.embree_build_ms.median(), 3)} |")
    return out


def driver_versions(ok, old: str, new: str) -> tuple:
    """rtbench's kernels on the older lavapipe and on the newer, in the same rounds: each cell the × Embree
    medians, then their quotient (new over old), and those quotients."""
    mine = ok[ok.structure_type != "driver"]
    indexed = mine.set_index(["mesa", "scene", "kernel", "rays_type"])
    by = indexed.speed_ratio_vs_embree1
    spans = {key: interval_of(r, "speed_ratio") for key, r in indexed.iterrows()}
    types = [t for t in RAY_TYPES if t in set(mine.rays_type)]
    out = ray_type_header(types)
    quotients = []
    for (scene, kernel), _ in mine.groupby(["scene", "kernel"], sort=False):
        cells = []
        for t in types:
            if (old, scene, kernel, t) not in by.index or (new, scene, kernel, t) not in by.index:
                cells.append("—")
                continue
            before, after = by[(old, scene, kernel, t)], by[(new, scene, kernel, t)]
            quotients.append(after / before)
            low, high = spans[(old, scene, kernel, t)], spans[(new, scene, kernel, t)]
            tie = " ~" if not low or not high or (low[1] >= high[0] and high[1] >= low[0]) else ""
            cells.append(f"{num(before)} → {num(after)} ({num(quotients[-1], 2)}×{tie})")
        out.append(f"| {scene} | {kernel} | " + " | ".join(cells) + " |")
    return out, quotients


def driver() -> list:
    """results/driver: the driver's ray query on Mesa 25's lavapipe against rtbench's kernels, and what
    the newer Mesa changes for rtbench's kernels against Debian's (both lavapipes in the same rounds)."""
    if not (folder_of("driver") / "runs.csv").exists():
        return []
    runs, context = load("driver")
    ok = driver_kernels(runs)
    versions = sorted(set(ok.mesa.dropna()), key=lambda v: tuple(int(x) for x in v.split(".")))
    if not versions:
        return []
    new, old = versions[-1], versions[0]
    table, quotients = driver_table(ok[ok.mesa == new])
    judged = ok[ok.structure_type == "driver"]
    failed = runs[runs.status != "ok"]
    out = ["### `results/driver/`: the driver's ray query as a peer, and what Mesa 25's lavapipe changes", "",
           provenance("driver", runs, context), "",
           "`configs/driver.toml`: the driver's `VK_KHR_ray_query` over its own acceleration structure "
           "(`structure.type = \"driver\"`, `strategy.type = \"ray_query\"`) against rtbench's branching kernel, "
           "persistent threads and the megakernel over the grid (min_dim 64) and the BVH, on the same rays. Debian 12's "
           f"lavapipe (Mesa {old}) lacks the extension; Mesa {new}'s lavapipe, from bookworm-backports, has it "
           "(`scripts/setup.sh` unpacks it into the build folder, `VK_ADD_DRIVER_FILES` names it to the loader, "
           "`device.name` picks a lavapipe by its driver's Mesa version). Both ran in the same process, their runs "
           "interleaved round by round. " + (f"{plural(len(failed), 'run')} failed: {reasons(failed.error)}. " if len(failed) else "") +
           f"The table is Mesa {new}'s. Each cell: the speed over Embree rtcIntersect1's on the same rays in the same "
           "run, the median and its 95% interval; † a run the noise guard flagged (`timing_warning`). The last row of "
           "each scene: the driver's median over the fastest rtbench kernel's, a ratio of ratios. The exact reference "
           f"judged every run: the driver's ray query got {count(int(wrong_rays(judged).fillna(0).sum()))} of "
           f"{count(judged.rays.sum())} rays wrong (false hits, false misses, other triangles), rtbench's kernels "
           f"{count(int(wrong_rays(ok[ok.structure_type != 'driver']).fillna(0).sum()))}. " + embree_speed_caption(ok), ""]
    out += table + ["", "Build times (medians over each scene's runs):", ""] + driver_builds(ok[ok.mesa == new])
    if quotients:
        headline("driver", "How fast is the driver's own ray query (Mesa 25's lavapipe)?",
                 f"{span(min(quotients), max(quotients))}× the speed of rtbench's fastest kernel on the same rays, "
                 "per scene and ray type (ratios of Embree ratios)", context)
    if old != new:
        rows, changes = driver_versions(ok, old, new)
        out += ["", f"What Mesa {new} changes for rtbench's kernels: each cell their × Embree median on Mesa {old} → on "
                f"Mesa {new}, and the newer's over the older's (a ratio of ratios, both timed in the same rounds); ~ where the "
                "two 95% intervals overlap or one has none (not ranked).", ""] + rows
        if changes:
            ties = sum(row.count(" ~)") for row in rows)
            out += ["", f"Over the {len(changes)} kernels and ray types, Mesa {new}'s ratio over Mesa {old}'s spans "
                    f"{span(min(changes), max(changes))}× (median {num(pd.Series(changes).median(), 2)}×); "
                    f"{len(changes) - ties} of the {len(changes)} with separated intervals, {ties} not ranked."]
    return out + [""]


def build_span(r):
    """A run's build ratio interval (low, high), None where it has none (fewer than 7 build rounds)."""
    return interval_of(r, "build_ratio", samples="build_rounds")


def build_verdict(r) -> str:
    """A build ratio against 1 by its 95% interval: "≤ Embree" wholly at or below, "> Embree" wholly
    above, "tie" across, "not ranked" without one."""
    span = build_span(r)
    if not span:
        return "not ranked"
    return "≤ Embree" if span[1] <= 1 else "> Embree" if span[0] > 1 else "tie"


def builds() -> list:
    """results/builds: the grid's and rtbench's BVH's builds against Embree's BVH build, in paired rounds."""
    if not (folder_of("builds") / "runs.csv").exists():
        return []
    runs, context = load("builds")
    ok = runs[(runs.status == "ok") & (runs.build_rounds > 0)].copy()
    if ok.empty:
        return []
    ok["what"] = [f"grid {int(r.structure_min_dim)}" if r.structure_type == "uniform_grid" else "rtbench BVH" for _, r in ok.iterrows()]
    rounds = int(ok.build_rounds.max())
    out = ["### `results/builds/`: how long does a structure take to build, against Embree's BVH?", "",
           provenance("builds", runs, context), "",
           f"`configs/builds.toml`: each structure built {rounds} times more after its run's own build, alternately with "
           f"Embree's BVH of the same triangles (`experiment.build_rounds`; every build in `samples.csv`). Each cell: the "
           "median build in ms; the ratio is the structure's median over Embree's, with its 95% interval (each median's "
           "97.5% order-statistic interval); the verdict places that interval against 1. The grid bins on TBB's "
           f"threads, Embree builds on its own ({int(ok.embree_threads.iloc[0])}, `embree_threads`). rtbench's BVH is "
           "built by Embree's `rtcBuildBVH` on a device of its own, whose creation and release its time includes; "
           "Embree's BVH reuses the run's device.", "",
           "| scene (triangles) | structure | cells | references | build ms | Embree BVH ms | ratio [95%] | verdict |",
           "|---|---|---|---|---|---|---|---|"]
    for _, r in ok.sort_values(["scene_triangles", "structure_type", "structure_min_dim"], ascending=[True, False, True]).iterrows():
        grid = r.structure_type == "uniform_grid"
        out.append(f"| {r.scene} ({count(r.scene_triangles)}) | {r.what} | {count(r.grid_cells) if grid else '—'} | "
                   f"{count(r.grid_references) if grid else count(r.bvh_references)} | {num(r.structure_build_ms_median)} | "
                   f"{num(r.embree_build_ms_median)} | {num(r.build_ratio_vs_embree)} {interval(*build_span(r)) if build_span(r) else '—'} | "
                   f"{build_verdict(r)} |")
    target = ok[(ok.structure_type == "uniform_grid") & (ok.scene_triangles >= 50000) & (ok.structure_min_dim <= 64)]
    verdicts = [build_verdict(r) for _, r in target.iterrows()]
    slower = target[[v == "> Embree" for v in verdicts]]
    worst = slower.loc[slower.build_ratio_vs_embree.idxmax()] if not slower.empty else None
    failed = runs[runs.status != "ok"]
    out += ["", f"Issue 47's target, the grid's build at most Embree's on the scenes of 50,000 triangles and more at "
            f"min_dim ≤ 64: {verdicts.count('≤ Embree')} of {len(verdicts)} at most Embree's, {verdicts.count('tie')} tied, "
            f"{verdicts.count('> Embree')} slower" + (f" (the slowest of those: {worst.scene} at min_dim {int(worst.structure_min_dim)}, "
            f"{num(worst.build_ratio_vs_embree)}×)" if worst is not None else "") + "." +
            (f" {plural(len(failed), 'run')} failed: {reasons(failed.error)}." if len(failed) else "")]
    grids = ok[ok.structure_type == "uniform_grid"]
    growth = []
    for scene, g in grids.groupby("scene", sort=False):
        if len(g) > 1:
            lo, hi = g.loc[g.grid_cells.idxmin()], g.loc[g.grid_cells.idxmax()]
            growth.append(f"{scene} {num(hi.grid_cells / lo.grid_cells, 2)}× the cells and {num(hi.grid_references / lo.grid_references, 2)}× "
                          f"the references, {num(hi.structure_build_ms_median / lo.structure_build_ms_median, 2)}× the time")
    if growth:
        out += ["", f"How the grid's build grows from min_dim {int(grids.structure_min_dim.min())} to its finest: " + "; ".join(growth) + "."]
    if verdicts:
        headline("builds", "Does the grid build as fast as Embree's BVH?",
                 f"{verdicts.count('≤ Embree')} of {len(verdicts)} grids (≥ 50,000 triangles, min_dim ≤ 64) at most Embree's build "
                 f"time by their 95% intervals, {verdicts.count('tie')} tied, {verdicts.count('> Embree')} slower" +
                 (f" (up to {num(worst.build_ratio_vs_embree)}×, {worst.scene} at {int(worst.structure_min_dim)})" if worst is not None else ""),
                 context)
    out += [""] + charts("builds", {"build_times": "the grid's build against its cells beside Embree's, and their ratio"})
    return out + [""]


def fastest_grid(g) -> tuple:
    """The grid size whose 95% interval of time lies wholly below every other's, in full ("10³ (3.51 ms
    [2.9, 4.59])") and short ("10³"); else the tie ("tie: 10³ [2.9, 4.59], 20³ [3.9, 5.23]", "tie of 10³,
    20³") or "no interval: not ranked"."""
    leading = leaders(g)
    name = lambda r: f"{count(r.grid_res_x)}³"
    if leading and len(leading) == 1:
        r = leading[0]
        return f"{name(r)} ({num(r.kernel_ms_median)} ms {interval(r.kernel_ms_ci_low, r.kernel_ms_ci_high)})", name(r)
    short = "tie of " + ", ".join(name(r) for r in leading) if leading else "not ranked"
    return ranked_text(leading, name, num), short


def device_of(context) -> str:
    return context["devices"][0].get("name", "?") if context.get("devices") else "?"


def christen2005() -> list:
    if not folder_of("christen2005").exists():
        return []
    runs, context = load("christen2005")
    ok = runs[runs.status == "ok"].copy()
    out = ["### `results/christen2005/`: Christen 2005's benchmarks (§6.2)", "",
           provenance("christen2005", runs, context), "",
           "Full tables: [`results/christen2005/tables.md`](results/christen2005/tables.md). His scenes A, B (Table 6.1's "
           "2,064 triangles) and C at 256×256 over a uniform grid: his multipass (K = M = 1, oracle 20%, the host in "
           "control), the branching kernel, and host C++ running the same grid traversal on the host's threads "
           f"(`strategy.type = \"cpu\"`). Figs. 6.10-6.11 set {host_against_device(ok, device_of(context))}. "
           "His figures are bitmaps missing from the thesis text: shapes, not numbers, compare. Ranked: by the two runs' "
           "95% intervals of time, a tie where they overlap; the fastest grid: the one whose interval lies wholly below "
           "every other grid's.", ""]
    first = ok[ok.sweep == "fig6_8"]
    if not first.empty:
        out += ["| Fig. 6.8, grid 20×20×20 | multipass ms | branching ms | cpu ms | cpu / branching | ranked |",
                "|---|---|---|---|---|---|"]
        for _, g in first.sort_values("scene_triangles").groupby("scene_triangles"):
            run = {t: g[g.strategy_type == t].iloc[0] for t in ("multipass", "branching", "cpu") if (g.strategy_type == t).any()}
            ms = lambda t: run[t].kernel_ms_median if t in run else float("nan")
            ranked = faster_of(run["cpu"], run["branching"], ("cpu", "branching")) if {"cpu", "branching"} <= set(run) else ""
            out.append(f"| {g.scene.iloc[0]} ({count(g.scene_triangles.iloc[0])} triangles) | {num(ms('multipass'))} | "
                       f"{num(ms('branching'))} | {num(ms('cpu'))} | {num(ms('cpu') / ms('branching'), 2)} | {ranked} |")
    sizes = ok[ok.sweep.isin(["fig6_8", "fig6_9"]) & ok.strategy_type.isin(["multipass", "branching"])]
    if not sizes.empty:
        best = [(f"{scene} {method}", *fastest_grid(g)) for (scene, method), g in sizes.groupby(["scene", "strategy_type"])]
        out += ["", "- **Fig. 6.9**, the fastest grid (10³–60³): " + "; ".join(f"{what}: {full}" for what, full, _ in best) + "."]
        headline("christen2005", "Christen 2005's benchmarks: the fastest grid",
                 "where the 95% intervals separate: " + "; ".join(f"{what}: {short}" for what, _, short in best), context)
    masked = ok[(ok.strategy_type == "multipass") & ok.sweep.isin(["fig6_8", "fig6_11"])]
    if "kernel_ms_stencil_pass" in masked and masked.kernel_ms_stencil_pass.notna().any():
        masked = masked[masked.kernel_ms_stencil_pass.notna()]
        share = masking_share(masked)
        out.append(f"- **§5.5, masking by state**: his early-z culling needed a masking pass before every traverse and "
                   f"intersect pass (twice our loop passes; `passes_total` counts none: our kernels test the state byte "
                   f"themselves). That test alone, timed as one more pass over finished rays, costs "
                   f"{num(masked.kernel_ms_stencil_pass.min())}–{num(masked.kernel_ms_stencil_pass.max())} ms a pass here, "
                   f"{num(100 * share.min())}–{num(100 * share.max())}% of a frame over its loop passes (an upper bound).")
    out += [""] + charts("christen2005", {"christen_grid_size": "render time against grid size (Christen Fig. 6.9)",
                                           "christen_gpu_cpu": f"{host_against_device(ok, device_of(context))}, by "
                                                               "iteration (Christen Figs. 6.10-6.11)"})
    return out + [""]


def trees() -> list:
    if not (folder_of("trees") / "runs.csv").exists():
        return []
    runs, context = load("trees")
    ok = against_sah(runs[runs.status == "ok"])
    out = ["### `results/trees/`: does a worse tree cost multipass more than branching?", "", provenance("trees", runs, context),
           "", "Full table: [`results/trees/tables.md`](results/trees/tables.md). Three BVHs of one layout and one set of "
           f"kernels, leaf size {values_text(ok.structure_leaf_size)}: Embree's binned SAH (`bvh`), its Morton build (`bvh`, `quality = \"low\"`) and the "
           "median split (`median_bvh`, no cost model). Each count over the SAH tree's on the same rays (deterministic): "
           "the tree's SAH cost, inner nodes visited per ray (the same for both strategies), and multipass's passes "
           f"(K = {values_text(ok.strategy_traverse_steps_per_pass)} steps, "
           f"M = {values_text(ok.strategy_intersections_per_pass)} tests a pass). Build times and speeds, single builds and noisy here, are in the full table only.", "",
           "| scene | rays | tree | SAH cost × | nodes/ray × | passes × |", "|---|---|---|---|---|---|"]
    multipass = ok[ok.strategy_type == "multipass"]
    worse = multipass[multipass.tree != "SAH"]
    for r in worse.sort_values(["scene_triangles", "rays_type", "tree"]).itertuples():
        out.append(f"| {r.scene} | {r.rays_type} | {r.tree} | {num(r.bvh_sah_cost_x)} | {num(r.nodes_per_ray_mean_x)} | "
                   f"{num(r.passes_total_x)} |")
    out.append("")
    for tree, g in worse.dropna(subset=["passes_total_x", "nodes_per_ray_mean_x"]).groupby("tree"):
        more = int((g.passes_total_x > g.nodes_per_ray_mean_x).sum())
        out.append(f"- {tree}: multipass's passes grow more than the nodes a ray visits (what branching's work follows) "
                   f"in {more} of {len(g)} scene and ray-type pairs.")
    median = worse[worse.tree == "median split"]
    if len(median):
        headline("trees", "Does a worse tree cost multipass more than branching?",
                 f"the median-split tree visits {span(median.nodes_per_ray_mean_x.min(), median.nodes_per_ray_mean_x.max())}× "
                 f"the SAH tree's nodes per ray, and multipass needs {span(median.passes_total_x.min(), median.passes_total_x.max())}× "
                 "its passes (counts)", context)
    return out + [""]


def order() -> list:
    if not (folder_of("order") / "runs.csv").exists():
        return []
    runs, context = load("order")
    pairs = sorted_beside_branching(runs[runs.status == "ok"])
    out = ["### `results/order/`: what does ray order alone do to the branching kernel?", "", provenance("order", runs, context),
           "", "Full table: [`results/order/tables.md`](results/order/tables.md). The branching kernel over each batch as "
           "it comes and sorted (`strategy.type = \"sorted\"`: the direction's octant, then the origin's Morton code, "
           "Garanzha & Loop 2010; the sort on the host, not in the kernel's time): the same rays, structure and kernel, "
           "so every count but the lanes' is equal. Lanes: SIMD lane utilisation (deterministic); speed: sorted's × "
           "Embree over branching's, faster or slower only where their 95% intervals separate.", "",
           "| scene | rays | structure | lanes | sorted lanes | sorted speed |", "|---|---|---|---|---|---|"]
    verdicts = []
    for r in pairs.sort_values(["triangles", "rays_type", "structure"]).itertuples():
        verdict = speed_verdict(r.sorted_span, r.speed_span)
        verdicts.append(verdict)
        out.append(f"| {r.scene} | {r.rays_type} | {r.structure} | {num(r.lanes)} | {num(r.sorted_lanes)} | {verdict} |")
    secondary = pairs[pairs.rays_type != "primary"]
    if len(secondary):
        gain = secondary.sorted_lanes / secondary.lanes
        counted = ", ".join(f"{verdicts.count(v)} {word}" for v, word in [("faster", "faster"), ("tie", "tied"), ("slower", "slower"),
                                                                        ("not ranked", "not ranked")] if verdicts.count(v))
        out += ["", f"- Secondary rays (reflection, path): sorting multiplies lane utilisation by {span(gain.min(), gain.max())}; "
                f"the host sort takes {span(100 * secondary.sort_share.min(), 100 * secondary.sort_share.max())}% of the sorted "
                f"kernel's time. Speed against branching, all {len(verdicts)} pairs: {counted}."]
        headline("order", "What does sorting rays do to the branching kernel?",
                 f"lane utilisation × {span(gain.min(), gain.max())} on reflection and path rays; speed against unsorted, "
                 f"{len(verdicts)} pairs: {counted}", context)
    return out + [""]


def golden() -> list:
    runs, context = load("golden")
    return ["### `results/golden/`: the counts CI checks", "",
            f"{len(runs)} runs at {size(runs.iloc[0])} rays "
            f"(`configs/golden.toml`: every structure, both strategies and both ray-triangle tests, packed vertices, a "
            f"mesh file), recorded by `{context.get('command', '?')}` at commit `{commit_text(context)}` on "
            f"{context.get('cpu', '?')} with {context['devices'][0]['name']}. CI runs `build/rtbench check "
            f"results/golden` (CTest `cli.check_golden`), and `Golden.ReproducesWithEmbreeForcedToEveryIsaThisCpuRuns` "
            f"again with Embree forced to each ISA the CPU runs.", ""]


def h200() -> list:
    folder = folder_of("nvidia-h200")
    rows = []
    for sub in sorted(p for p in folder.iterdir() if (p / "runs.csv").exists()):
        runs = read_runs(sub)
        reference = runs.error.fillna("").str.contains("differ from the CPU reference")
        rows.append((sub.name, len(runs), int((runs.status != "ok").sum()), int(reference.sum()),
                     reasons(runs[(runs.status != "ok") & ~reference].error)))
    context = json.loads((folder / rows[0][0] / "context.json").read_text()) if rows else {}
    device = context.get("devices", [{}])[0]
    return ["### `results/nvidia-h200/`: the configs of record on an NVIDIA H200, failed, and why", "",
            f"{device.get('name', '?')} ({device.get('driver', '?')}) at commit `{commit_text(context)}`: " +
            "; ".join(f"{name}: {failed} of {n} runs failed, {reference} of them the CPU-reference check" +
                      (f" (the others: {others})" if others else "") for name, n, failed, reference, others in rows) +
            ". Vulkan lets division be off by 2.5 ulp and NVIDIA's driver "
            "uses it; the fix (`rtDivide`, docs/method.md) came after, and no GPU has been lent since to measure it. "
            "[`results/nvidia-h200/README.md`](results/nvidia-h200/README.md) has the details.", ""]


def results_page() -> str:
    """results/README.md: every folder's section, its links relative to results/."""
    HEADLINES.clear()
    out = ["# Results of record", "",
           "<!-- Written by scripts/readme_figures.py from the folders here; the test scripts.readme_figures fails when "
           "this file differs from what it writes. Do not edit. -->", "",
           "Every figure below comes from a `runs.csv` in this folder, and each folder names the machine, device, "
           "command and commit its `context.json` records. Timings are medians with 95% intervals (from the order statistics "
           "from results schema 23 on; a percentile bootstrap in folders recorded before) of the "
           "repetitions of one run (an interval says nothing of the spread between runs in separate processes); a speed "
           "claim is a ratio measured in the same run. Counts (passes, bytes, work, rays wrong) are the same on every "
           "machine with the same device; timings are that machine's. On every table: " + EMBREE_SPEED + ". One method "
           "is called faster than another (or the fastest) only where their 95% intervals do not overlap; where they "
           "overlap it is a tie, given with both intervals; a run without an interval (one timed repetition) is not "
           "ranked.", ""]
    for part in (bunny, structures, builds, purcell2002, stability, accuracy, raytypes, strategies, multipass_device, wavefront, division, control, driver, christen2005, trees, order, golden, h200):
        lines = part()
        if lines:
            ANCHORS[re.search(r"`results/([^`]+)/`", lines[0]).group(1)] = anchor(lines[0].lstrip("# "))
        out += lines
    while out and out[-1] == "":
        out.pop()
    text = "\n".join(out) + "\n"
    return text.replace("](results/", "](").replace("### `results/", "## `results/")


ANCHORS = {}  # folder -> its heading's anchor in results/README.md


def anchor(heading: str) -> str:
    """A Markdown heading's anchor as GitHub makes it: lower case, punctuation dropped, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


def headline_table() -> str:
    """The README's table: a row per folder, from HEADLINES (results_page() fills it)."""
    out = [BEGIN, "",
           "| results | question | headline (medians; intervals and noise flags on the full page) | recorded on |",
           "|---|---|---|---|"]
    for name, (question, text, where) in HEADLINES.items():
        out.append(f"| [`{name}/`](results/README.md#{ANCHORS.get(name, '')}) | {question} | {text} | {where} |")
    return "\n".join(out + ["", END])


def first_config_differs(text: str) -> bool:
    """Whether the README's ```toml block is not configs/first.toml as it is (the test runs that file)."""
    config = (ROOT / "configs" / "first.toml").read_text()
    return f"```toml\n{config}```" not in text


def differs(path: Path, committed: str, new: str) -> bool:
    """Whether the committed text differs from what is written now (the diff printed)."""
    if committed == new:
        return False
    sys.stdout.writelines(difflib.unified_diff(committed.splitlines(True), new.splitlines(True),
                                               f"{path} (committed)", "scripts/readme_figures.py (from results/)"))
    print(f"\n{path} differs from results/: run /usr/bin/python3 scripts/readme_figures.py", file=sys.stderr)
    return True


def main(argv) -> int:
    readme = Path(argv[argv.index("--readme") + 1]) if "--readme" in argv else ROOT / "README.md"
    results = Path(argv[argv.index("--results") + 1]) if "--results" in argv else ROOT / "results" / "README.md"
    text = readme.read_text()
    page = results_page()
    if "--print" in argv:
        print(page, end="")
        return 0
    table = headline_table()
    if BEGIN not in text or END not in text:
        print(f"{readme}: no headline table (the markers {BEGIN} ... {END})", file=sys.stderr)
        return 1
    start, end = text.index(BEGIN), text.index(END) + len(END)
    if "--check" in argv:
        if first_config_differs(text):
            print(f"{readme}: its ```toml block is not configs/first.toml", file=sys.stderr)
            return 1
        committed_page = results.read_text() if results.exists() else ""
        return 1 if differs(readme, text[start:end], table) | differs(results, committed_page, page) else 0
    readme.write_text(text[:start] + table + text[end:])
    results.write_text(page)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
