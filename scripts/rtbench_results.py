"""Loading an rtbench results folder for the scripts (Debian's python3-pandas)."""
import json
import os
import stat
import sys
import tempfile
from pathlib import Path

import pandas as pd

SCENES = {"cgal:bunny00": "bunny", "procedural:christen_a": "scene A", "procedural:christen_b": "scene B",
          "procedural:christen_b_thesis": "scene B (Table 6.1)",
          "christen_c": "scene C", "teapot_in_stadium": "teapot in stadium", "million": "1M triangles",
          "procedural:closed_box": "closed box", "procedural:icosphere": "icosphere", "whitted_room": "Whitted room",
          "purcell_bunny": "bunny on a floor", "procedural:forest": "forest", "procedural:building": "building"}


def scene_name(source: str) -> str:
    """A short name: the table's, or a scene description's file name without .toml."""
    if source.endswith(".toml"):
        source = Path(source).stem
    return SCENES.get(source, source)


def method_name(run) -> str:
    """structure (with its grid resolution rule) for one run: "grid 64", "bvh", "auto (bvh)"."""
    kind = run.structure_type
    if kind == "uniform_grid":
        name = f"grid {int(run.structure_min_dim)}" if pd.notna(run.get("structure_min_dim")) else "grid"
        return name + (" conservative" if str(run.get("structure_conservative")).lower() == "true" else "")
    if kind == "auto":
        return f"auto ({run.auto_choice})"
    return {"brute_force": "brute force"}.get(kind, kind)


def fmt(value, digits=3) -> str:
    """A table cell: the number with thousands separators and `digits` decimals, "" when NaN."""
    return "" if pd.isna(value) else f"{value:,.{digits}f}"


def structure_names(structure_type: pd.Series) -> pd.Series:
    """structure.type as tables name it: "grid" for uniform_grid, every other type as it is."""
    return structure_type.map({"uniform_grid": "grid"}).fillna(structure_type)


def division_names(runs: pd.DataFrame) -> pd.Series:
    """intersection.division of each run: "double" for runs before the key (results schema 18), which all
    divided through the double quotient."""
    if "intersection_division" not in runs:
        return pd.Series("double", index=runs.index)
    return runs.intersection_division.fillna("double")


def commit_text(context) -> str:
    """The commit a folder was made at, short: "2c376b45fb82", or "2c376b45fb82 with uncommitted
    changes (diff 4088b93b)" for a working tree that differed from it (rtbench's "-dirty-" hash)."""
    commit = str(context.get("git_commit", "?"))
    base, _, diff = commit.partition("-dirty-")
    return base[:12] + (f" with uncommitted changes (diff {diff})" if "-dirty" in commit else "")


def wrong_rays(frame, prefix="exact_"):
    """Rays wrong against the exact reference: false misses + false hits + wrong triangle (a simplified
    scene has other triangles: no wrong triangle counted). prefix "embree_exact_" for Embree's."""
    return frame[prefix + "false_misses"] + frame[prefix + "false_hits"] + frame[prefix + "wrong_primitive"].fillna(0)


def sweep_of(label: str) -> str:
    """The [[sweep]] name in a run label: "name:key=value ...", "name", "key=value ..." or "single run"."""
    if ":" in label:
        return label.split(":")[0]
    return "" if "=" in label or label == "single run" else label


# pandas dtypes of columns.csv's value types (harness/columns.h columnValueType).
DTYPES = {"integer": "Int64", "number": "float64", "boolean": "boolean", "text": "string"}
AXES = ("_x", "_y", "_z")
# The 3-vector config keys (schema/keys.h keyColumns), by their one column before results schema 6.
VECTOR_KEYS = ("scene_translate", "camera_position", "camera_look_at", "camera_up", "structure_resolution")


