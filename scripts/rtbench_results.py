"""Loading an rtbench results folder for the scripts (Debian's python3-pandas)."""
import json
from pathlib import Path

import pandas as pd

SCENES = {"cgal:bunny00": "bunny", "procedural:christen_a": "scene A", "procedural:christen_b": "scene B",
          "christen_c": "scene C", "teapot_in_stadium": "teapot in stadium", "million": "1M triangles",
          "procedural:closed_box": "closed box", "procedural:icosphere": "icosphere"}


def scene_name(source: str) -> str:
    """A short name: the table's, or a scene description's file name without .toml."""
    if source.endswith(".toml"):
        source = Path(source).stem
    return SCENES.get(source, source)


def method_name(run) -> str:
    """structure (with its grid resolution rule) for one run: "grid 64", "bvh", "auto (bvh)"."""
    kind = run.structure_type
    if kind == "uniform_grid":
        name = f"grid {int(run.structure_min_dim)}" if run.get("structure_min_dim") == run.get("structure_min_dim") else "grid"
        return name + (" conservative" if str(run.get("structure_conservative")).lower() == "true" else "")
    if kind == "auto":
        return f"auto ({run.auto_choice})"
    return {"brute_force": "brute force"}.get(kind, kind)


def sweep_of(label: str) -> str:
    """The [[sweep]] name in a run label: "name:key=value ...", "name", "key=value ..." or "single run"."""
    if ":" in label:
        return label.split(":")[0]
    return "" if "=" in label or label == "single run" else label


def load(folder: Path):
    """(ok runs with `scene` and `sweep` columns added, failed runs, context dict, device name)."""
    runs = pd.read_csv(folder / "runs.csv")
    context = json.loads((folder / "context.json").read_text())
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
