"""`verify_dataset`: check a data set folder against its own checksums and manifest.

Verification exists to find damage, so it expects any: every fault of a file (missing,
not a regular file, truncated, garbage, JSON of another shape) is one line of the report
naming the file, and for a shard the member where it was found; nothing raises but a
folder that is no data set at all. Only files of the data set are opened: shard names
must be ``shard-NNNNNN.tar`` (no paths), and links are not followed. Shards stream
through once (memory holds one member's chunk and the small json members).
"""

from __future__ import annotations

import hashlib
import json
import tarfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, BinaryIO

from homesim.dataset.layout import Layout, read_json, shard_names
from homesim.dataset.manifest import read_manifest
from homesim.dataset.tarfiles import MemberHash, iter_members
from homesim.errors import DataError, HomesimError, excerpt, one_line
from homesim.files import open_regular

MAX_META_BYTES = 64 * 1024 * 1024
"""Largest episode json member read (one is ~10 KB a step)."""
MAPS = ("depth", "class", "instance", "flow")


@dataclass
class Report:
    """What `verify_dataset` found: problems (empty when all is well) and counts."""

    episodes: int = 0
    ok: int = 0
    shards: int = 0
    frames: int = 0
    problems: list[str] = field(default_factory=list)


@dataclass
class ScannedEpisode:
    """One episode as a shard holds it: member names in order, its json member (None
    when it has none or it is over `MAX_META_BYTES`) and the `MemberHash` of its members."""

    key: str
    names: list[str]
    meta: bytes | None
    sha256: str


class ShardError(DataError):
    """A shard that cannot be read on, with the member where it stopped."""


class _HashingReader:
    """A file read through, hashed on the way (the shard's SHA-256 in the same pass)."""

    def __init__(self, f: BinaryIO):
        self.f, self.sha = f, hashlib.sha256()

    def read(self, n: int = -1) -> bytes:
        data = self.f.read(n)
        self.sha.update(data)
        return data

    def finish(self) -> str:
        while self.read(1 << 20):
            pass
        return self.sha.hexdigest()


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


def scan_shard(path: Path, sha: list[str] | None = None) -> Iterator[ScannedEpisode]:
    """The episodes of the shard at `path` (a regular file, not a link), streaming; at the
    end the file's SHA-256 is appended to `sha`. `ShardError` names the shard and the
    member where a fault stops the reading."""
    with open_regular(path, "shard", follow_links=False) as f:
        reader = _HashingReader(f)
        current: dict[str, Any] | None = None
        last = "its first member"
        try:
            with tarfile.open(fileobj=reader, mode="r|") as tar:  # type: ignore[call-overload]
                for info in tar:
                    last = info.name
                    if not info.isfile():
                        raise ShardError(f"{path.name}: {_shown(info.name)}: not a file member")
                    key = info.name.split(".", 1)[0]
                    if current is not None and current["key"] != key:
                        yield _scanned(current)
                        current = None
                    current = current or {"key": key, "names": [], "meta": None,
                                          "hash": MemberHash()}
                    _read_member(tar, info, current)
            if current is not None:
                yield _scanned(current)
            if sha is not None:
                sha.append(reader.finish())
        except (tarfile.TarError, EOFError, OSError, ValueError) as e:
            raise ShardError(f"{path.name}: unreadable at or after {_shown(last)} "
                             f"({one_line(str(e) or type(e).__name__, 120)})") from None


def _read_member(tar: tarfile.TarFile, info: tarfile.TarInfo, current: dict[str, Any]
                 ) -> None:
    member = tar.extractfile(info)
    assert member is not None  # a file member
    h: MemberHash = current["hash"]
    h.start(info.name, info.size)
    keep = info.name == f"{current['key']}.json" and info.size <= MAX_META_BYTES
    kept = []
    while chunk := member.read(1 << 20):
        h.update(chunk)
        if keep:
            kept.append(chunk)
    if keep:
        current["meta"] = b"".join(kept)
    current["names"].append(info.name)


def _scanned(current: dict[str, Any]) -> ScannedEpisode:
    return ScannedEpisode(current["key"], current["names"], current["meta"],
                          current["hash"].hexdigest())


def verify_dataset(root: str | Path) -> Report:
    """Check shard checksums, each episode's member checksum and frame count, and that the
    manifest lists every episode; every fault is one line of `Report.problems`."""
    layout = Layout(root)
    if not layout.config_path.exists() and not layout.config_path.is_symlink():
        raise DataError(f"{layout.root}: not a homesim data set (no dataset.json)")
    report = Report()
    try:
        info = read_json(layout.config_path)
        if not isinstance(info, dict):
            raise DataError("dataset.json: expected a JSON object")
        if not info.get("complete"):
            report.problems.append("dataset.json: the run has not finished (resume it)")
            return report
        names = shard_names(info)
    except DataError as e:
        report.problems.append(str(e))
        return report
    rows = _manifest_rows(layout, report)
    seen: set[str] = set()
    for name, shard in zip(names, info["shards"], strict=True):
        report.shards += 1
        _check_shard(layout.shards / name, shard, rows, seen, report)
    missing = [k for k, r in rows.items() if r["status"] == "ok" and k not in seen]
    if missing:
        report.problems.append(f"{missing[0]}: in the manifest but in no shard "
                               f"({len(missing)} episodes)")
    config = info.get("config")
    n = config.get("n") if isinstance(config, dict) else None
    if n != len(rows):
        report.problems.append(f"episodes.parquet: {len(rows)} rows, expected "
                               f"{excerpt(str(n), 20)} (dataset.json's config n)")
    return report