def split_vector_cells(runs: pd.DataFrame) -> pd.DataFrame:
    """A folder before results schema 6 wrote a 3-vector key as one "[x y z]" cell: three numeric
    columns <key>_x, _y, _z instead, as rtbench's own readers do (harness/columns.cpp)."""
    for column in [c for c in VECTOR_KEYS if c in runs.columns]:
        cells = runs[column].astype("string").str.strip("[]").str.split(" ", expand=True)
        for a, axis in enumerate(AXES):
            values = pd.to_numeric(cells[a]) if a in cells else pd.Series(float("nan"), index=runs.index)
            runs.insert(runs.columns.get_loc(column), column + axis, values.astype(float))
        runs = runs.drop(columns=column)
    return runs


WHOLE_TRAVERSAL = ("branching", "persistent", "megakernel")

# What the tables say of the scenes they name after Christen 2005 (Table 6.1: A "3 Boxes", 36
# triangles; B "Cubes distributed in room", 2,064; C "High and low polygon objects", 61,562).
CHRISTEN_SCENES = ("Scenes A, B and C after Christen 2005 Table 6.1: scene A is his 3 boxes (36 triangles); scene B "
                   "here is a room of 12 triangles with 166 cubes, 2,004 triangles, where his table says 2,064 "
                   "(`procedural:christen_b_thesis`, 171 cubes, is one reading of that, used by results/christen2005 only); scene C "
                   "(`scenes/christen_c.toml`) matches his 61,562 triangles only: which objects and where they stand "
                   "are ours, the thesis does not say.")


def split_simd_measures(runs: pd.DataFrame) -> pd.DataFrame:
    """The two SIMD measures a folder before results schema 14 kept in one column, simd_efficiency:
    simd_lane_utilisation (the ballots' lanes) for the whole-traversal kernels, and
    simd_efficiency_purcell (Purcell's, over the stream) for multipass with the oracle on the host;
    what that column cannot tell (Purcell's measure of a whole-traversal kernel, multipass on the
    device, whose old value was over its compacted lists) stays missing."""
    if "simd_efficiency" not in runs or "strategy_type" not in runs:
        return runs
    strategy = runs.strategy_type.astype("string")
    host = ~runs["strategy_control"].astype("string").eq("device").fillna(False) if "strategy_control" in runs \
        else pd.Series(True, index=runs.index)
    old = pd.to_numeric(runs.simd_efficiency, errors="coerce")
    if "simd_lane_utilisation" not in runs:
        runs["simd_lane_utilisation"] = old.where(strategy.isin(WHOLE_TRAVERSAL).fillna(False))
    if "simd_efficiency_purcell" not in runs:
        runs["simd_efficiency_purcell"] = old.where((strategy.eq("multipass").fillna(False)) & host)
    return runs


class UnsafePath(OSError):
    """A results folder's file that is not a plain file where one is read or written (a link, a
    FIFO, a device): refused, never followed or waited on."""


def readable_file(path: Path) -> Path:
    """`path` if it is a regular file (not a FIFO, which would hang the read, nor a device); a
    missing file is the caller's to report."""
    path = Path(path)
    if os.path.lexists(path):
        mode = os.stat(path).st_mode
        if not stat.S_ISREG(mode):
            raise UnsafePath(f"{path}: not a regular file (a FIFO, device or folder); refusing to read it")
    return path


def write_file_atomically(target: Path, write):
    """`write(binary file)` into a new temporary file beside `target` (mkstemp: O_EXCL, never a
    name planted before), then os.replace over `target`: it replaces a name and never writes
    through a link. A target that is a link, or exists and is not a regular file, is refused; a
    failed write leaves the old file."""
    target = Path(target)
    if target.is_symlink():
        raise UnsafePath(f"{target}: is a symbolic link; refusing to write through it")
    if target.exists() and not target.is_file():
        raise UnsafePath(f"{target}: exists and is not a regular file; refusing to write there")
    if target.parent.is_symlink():
        raise UnsafePath(f"{target.parent}: is a symbolic link; refusing to write through it")
    fd, temporary = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        mask = os.umask(0)
        os.umask(mask)
        os.fchmod(fd, 0o666 & ~mask)  # as a plain open() would create it, not mkstemp's 0600
        with os.fdopen(fd, "wb") as out:
            write(out)
            out.flush()
            os.fsync(out.fileno())
        os.replace(temporary, target)
    except BaseException:
        try:
            os.unlink(temporary)
        except FileNotFoundError:
            pass
        raise


