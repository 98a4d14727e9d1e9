"""`verify_dataset`: check a data set folder against its own checksums and manifest."""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from homesim.dataset.layout import Layout, read_json
from homesim.dataset.manifest import read_manifest
from homesim.dataset.tarfiles import MemberHash, file_sha256, iter_members
from homesim.errors import DataError


@dataclass
class Report:
    """What `verify_dataset` found: problems (empty when all is well) and counts."""

    episodes: int = 0
    ok: int = 0
    shards: int = 0
    frames: int = 0
    problems: list[str] = field(default_factory=list)


def iter_episodes(shard: Path) -> Iterator[tuple[str, list[tuple[str, bytes]]]]:
    """(key, members) of each episode of a shard, streaming (members are consecutive)."""
    key: str | None = None
    members: list[tuple[str, bytes]] = []
    for name, data in iter_members(shard):
        k = name.split(".", 1)[0]
        if k != key and members:
            yield key or "", members
            members = []
        key = k
        members.append((name, data))
    if members:
        yield key or "", members


def verify_dataset(root: str | Path) -> Report:
    """Check shard checksums, each episode's member checksum and frame count, and that the
    manifest lists every episode."""
    layout = Layout(root)
    if not layout.config_path.exists():
        raise DataError(f"{layout.root}: not a homesim data set (no dataset.json)")
    info = read_json(layout.config_path)
    report = Report()
    if not info.get("complete"):
        report.problems.append("dataset.json: the run has not finished (resume it)")
        return report
    rows = {r["key"]: r for r in read_manifest(layout.manifest_path)}
    report.episodes = len(rows)
    report.ok = sum(1 for r in rows.values() if r["status"] == "ok")
    seen: set[str] = set()
    for shard in info["shards"]:
        report.shards += 1
        _check_shard(layout.shards / shard["name"], shard, rows, seen, report)
    missing = [k for k, r in rows.items() if r["status"] == "ok" and k not in seen]
    if missing:
        report.problems.append(f"{missing[0]}: in the manifest but in no shard "
                               f"({len(missing)} episodes)")
    if info["config"]["n"] != len(rows):
        report.problems.append(f"episodes.parquet: {len(rows)} rows, expected "
                               f"{info['config']['n']}")
    return report


def _check_shard(path: Path, shard: dict[str, Any], rows: dict[str, dict[str, Any]],
                 seen: set[str], report: Report) -> None:
    if not path.exists():
        report.problems.append(f"{path.name}: missing")
        return
    if file_sha256(path) != shard["sha256"]:
        report.problems.append(f"{path.name}: checksum differs from dataset.json")
    for key, members in iter_episodes(path):
        seen.add(key)
        row = rows.get(key)
        if row is None:
            report.problems.append(f"{path.name}: {key} is not in the manifest")
            continue
        h = MemberHash()
        for name, data in members:
            h.add(name, data)
        if h.hexdigest() != row["sha256"]:
            report.problems.append(f"{path.name}: {key}: checksum differs from the manifest")
        problem = _check_members(key, members, row)
        if problem:
            report.problems.append(f"{path.name}: {key}: {problem}")
        report.frames += row["num_frames"]


def _check_members(key: str, members: list[tuple[str, bytes]], row: dict[str, Any]
                   ) -> str | None:
    names = dict(members)
    meta_bytes = names.get(f"{key}.json")
    if meta_bytes is None:
        return "no json member"
    try:
        meta = json.loads(meta_bytes)
    except ValueError:
        return "json member unreadable"
    if meta["num_frames"] != row["num_frames"]:
        return f"json says {meta['num_frames']} frames, the manifest {row['num_frames']}"
    stride, frames = meta["gt_stride"], meta["num_frames"]
    for modality in ("depth", "class", "instance", "flow"):
        if modality in meta["modalities"]:
            have = sum(1 for n in names if n.endswith(f".{modality}.png"))
            want = -(-frames // stride)
            if have != want:
                return f"{have} {modality} frames, expected {want}"
    if "rgb" in meta["modalities"] and f"{key}.mp4" not in names:
        return "no mp4 member"
    return None
