"""The data set card's figures: counts, Table 1(a), action and object histograms and a
contact sheet of random episodes, from a finished data set folder; for a plan folder
(`homesim.dataset.plan`) the counts of every part and how well the training programs'
step classes cover each test row's."""

from __future__ import annotations

import json
import random
import re
from collections import Counter
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from homesim.dataset.layout import Layout, dumps, read_json
from homesim.dataset.plan import PlanFolder
from homesim.dataset.read import shard_paths
from homesim.dataset.verify import iter_episodes
from homesim.errors import DataError
from homesim.files import write_text
from homesim.knowledge.datasets import ActivityDataset, ActivityProgram
from homesim.knowledge.stats import action_counts, object_counts, summarize
from homesim.program.parse import parse_program
from homesim.render.video import decode_video

SHEET_EPISODES = 12


@dataclass(frozen=True)
class CardStats:
    """The counts of a data set card."""

    episodes: int
    made: int
    failed: int
    failed_by_stage: dict[str, int]
    frames: int
    hours: float
    fps: int
    width: int
    height: int
    homes: dict[str, int]
    agents: dict[str, int]
    bytes: int  # shard files on disk
    bytes_per_frame: float
    table1a: dict[str, float]  # programs, avg_steps, avg_sentences, avg_words
    actions: list[tuple[str, int]]
    objects: list[tuple[str, int]]


def card_stats(root: str | Path, programs: ActivityDataset) -> CardStats:
    """Counts from the manifest and config; Table 1(a) and histograms from `programs`
    (the made episodes' programs, one per episode)."""
    layout = Layout(root)
    config = read_json(layout.config_path)["config"]
    rows = layout.finished_rows()
    made = [r for r in rows if r["status"] == "ok"]
    frames = sum(r["num_frames"] for r in made)
    size = sum(s["bytes"] for s in layout.finished_shards())  # on disk, with tar headers
    s = summarize(programs)
    return CardStats(
        episodes=len(rows), made=len(made), failed=len(rows) - len(made),
        failed_by_stage=dict(Counter(r["stage"] for r in rows if r["status"] != "ok")),
        frames=frames, hours=frames / config["fps"] / 3600, fps=config["fps"],
        width=config["width"], height=config["height"],
        homes=dict(sorted(Counter(r["home"] for r in made).items())),
        agents=dict(sorted(Counter(r["agent"] for r in made).items())),
        bytes=size, bytes_per_frame=size / frames if frames else 0.0,
        table1a={"programs": s.programs, "avg_steps": s.avg_steps,
                 "avg_sentences": s.avg_sentences, "avg_words": s.avg_words},
        actions=action_counts(programs, top=None), objects=object_counts(programs, top=40))


def scan(root: str | Path, sheet_keys: set[str]
         ) -> tuple[ActivityDataset, list[tuple[str, np.ndarray]]]:
    """One pass over the shards: every made episode's program, and one labelled frame
    (the middle one) of each episode in `sheet_keys`."""
    items, frames = [], []
    for shard in shard_paths(root):
        for key, members in iter_episodes(shard):
            by_name = dict(members)
            meta = json.loads(by_name[f"{key}.json"])
            items.append(ActivityProgram(key, parse_program(meta["spec"]["program"]), key))
            if key in sheet_keys and f"{key}.mp4" in by_name:
                frames.append(_sheet_frame(key, meta, by_name[f"{key}.mp4"]))
    return ActivityDataset(items, str(root)), frames


def _sheet_frame(key: str, meta: dict[str, Any], video: bytes) -> tuple[str, np.ndarray]:
    rgb = decode_video(video, meta["width"], meta["height"])
    middle = len(rgb) // 2
    step = next((s for s in meta["steps"] if s["start_frame"] <= middle <= s["end_frame"]),
                None)
    label = f"{key[3:]} {meta['home']} {meta['agent']}: {step['step'] if step else ''}"
    return label, rgb[middle]


def write_card(root: str | Path, out: str | Path, seed: int = 0) -> list[Path]:
    """Write stats.json, actions.png, objects.png and contact_sheet.png into `out` (for a
    run still going or stopped: over the shards finished so far)."""
    from homesim.knowledge.stats_plots import plot_counts
    from homesim.render.sheet import contact_sheet

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    rows = [r for r in Layout(root).finished_rows() if r["status"] == "ok"]
    chosen = random.Random(seed).sample([r["key"] for r in rows],
                                        min(SHEET_EPISODES, len(rows)))
    programs, frames = scan(root, set(chosen))
    stats = card_stats(root, programs)
    paths = [write_text(out / "stats.json", dumps(asdict(stats)))]
    paths.append(plot_counts(stats.actions, out / "actions.png",
                             f"Actions in {stats.made} episodes", "tab:blue"))
    paths.append(plot_counts(stats.objects, out / "objects.png",
                             f"Objects in {stats.made} episodes (40 most common)",
                             "tab:orange"))
    if frames:
        order = {k[3:]: i for i, k in enumerate(sorted(chosen))}
        frames.sort(key=lambda f: order.get(f[0].split(" ", 1)[0], 0))
        paths.append(contact_sheet(frames, out / "contact_sheet.png", columns=4,
                                   title=f"{len(frames)} random episodes (middle frame)"))
    return paths


