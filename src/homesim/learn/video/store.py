"""Every frame of a data set in a few arrays on disk, read through memory maps: what the
frame models (`framecnn`, `segment`) train and compute features on.

A 5 000-episode set at 64x48 and 4 frames/s holds ~500 000 frames (~5 GB of RGB): too
much to hold in memory on a small machine, and random batches from per-episode files
would read each file many times. So the reduced episodes (`cache`) are written once, in
order, into

    <store>/frames.npy   (N, 3, H, W) uint8   RGB
    <store>/maps.npy     (N, H/2, W/2) uint8  ground-truth class map (`classes` index)
    <store>/step.npy     (N,) int16           the episode step shown (-1: none)
    <store>/joints.npy   (N, J, 3) float16    the agent's 2-D joints: x, y as shares of
                                              the frame, visible (1/0)
    <store>/index.json   classes; per episode its part, key, first row, frame count,
                         home, agent, fps, step texts, title, description, program

and opened with ``np.load(mmap_mode="r")``: the operating system pages in what a batch
needs. The store is named by a hash of what it is made of (the episodes' member
checksums, the format, the parts), so it is built once and never goes stale; a build
stopped midway leaves no index and is begun again.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from homesim.errors import HomesimError
from homesim.files import write_text

STORE_VERSION = 2


@dataclass(frozen=True)
class StoredEpisode:
    """One episode's place in the store and what learning needs to know of it."""

    key: str
    part: str
    start: int  # first row
    length: int
    home: str
    agent: str
    fps: int
    steps: list[str]  # step texts (the program's), indexed by `step.npy`
    program: str  # title, description, blank line, steps: `parse_program` reads it

    @property
    def rows(self) -> np.ndarray:
        return np.arange(self.start, self.start + self.length)


class FrameStore:
    """The arrays of a built store (memory-mapped) and its episodes."""

    def __init__(self, root: Path):
        self.root = root
        index = json.loads((root / "index.json").read_text(encoding="utf-8"))
        self.classes: list[str] = index["classes"]
        self.episodes = [StoredEpisode(**e) for e in index["episodes"]]
        self.frames = np.load(root / "frames.npy", mmap_mode="r")
        self.maps = np.load(root / "maps.npy", mmap_mode="r")
        self.step = np.load(root / "step.npy")
        self.joints = np.load(root / "joints.npy", mmap_mode="r")

    def part(self, name: str) -> list[StoredEpisode]:
        return [e for e in self.episodes if e.part == name]

    def rows(self, episodes: list[StoredEpisode]) -> np.ndarray:
        """Every row of the episodes, in order."""
        if not episodes:
            return np.zeros(0, np.int64)
        return np.concatenate([e.rows for e in episodes])


def store_name(items: list[tuple[str, str, str]], tag: str) -> str:
    """A name for the store of (part, key, reduced file name) items at a format `tag`
    (the file is named by the episode's member checksum)."""
    digest = hashlib.sha256(json.dumps([STORE_VERSION, tag, items]).encode()).hexdigest()
    return f"store-{tag}-{digest[:16]}"


def _lut(local: list[str], index: dict[str, int]) -> np.ndarray:
    return np.array([index[n] for n in local], np.uint8)


def _read_meta(path: Path) -> tuple[dict[str, Any], int]:
    with np.load(path, allow_pickle=False) as data:
        return json.loads(str(data["meta"])), len(data["step"])


def build_store(root: Path, items: list[tuple[str, str, Path]]) -> FrameStore:
    """Write the store at `root` from (part, key, reduced episode file) items (`cache`: frames,
    maps with the episode's own class ids, step, meta), unless it is there. Streams: one
    episode in memory at a time."""
    if (root / "index.json").is_file():
        return FrameStore(root)
    metas = [_read_meta(path) for _, _, path in items]
    classes = ["background", *sorted({n for m, _ in metas for n in m["classes"]}
                                     - {"background"})]
    if len(classes) > 256:
        raise HomesimError(f"{len(classes)} object classes: class maps hold at most 256")
    index = {n: i for i, n in enumerate(classes)}
    total = sum(n for _, n in metas)
    with np.load(items[0][2], allow_pickle=False) as data:
        frame_shape, map_shape = data["frames"].shape[1:], data["maps"].shape[1:]
        joint_shape = data["joints"].shape[1:]
    root.mkdir(parents=True, exist_ok=True)
    frames = np.lib.format.open_memmap(root / "frames.npy", "w+", np.uint8,
                                       (total, *frame_shape))
    maps = np.lib.format.open_memmap(root / "maps.npy", "w+", np.uint8, (total, *map_shape))
    joints = np.lib.format.open_memmap(root / "joints.npy", "w+", np.float16,
                                       (total, *joint_shape))
    step = np.zeros(total, np.int16)
    stored, row = [], 0
    for (part, key, path), (meta, n) in zip(items, metas, strict=True):
        with np.load(path, allow_pickle=False) as data:
            frames[row:row + n] = data["frames"]
            maps[row:row + n] = _lut(meta["classes"], index)[data["maps"]]
            step[row:row + n] = data["step"]
            joints[row:row + n] = data["joints"]
        program = f"{meta['title']}\n{meta['description']}\n\n{meta['program']}"
        stored.append(StoredEpisode(key, part, row, n, meta["home"], meta["agent"],
                                    int(meta["fps"]), meta["steps"], program).__dict__)
        row += n
    for array in (frames, maps, joints):
        array.flush()
    del frames, maps, joints
    np.save(root / "step.npy", step)
    write_text(root / "index.json", json.dumps({"version": STORE_VERSION,
                                                "classes": classes, "episodes": stored}),
               force=True)
    return FrameStore(root)
