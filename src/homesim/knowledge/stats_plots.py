"""Write `DatasetStats` out: Table 1(c) and Fig. 4 as PNGs, all numbers as Markdown and JSON.

Plots use matplotlib's Agg backend (no display needed). Needs the ``stats`` extra.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict
from pathlib import Path

from homesim.errors import DataError
from homesim.files import atomic_write, write_text
from homesim.knowledge.stats import DatasetStats, SimilarityMatrix

SIMILARITY_PNG = "table1c_similarity.png"
ACTIONS_PNG = "fig4_actions.png"
OBJECTS_PNG = "fig4_objects.png"
MARKDOWN = "stats.md"
JSON = "stats.json"


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")  # headless; must come before pyplot is imported
    import matplotlib.pyplot as plt

    return plt


def plot_similarity(matrix: SimilarityMatrix, path: Path, title: str = "") -> Path:
    """The activity-by-activity similarity matrix as a heat map (nan cells grey)."""
    import numpy as np

    plt = _pyplot()
    k = len(matrix.activities)
    size = max(4.0, 0.32 * k + 2.5)
    fig, ax = plt.subplots(figsize=(size + 1.2, size))
    cmap = plt.get_cmap("viridis").with_extremes(bad="lightgrey")
    finite = matrix.values[np.isfinite(matrix.values)]
    top = max(0.01, float(finite.max())) if finite.size else 1.0
    image = ax.imshow(np.ma.masked_invalid(matrix.values), cmap=cmap, vmin=0.0, vmax=top)
    labels = [f"{a} ({n})" for a, n in zip(matrix.activities, matrix.programs, strict=True)]
    ax.set_xticks(range(k), labels, rotation=90, fontsize=8)
    ax.set_yticks(range(k), labels, fontsize=8)
    ax.set_title(title or "Mean normalized LCS between activities (block-sorted)", fontsize=10)
    fig.colorbar(image, ax=ax, fraction=0.046, pad=0.04, label="normalized LCS")
    fig.tight_layout()
    _save(fig, path)
    plt.close(fig)
    return path


def plot_counts(counts: list[tuple[str, int]], path: Path, title: str, color: str) -> Path:
    """A bar chart of (name, count) pairs, most common first."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(max(6.0, 0.22 * len(counts) + 2), 4.5))
    ax.bar(range(len(counts)), [c for _, c in counts], color=color)
    ax.set_xticks(range(len(counts)), [n for n, _ in counts], rotation=90, fontsize=8)
    ax.set_xlim(-0.6, max(len(counts), 1) - 0.4)
    ax.set_ylabel("occurrences")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    _save(fig, path)
    plt.close(fig)
    return path


def _fmt(value: float, digits: int = 2) -> str:
    return "–" if math.isnan(value) else f"{value:.{digits}f}"


def to_markdown(stats: DatasetStats) -> str:
    """All the numbers as Markdown tables."""
    s = stats.summary
    lines = [
        f"# Dataset statistics: {stats.name or 'data set'}", "",
        "## Table 1(a)", "",
        "| programs | activities | avg. steps | avg. sentences | avg. words |",
        "|---:|---:|---:|---:|---:|",
        f"| {s.programs} | {s.activities} | {s.avg_steps:.2f} | {s.avg_sentences:.2f} "
        f"| {s.avg_words:.2f} |", "",
        "## Table 1(b): pairwise LCS between programs of one activity (over steps)", "",
        "| activity | programs | pairs | mean LCS (steps) | mean normalized LCS |",
        "|---|---:|---:|---:|---:|",
    ]
    lines += [f"| {r.activity} | {r.programs} | {r.pairs} | {_fmt(r.mean_lcs)} "
              f"| {_fmt(r.mean_normalized_lcs, 3)} |" for r in stats.activity_lcs]
    lines += ["", f"Mean normalized LCS, same activity: {_fmt(stats.within_activity, 3)}; "
              f"different activities: {_fmt(stats.between_activities, 3)}.", "",
              "## Table 1(c)", "", f"![similarity matrix]({SIMILARITY_PNG})", "",
              f"## Fig. 4: the {len(stats.actions)} most common actions and "
              f"{len(stats.objects)} most common objects", "",
              f"![actions]({ACTIONS_PNG})", "", f"![objects]({OBJECTS_PNG})", "",
              "| rank | action | steps | object | mentions |", "|---:|---|---:|---|---:|"]
    for i in range(max(len(stats.actions), len(stats.objects))):
        a = stats.actions[i] if i < len(stats.actions) else ("", "")
        o = stats.objects[i] if i < len(stats.objects) else ("", "")
        lines.append(f"| {i + 1} | {a[0]} | {a[1]} | {o[0]} | {o[1]} |")
    return "\n".join(lines) + "\n"


def to_json(stats: DatasetStats) -> dict:
    """All the numbers as plain JSON values (nan becomes null)."""
    def clean(value):
        if isinstance(value, float) and math.isnan(value):
            return None
        if isinstance(value, dict):
            return {k: clean(v) for k, v in value.items()}
        if isinstance(value, list | tuple):
            return [clean(v) for v in value]
        return value

    sim = stats.similarity
    return clean({
        "name": stats.name,
        "summary": asdict(stats.summary),
        "activity_lcs": [asdict(r) for r in stats.activity_lcs],
        "within_activity": stats.within_activity,
        "between_activities": stats.between_activities,
        "similarity": {"activities": sim.activities, "programs": sim.programs,
                       "values": sim.values.tolist()},
        "actions": [list(kv) for kv in stats.actions],
        "objects": [list(kv) for kv in stats.objects],
    })


OUTPUTS = (SIMILARITY_PNG, ACTIONS_PNG, OBJECTS_PNG, MARKDOWN, JSON)
"""The files `write_stats` writes into its folder."""


def _save(fig, path: Path) -> None:
    with atomic_write(path, "wb") as f:
        fig.savefig(f, dpi=120, format="png")


def write_stats(stats: DatasetStats, out: Path, force: bool = True) -> list[Path]:
    """Write the PNGs, ``stats.md`` and ``stats.json`` into `out` (created if needed).

    Each file is written atomically; `force=False` refuses (before writing any) when one
    of them exists.
    """
    out = Path(out)
    existing = [out / name for name in OUTPUTS if (out / name).exists()]
    if existing and not force:
        raise DataError(f"{existing[0]}: already exists; pass --force to replace it")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise DataError(f"{out}: cannot create the output folder ({e.strerror or e})") from None
    if not out.is_dir():
        raise DataError(f"{out}: not a folder")
    name = f" ({Path(stats.name).name})" if stats.name else ""
    written = [
        plot_similarity(stats.similarity, out / SIMILARITY_PNG,
                        f"Table 1(c){name}: mean normalized LCS between activities"),
        plot_counts(stats.actions, out / ACTIONS_PNG,
                    f"Fig. 4{name}: the {len(stats.actions)} most common actions", "tab:blue"),
        plot_counts(stats.objects, out / OBJECTS_PNG,
                    f"Fig. 4{name}: the {len(stats.objects)} most common objects", "tab:orange"),
    ]
    write_text(out / MARKDOWN, to_markdown(stats))
    write_text(out / JSON, json.dumps(to_json(stats), indent=1) + "\n")
    return [*written, out / MARKDOWN, out / JSON]