def step_classes(program: ActivityProgram) -> list[str]:
    """A program's steps as classes: action and object classes, no instance numbers
    (``[Grab] <cup> (1)`` -> ``[Grab] <cup>``), what the clip models recognise."""
    return [re.sub(r"\s*\(\d+\)", "", str(step)).strip() for step in program.program.steps]


def coverage(train: ActivityDataset, test: ActivityDataset) -> dict[str, float]:
    """How the training programs' step classes cover the test programs': the share of
    the test step classes seen in training (at all, five times or more), and of the test
    steps whose class was seen."""
    seen = Counter(c for p in train for c in step_classes(p))
    tested = Counter(c for p in test for c in step_classes(p))
    total = sum(tested.values())
    return {"test_classes": len(tested), "train_classes": len(seen),
            "classes_seen": sum(c in seen for c in tested) / max(len(tested), 1),
            "classes_seen_5": sum(seen[c] >= 5 for c in tested) / max(len(tested), 1),
            "steps_seen": sum(n for c, n in tested.items() if c in seen) / max(total, 1)}


def plan_stats(folder: PlanFolder, chosen: set[tuple[str, str]]
               ) -> tuple[dict[str, Any], dict[str, ActivityDataset], list]:
    """A plan's stats (each part's counts, the train share, each test row's coverage by
    train), each part's programs, and the labelled frames of the `chosen` (part, key)."""
    parts, frames, programs = {}, [], {}
    for p in folder.plan.parts:
        ds, shots = scan(folder.folder(p.name), {k for q, k in chosen if q == p.name})
        programs[p.name] = ActivityDataset([replace(x, id=f"{p.name}/{x.id}") for x in ds],
                                           p.name)
        parts[p.name] = {"role": p.role, **asdict(card_stats(folder.folder(p.name), ds))}
        frames += [(f"{p.name} {label}", image) for label, image in shots]
    train = ActivityDataset([x for p in folder.plan.parts if p.role == "train"
                             for x in programs[p.name]], "train")
    made = sum(v["made"] for v in parts.values())
    trained = sum(v["made"] for v in parts.values() if v["role"] == "train")
    rows = {row: {"label": label, **coverage(train, ActivityDataset(
        [x for q in pooled for x in programs[q]], row))} for row, label, pooled in folder.plan.rows}
    return ({"parts": parts, "made": made, "train_share": trained / max(made, 1),
             "coverage": rows}, programs, frames)


def write_plan_card(root: str | Path, out: str | Path, seed: int = 0) -> list[Path]:
    """The card of a plan folder: stats.json (`plan_stats`), the action and object
    histograms of all parts and a contact sheet of 12 random episodes of all parts."""
    from homesim.dataset.plan import read_plan
    from homesim.knowledge.stats_plots import plot_counts
    from homesim.render.sheet import contact_sheet

    folder = read_plan(root)
    if folder is None:
        raise DataError(f"{root}: not a plan folder (no plan.json)")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    keys = [(p.name, r["key"]) for p in folder.plan.parts
            for r in Layout(folder.folder(p.name)).finished_rows() if r["status"] == "ok"]
    chosen = set(random.Random(seed).sample(keys, min(SHEET_EPISODES, len(keys))))
    stats, programs, frames = plan_stats(folder, chosen)
    everything = ActivityDataset([x for ds in programs.values() for x in ds], "all")
    paths = [write_text(out / "stats.json", dumps(stats))]
    paths.append(plot_counts(action_counts(everything, top=None), out / "actions.png",
                             f"Actions in {stats['made']} episodes", "tab:blue"))
    paths.append(plot_counts(object_counts(everything, top=40), out / "objects.png",
                             f"Objects in {stats['made']} episodes (40 most common)",
                             "tab:orange"))
    if frames:
        frames.sort(key=lambda f: f[0])
        paths.append(contact_sheet(frames, out / "contact_sheet.png", columns=4,
                                   title=f"{len(frames)} random episodes (middle frame)"))
    return paths