def write_text_atomically(target: Path, text: str):
    write_file_atomically(target, lambda out: out.write(text.encode()))


def save_figure(fig, target: Path, **options):
    """A matplotlib figure into `target` (its format from the suffix), as write_file_atomically writes."""
    ext = Path(target).suffix[1:]
    if ext == "svg":  # no date, so that a chart of the same runs is the same file
        options = dict(options, metadata={"Date": None})
    write_file_atomically(target, lambda out: fig.savefig(out, format=ext, **options))


def read_runs(folder: Path) -> pd.DataFrame:
    """A folder's runs.csv with clean types: each column's pandas dtype from the folder's columns.csv
    (integers Int64, booleans boolean, text string, missing cells <NA>); a folder without one (before
    results schema 5) gets pandas' own guesses. 3-vectors are three numeric columns either way; the
    SIMD measures are two columns either way (split_simd_measures)."""
    folder = Path(folder)
    dictionary = folder / "columns.csv"
    dtypes = None
    if dictionary.exists():
        columns = pd.read_csv(readable_file(dictionary), dtype="string", keep_default_na=False)
        dtypes = {c: DTYPES[t] for c, t in zip(columns.column, columns.type)} if "type" in columns else None
    readable_file(folder / "runs.csv")
    if dtypes is None:
        runs = pd.read_csv(folder / "runs.csv", dtype={"run": "string", "config_hash": "string"})
    else:
        header = pd.read_csv(folder / "runs.csv", nrows=0).columns
        runs = pd.read_csv(folder / "runs.csv", dtype={c: dtypes.get(c, "string") for c in header})
    return split_simd_measures(split_vector_cells(runs))


def read_samples(folder: Path) -> pd.DataFrame:
    """A folder's samples.csv (every timed repetition: run, method, round, ms, ...), read once for
    round_times and round_ratios; no rows where the folder has none."""
    path = Path(folder) / "samples.csv"
    if not path.exists():
        return pd.DataFrame(columns=["run", "method", "round", "ms"])
    return pd.read_csv(readable_file(path), dtype={"run": str})


def round_times(samples: pd.DataFrame, run: str, method: str = "kernel") -> pd.Series:
    """One run's time in each timing round (ms; `method` as samples.csv names it, the median where a
    round holds several repetitions), indexed by round. Empty where the samples lack the run."""
    of_run = samples[(samples.method == method) & (samples.run == str(run))]
    return of_run.groupby("round").ms.median().astype(float)


def round_ratios(samples: pd.DataFrame, numerator: str, denominator: str, method: str = "kernel") -> pd.Series:
    """Two runs' times divided round by round (numerator run over denominator run), indexed by round.
    Runs timed in interleaved rounds (experiment.order = "interleaved") saw the same machine in round
    r, so the ratios' spread is the comparison's own. Empty where either run has no rounds."""
    return (round_times(samples, numerator, method) / round_times(samples, denominator, method)).dropna()


def with_vector_text(runs: pd.DataFrame) -> pd.DataFrame:
    """Adds a text column "[x y z]" per 3-vector key (before its _x column), as the config writes the
    value: the charts treat the key as one swept value, not three."""
    for key in VECTOR_KEYS:
        if key + "_x" not in runs.columns or key in runs.columns:
            continue
        parts = [runs[key + axis] for axis in AXES]
        text = [pd.NA if any(pd.isna(v) for v in values) else "[" + " ".join(f"{float(v):.9g}" for v in values) + "]"
                for values in zip(*parts)]
        runs.insert(runs.columns.get_loc(key + "_x"), key, pd.array(text, dtype="string"))
    return runs


def refused_in_one_line(kind, error, trace):
    """A table script's refusal (UnsafePath) as one line naming the file, exit status 1; any other
    error as Python reports it."""
    if isinstance(error, UnsafePath):
        print(f"{Path(sys.argv[0]).name}: {error}", file=sys.stderr)
    else:
        sys.__excepthook__(kind, error, trace)