_ROW_TYPES = {"key": str, "status": str, "num_frames": int}


def _manifest_rows(layout: Layout, report: Report) -> dict[str, dict[str, Any]]:
    """The manifest's rows by key, each of the right shape (the others reported)."""
    try:
        table = read_manifest(layout.manifest_path)
    except HomesimError as e:
        report.problems.append(str(e))
        return {}
    rows: dict[str, dict[str, Any]] = {}
    for i, row in enumerate(table):
        bad = next((f"{k!r} must be {t.__name__}" for k, t in _ROW_TYPES.items()
                    if type(row.get(k)) is not t), None)
        if bad is None and row["status"] not in ("ok", "failed"):
            bad = "'status' must be ok or failed"
        if bad is None and row["status"] == "ok" and not isinstance(row.get("sha256"), str):
            bad = "'sha256' must be a string for an episode that is ok"
        if bad is None and row["key"] in rows:
            bad = f"key {_shown(row['key'])} comes twice"
        if bad is not None:
            report.problems.append(f"episodes.parquet: row {i}: {bad}")
            continue
        rows[row["key"]] = row
    report.episodes = len(rows)
    report.ok = sum(1 for r in rows.values() if r["status"] == "ok")
    return rows


def _check_shard(path: Path, shard: dict[str, Any], rows: dict[str, dict[str, Any]],
                 seen: set[str], report: Report) -> None:
    if not path.exists() and not path.is_symlink():
        report.problems.append(f"{path.name}: missing")
        return
    sha: list[str] = []
    try:
        for episode in scan_shard(path, sha):
            _check_episode(path.name, episode, rows, seen, report)
    except HomesimError as e:
        report.problems.append(str(e).removeprefix(f"{path.parent}/"))
        return
    if sha and sha[0] != shard.get("sha256"):
        report.problems.append(f"{path.name}: checksum differs from dataset.json")


def _check_episode(shard: str, episode: ScannedEpisode, rows: dict[str, dict[str, Any]],
                   seen: set[str], report: Report) -> None:
    key = episode.key
    seen.add(key)
    row = rows.get(key)
    if row is None:
        report.problems.append(f"{shard}: {_shown(key)}: not in the manifest")
        return
    if episode.sha256 != row["sha256"]:
        report.problems.append(f"{shard}: {_shown(key)}: checksum differs from the manifest")
    problem = _check_members(episode, row)
    if problem:
        report.problems.append(f"{shard}: {problem}")
    report.frames += row["num_frames"]


def _check_members(episode: ScannedEpisode, row: dict[str, Any]) -> str | None:
    """What is wrong with an episode's members (naming the member), or None."""
    key, json_name = episode.key, f"{episode.key}.json"
    if episode.meta is None:
        return f"{_shown(json_name)}: missing (or over {MAX_META_BYTES >> 20} MiB)"
    try:
        meta = json.loads(episode.meta)
    except (ValueError, RecursionError):
        return f"{_shown(json_name)}: not JSON"
    fields = _meta_fields(meta)
    if isinstance(fields, str):
        return f"{_shown(json_name)}: {fields}"
    frames, stride, modalities = fields
    if frames != row["num_frames"]:
        return (f"{_shown(json_name)}: says {frames} frames, the manifest "
                f"{row['num_frames']}")
    for modality in MAPS:
        if modality in modalities:
            have = sum(1 for n in episode.names if n.endswith(f".{modality}.png"))
            want = -(-frames // stride)
            if have != want:
                return f"{_shown(key)}: {have} {modality} frames, expected {want}"
    if "rgb" in modalities and f"{key}.mp4" not in episode.names:
        return f"{_shown(key + '.mp4')}: missing"
    return None


def _meta_fields(meta: Any) -> tuple[int, int, list[str]] | str:
    """(num_frames, gt_stride, modalities) of an episode json, or what is wrong with it."""
    if not isinstance(meta, dict):
        return "expected a JSON object"
    frames, stride, modalities = (meta.get(k) for k in ("num_frames", "gt_stride",
                                                        "modalities"))
    if type(frames) is not int or frames < 0:
        return f"'num_frames' must be a count, got {excerpt(str(frames), 20)}"
    if type(stride) is not int or stride < 1:
        return f"'gt_stride' must be at least 1, got {excerpt(str(stride), 20)}"
    if not (isinstance(modalities, list) and all(isinstance(m, str) for m in modalities)):
        return "'modalities' must be a list of names"
    return frames, stride, modalities


def _shown(name: str) -> str:
    """A member name as a report line quotes it: printable, cut short."""
    shown = excerpt(name, 80)
    return shown if shown.isprintable() else repr(shown)