def open_results(doc: str):
    """A table script's one argument, the RESULTS_DIR, loaded as `load` loads it, the ok runs a copy
    to add columns to: (folder, runs, failed, context, device). Any other command line prints the
    script's usage (`doc`) and exits with status 2."""
    if len(sys.argv) != 2:
        print(doc)
        sys.exit(2)
    folder = Path(sys.argv[1])
    sys.excepthook = refused_in_one_line
    runs, failed, context, device = load(folder)
    return folder, runs.copy(), failed, context, device


def live_headline(runs: pd.DataFrame) -> bool:
    """Whether host-controlled multipass's kernel_ms is its live loop (results schema 25 on, where
    kernel_ms_replay holds the replayed passes' GPU time) rather than the replay."""
    return "kernel_ms_replay" in runs and runs.kernel_ms_replay.notna().any()


def passes_gpu_ms(runs: pd.DataFrame) -> pd.Series:
    """Multipass: the GPU time of a frame's passes, without the host's read-backs (kernel_ms_replay where
    the headline is the live loop, else kernel_ms_median)."""
    if "kernel_ms_replay" not in runs:
        return runs.kernel_ms_median
    return runs.kernel_ms_replay.where(runs.kernel_ms_replay.notna(), runs.kernel_ms_median)


def masking_share(runs: pd.DataFrame) -> pd.Series:
    """Multipass: the state test alone (kernel_ms_stencil_pass) times the traverse and intersect passes,
    over the frame's passes' GPU time: an upper bound on the share of a frame the ray-state test costs."""
    return runs.kernel_ms_stencil_pass * (runs.passes_traverse + runs.passes_intersect) / passes_gpu_ms(runs)


def command_text(context: dict) -> str:
    """How a folder was made: its command, commit and date (context.json)."""
    return f"Command: `{context.get('command', '?')}` at commit {commit_text(context)}, {context.get('date_utc', '?')}."


def load(folder: Path):
    """(ok runs with `scene` and `sweep` columns added, failed runs, context dict, device name)."""
    runs = with_vector_text(read_runs(folder))
    context = json.loads(readable_file(folder / "context.json").read_text())
    failed = runs[runs.status != "ok"]
    runs = runs[runs.status == "ok"].copy()
    runs["scene"] = runs.scene_source.map(scene_name)
    # The sweep's name: its own column from results schema 5 on, else the label's prefix.
    runs["sweep"] = runs["sweep"].fillna("").astype(str) if "sweep" in runs else runs.label.map(sweep_of)
    for column in ["strategy_scheduling", "strategy_suppress_finished_reads"]:
        if column not in runs:
            runs[column] = None
    device = context["devices"][0]["name"] if context.get("devices") else "?"
    return runs, failed, context, device


def whitted_frames(runs: pd.DataFrame) -> pd.DataFrame:
    """Whitted frames to depth D (rays.type = whitted, Purcell Table 3's Whitted ray tracer): the
    camera rays plus generations 1..D of reflections and refractions and the shadow rays of
    generations 0..D, each batch a run of its own, summed and set against the camera rays' run of
    the same scene and method ("method" column). A depth is kept only when every batch up to it is
    there. Columns: scene, method, depth, rays, and × primary for rays, time, bytes and Embree's
    time; secondary_simd: the secondary batches' mean SIMD efficiency (Purcell's measure, the same for
    every strategy); wrong: their rays wrong."""
    rows = []
    primary = runs[runs.rays_type == "primary"].set_index(["scene", "method"])
    whitted = runs[runs.rays_type == "whitted"]
    for (scene, method), g in whitted.groupby(["scene", "method"]):
        if (scene, method) not in primary.index:
            continue
        base = primary.loc[(scene, method)]
        for depth in sorted(g.whitted_depth.unique()):
            upto = g[g.whitted_depth <= depth]
            if len(upto) != 2 * int(depth) + 1:  # shadow 0..D, secondary 1..D
                continue
            total = lambda column: upto[column].sum() + base[column]
            rows.append({"scene": scene, "method": method, "depth": int(depth), "rays": int(total("rays")),
                         "rays_x": total("rays") / base.rays,
                         "time_x": total("kernel_ms_median") / base.kernel_ms_median,
                         "bytes_x": total("bytes_total") / base.bytes_total,
                         "embree_x": total("embree1_ms_median") / base.embree1_ms_median,
                         "secondary_simd": upto[upto.whitted_rays == "secondary"].simd_efficiency_purcell.mean(),
                         "wrong": int(wrong_rays(upto).sum())})
    return pd.DataFrame(rows)


def failed_rows(failed: pd.DataFrame, what: str, name) -> list:
    """The failed runs as a Markdown table (empty when none): run, `what` (name(row)), strategy, why."""
    if not len(failed):
        return []
    return ["", f"| run | {what} | strategy | why |", "|---|---|---|---|"] + [
        f"| {r.run} | {name(r)} | {r.strategy_type} | {str(r.error).replace('|', '/')} |" for r in failed.itertuples()]


def write_tables(folder: Path, lines: list) -> int:
    """Writes folder/tables.md and names it."""
    write_text_atomically(folder / "tables.md", "\n".join(lines) + "\n")
    print(folder / "tables.md")
    return 0


def christen_iterations(runs: pd.DataFrame) -> list:
    """Christen 2005's iteration of each run (Figs. 6.10-6.11), as configs/christen2005.toml reads it:
    1 for the camera rays, 1 + n for mirror reflection n."""
    return [1 + int(n) if kind == "reflection" else 1
            for kind, n in zip(runs.rays_type, runs.get("reflection_iteration", pd.Series(0, index=runs.index)).fillna(0))]


# "× Embree" means one thing in every table: the kernel's speed over Embree's on the same rays,
# speed_ratio_vs_embree1 (Embree's time over the kernel's), never a time ratio.
EMBREE_SPEED = "× Embree: speed over Embree rtcIntersect1 on the same rays (above 1: faster)"


def embree_threads(runs: pd.DataFrame) -> str:
    """The TBB threads Embree ran on, from `embree_threads`: "2", "2/4" where the runs differ, "?"."""
    threads = runs["embree_threads"].dropna() if "embree_threads" in runs else []
    return "/".join(str(t) for t in sorted({int(t) for t in threads})) or "?"


def embree_on(runs: pd.DataFrame) -> str:
    """"Embree rtcIntersect1 on 2 threads", the threads read from the runs."""
    threads = embree_threads(runs)
    return f"Embree rtcIntersect1 on {threads} thread{'' if threads == '1' else 's'}"


def embree_speed_caption(runs: pd.DataFrame) -> str:
    """The sentence a table with a × Embree column carries."""
    return f"{EMBREE_SPEED}; {embree_on(runs)} (`embree_threads`)."


def host_against_device(runs: pd.DataFrame, device: str) -> str:
    """Christen 2005's "GPU against CPU" as these runs measured it: the Vulkan kernels on the device
    (`device`; lavapipe, whose name says llvmpipe, runs them on the host's own cores) against rtbench's
    host C++ traversal."""
    names = sorted(set(runs["device"].dropna())) if "device" in runs else []
    device = " / ".join(names) or device
    if "llvmpipe" in device:
        return "the Vulkan kernels on lavapipe against host C++ on the same cores (Christen's GPU against CPU)"
    return f"the Vulkan kernels on {device} against host C++ (Christen's GPU against CPU)"


# Ranking: one run is faster than another only where their 95% intervals do not overlap.
def interval_of(run, prefix="kernel_ms", samples="timing_repetitions"):
    """A run's 95% interval (low, high) from <prefix>_ci_low and _ci_high (kernel_ms: GPU time;
    speed_ratio: × Embree; build_ratio, with samples="build_rounds": the build over Embree's);
    None where it has none: empty cells (too few samples), or one sample (an older folder's
    bootstrap of one value: a point, not an interval)."""
    low, high = getattr(run, prefix + "_ci_low", None), getattr(run, prefix + "_ci_high", None)
    repetitions = getattr(run, samples, None)
    if pd.isna(low) or pd.isna(high) or (pd.notna(repetitions) and repetitions < 2):
        return None
    return float(low), float(high)


def interval_text(span, digits=3) -> str:
    """A 95% interval alone: "[63.2, 66.4]", or "—" where there is none."""
    return f"[{fmt(span[0], digits)}, {fmt(span[1], digits)}]" if span else "—"


def with_interval(value, span, show=fmt) -> str:
    """A median and its 95% interval: "0.306 [0.203, 0.613]", or "0.142 (no interval)"."""
    return f"{show(value)} " + (f"[{show(span[0])}, {show(span[1])}]" if span else "(no interval)")


def leaders(runs: pd.DataFrame):
    """The runs that no other run beats on GPU time, fastest median first; a run beats another when its
    95% interval lies wholly below the other's. One leader: a winner the intervals separate; several: a
    tie; None where a run has no interval (not ranked)."""
    rows = [r for _, r in runs.iterrows()]
    spans = [interval_of(r) for r in rows]
    if not rows or any(s is None for s in spans):
        return None
    kept = [r for r, mine in zip(rows, spans) if not any(other[1] < mine[0] for other in spans)]
    return sorted(kept, key=lambda r: r.kernel_ms_median)


def ranked_text(leading, name, show=fmt) -> str:
    """leaders() of GPU time in words: the winner's name(run), "tie: a [l, h], b [l, h]", or "no interval:
    not ranked"."""
    if leading is None:
        return "no interval: not ranked"
    if len(leading) == 1:
        return name(leading[0])
    return "tie: " + ", ".join(f"{name(r)} [{show(r.kernel_ms_ci_low)}, {show(r.kernel_ms_ci_high)}]" for r in leading)


def auto_verdicts(runs: pd.DataFrame) -> list:
    """`auto` against the candidates it weighs (the grid at min_dim 64, not conservative; the BVH; brute
    force), measured in the same sweep on the same scene and strategy: per auto run (auto, pool, leaders
    of the pool, verdict): "yes" (its choice the one leader), "tie" (among tied leaders), "no" (another
    candidate's interval wholly below its choice's) or "no interval" (not ranked)."""
    conservative = runs.structure_conservative.fillna(False).astype(bool) if "structure_conservative" in runs else False
    candidates = runs[runs.structure_type.isin(["bvh", "brute_force"]) |
                      ((runs.structure_type == "uniform_grid") & (runs.structure_min_dim == 64) & ~conservative)]
    out = []
    for _, auto in runs[runs.structure_type == "auto"].iterrows():
        pool = candidates[(candidates.scene_source == auto.scene_source) & (candidates.strategy_type == auto.strategy_type)]
        if pool.empty:
            continue
        leading = leaders(pool)
        chosen = [r for r in leading or [] if r.structure_type == auto.auto_choice]
        verdict = "no interval" if leading is None else "no" if not chosen else "yes" if len(leading) == 1 else "tie"
        out.append((auto, pool, leading, verdict))
    return out


def auto_summary(verdicts: list) -> str:
    """auto_verdicts() counted in one sentence."""
    n = {v: sum(1 for *_, verdict in verdicts if verdict == v) for v in ("yes", "tie", "no", "no interval")}
    return (f"`auto` picked the fastest candidate (its 95% interval wholly below every other's) in {n['yes']} of "
            f"{len(verdicts)} cases; its choice tied the fastest (overlapping intervals) in {n['tie']}; another "
            f"candidate was faster (intervals apart) in {n['no']}; {n['no interval']} without intervals (not ranked).")


def faster_of(a, b, names=("a", "b")) -> str:
    """Two runs ranked by their 95% intervals of GPU time: "<name> faster" where the intervals separate,
    "tie" where they overlap, else "no interval: not ranked"."""
    leading = leaders(pd.DataFrame([a, b]).reset_index(drop=True))
    if leading is None:
        return "no interval: not ranked"
    return "tie" if len(leading) == 2 else f"{names[leading[0].name]} faster"


def verdict_counts(verdicts: list, what: str) -> str:
    """faster_of()'s verdicts counted: "branching faster on 2 of 3 scenes, tie on 1"."""
    counted = pd.Series(verdicts).value_counts()
    return ", ".join(f"{v} on {n}" + (f" of {len(verdicts)} {what}" if i == 0 else "") for i, (v, n) in enumerate(counted.items()))


TREES = {("bvh", "medium"): "SAH", ("bvh", "low"): "Morton", ("median_bvh", None): "median split"}


def tree_names(runs: pd.DataFrame) -> pd.Series:
    """The BVH a run traced (configs/trees.toml): Embree's binned SAH ("SAH", structure.quality
    medium), its Morton build ("Morton", low) or the median split (structure.type = median_bvh)."""
    quality = runs.structure_quality if "structure_quality" in runs else pd.Series(None, index=runs.index)
    return pd.Series([TREES.get((t, q if t == "bvh" else None), t) for t, q in zip(runs.structure_type, quality)],
                     index=runs.index)


def against_sah(runs: pd.DataFrame) -> pd.DataFrame:
    """Each run beside the SAH tree's run of the same scene, ray type and strategy: the ok runs with
    a `tree` column and, for SAH cost, nodes visited per ray and passes, `<column>_x`, the run's value
    over the SAH tree's (1 for the SAH tree itself)."""
    runs = runs.copy()
    runs["tree"] = tree_names(runs)
    key = ["scene", "rays_type", "strategy_type", "structure_leaf_size", "camera_width", "camera_height"]
    sah = runs[runs.tree == "SAH"].set_index(key, verify_integrity=True)
    for column in ["bvh_sah_cost", "nodes_per_ray_mean", "passes_total"]:
        base = [sah[column].get(tuple(k), float("nan")) for k in runs[key].itertuples(index=False)]
        runs[column + "_x"] = runs[column] / pd.Series(base, index=runs.index)
    return runs


def sorted_beside_branching(runs: pd.DataFrame) -> pd.DataFrame:
    """configs/order.toml's pairs: each sorted run (strategy.type = sorted) beside branching's run of
    the same scene, ray type and structure, a row each: scene, triangles, rays_type, structure, rays,
    lanes (branching's SIMD lane utilisation), sorted_lanes, moved (rays the sort moved), sort_share
    (the host sort's time over the sorted kernel's), and both runs' speed over Embree with their
    95% intervals (speed, speed_span; sorted_speed, sorted_span)."""
    runs = runs.copy()
    runs["structure"] = [method_name(r) for _, r in runs.iterrows()]
    key = ["scene", "rays_type", "structure", "camera_width", "camera_height"]
    branching = runs[runs.strategy_type == "branching"].set_index(key, verify_integrity=True)
    rows = []
    for r in runs[runs.strategy_type == "sorted"].itertuples():
        k = tuple(getattr(r, column) for column in key)
        if k not in branching.index:
            raise ValueError(f"run {r.run}: a sorted run without branching's of the same scene, rays and structure")
        b = branching.loc[k]
        rows.append({"scene": r.scene, "triangles": r.scene_triangles, "rays_type": r.rays_type, "structure": r.structure,
                     "rays": r.rays, "lanes": b.simd_lane_utilisation, "sorted_lanes": r.simd_lane_utilisation,
                     "moved": r.sorted_rays_moved, "sort_share": r.sorted_sort_ms / r.kernel_ms_median,
                     "speed": b.speed_ratio_vs_embree1, "speed_span": interval_of(b, "speed_ratio"),
                     "sorted_speed": r.speed_ratio_vs_embree1, "sorted_span": interval_of(r, "speed_ratio")})
    return pd.DataFrame(rows, columns=["scene", "triangles", "rays_type", "structure", "rays", "lanes", "sorted_lanes", "moved",
                                       "sort_share", "speed", "speed_span", "sorted_speed", "sorted_span"])


def speed_verdict(span, other_span) -> str:
    """"faster" or "slower" where the first run's 95% interval of speed lies wholly above or below
    the other's, "tie" where they overlap, "not ranked" where either has none."""
    if not span or not other_span:
        return "not ranked"
    return "faster" if span[0] > other_span[1] else "slower" if span[1] < other_span[0] else "tie"


def values_text(column: pd.Series) -> str:
    """An integer column's distinct values as a caption gives them: "4", "1 and 4"."""
    return " and ".join(str(int(v)) for v in sorted(column.dropna().unique())) or "?"
