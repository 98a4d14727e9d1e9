"""Episodes of an activity data set (`homesim dataset generate`) held small for learning.

Each episode keeps, at the clip models' `VideoFormat` (`homesim.learn.video.cache`: frame
rate and size, cached per episode), its RGB frames and per frame the share of pixels of
every object class (the *oracle perception* input: the ground-truth class segmentation
instead of RGB), with the step each frame shows. 2-second clips are cut from it, labelled
with the step they mostly show; the whole episode is a video -> program example.
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from homesim.dataset.layout import Layout
from homesim.errors import HomesimError
from homesim.learn.data import Example
from homesim.learn.video.cache import VideoFormat, episode_rows, fill_cache, shard_episodes
from homesim.program.parse import parse_program

CLIP_SECONDS = 2.0
_INSTANCE = re.compile(r"\s*\(\d+\)")


def step_class(step_text: str) -> str:
    """A step's class for clip recognition: action and object classes, no instance numbers
    (``[Grab] <cup> (1)`` -> ``[Grab] <cup>``)."""
    return _INSTANCE.sub("", step_text).strip()


@dataclass
class Episode:
    """One episode, small: frames (T, 3, h, w) uint8, classes (T, C) float32 pixel shares
    over `ClassIndex`, step (T,) int (-1 for none), and its program as an `Example`."""

    key: str
    home: str
    agent: str
    fps: int
    frames: np.ndarray
    classes: np.ndarray
    step: np.ndarray
    step_texts: list[str]
    example: Example

    def clips(self, seconds: float = CLIP_SECONDS, hop: float | None = None
              ) -> list[tuple[int, int, str]]:
        """Windows (start, end, step class) that show a step, every `hop` seconds
        (default: non-overlapping)."""
        length = max(1, round(seconds * self.fps))
        step = max(1, round((hop or seconds) * self.fps))
        out = []
        for a in range(0, len(self.step) - length + 1, step):
            shown = [int(s) for s in self.step[a:a + length] if s >= 0]
            if shown:
                main = Counter(shown).most_common(1)[0][0]
                out.append((a, a + length, step_class(self.step_texts[main])))
        return out


def class_index(names: list[str]) -> dict[str, int]:
    """Global class name -> column (0 is background and unknown classes)."""
    return {n: i for i, n in enumerate(["background", *sorted(set(names) - {"background"})])}


def _global_shares(shares: np.ndarray, names: list[str], index: dict[str, int]
                   ) -> np.ndarray:
    """(T, local classes) shares -> (T, len(index)) shares of the global columns."""
    columns = np.zeros((len(names), len(index)), np.float32)
    columns[np.arange(len(names)), [index.get(n, 0) for n in names]] = 1.0
    return shares @ columns


def _folder_episodes(folder: Path, fmt: VideoFormat, cache: Path | None, workers: int
                     ) -> list[dict]:
    """The reduced episodes of a data set folder's finished shards (a run still going
    gives the shards written so far)."""
    if not (folder / "dataset.json").is_file():
        raise HomesimError(f"{folder}: not a data set folder (run 'homesim dataset generate')")
    layout = Layout(folder)
    shards = [(layout.shards / s["name"], episode_rows(s["rows"]))
              for s in layout.finished_shards()]
    if cache is not None:
        fill_cache(shards, fmt, cache, workers)
    out = [e for shard, rows in shards for e in shard_episodes(shard, rows, fmt, cache)]
    if not out:
        raise HomesimError(f"{folder}: no finished shards (run 'homesim dataset generate')")
    return out


def load_episodes(source: Path | str, fmt: VideoFormat | None = None,
                  cache: Path | None = None, workers: int = 1
                  ) -> tuple[list[Episode], dict[str, int]]:
    """Every episode of a data set folder, or of several separated by commas (keys become
    ``<folder name>/<key>``), at `fmt` (`videocache`; reduced shards are kept in `cache`,
    made by `workers` processes). Needs the rgb and class modalities."""
    fmt = fmt or VideoFormat()
    folders = [Path(p) for p in str(source).split(",")]
    raw = [(folder, r) for folder in folders
           for r in _folder_episodes(folder, fmt, cache, workers)]
    index = class_index([n for _, r in raw for n in r["meta"]["classes"]])
    episodes = []
    for folder, r in raw:
        meta = r["meta"]
        key = f"{folder.name}/{meta['key']}" if len(folders) > 1 else meta["key"]
        program = parse_program(f"{meta['title']}\n{meta['description']}\n\n{meta['program']}")
        example = Example(key, program, source=str(folder), home=meta["home"])
        episodes.append(Episode(
            key, meta["home"], meta["agent"], int(meta["fps"]), r["frames"],
            _global_shares(r["shares"], meta["classes"], index), r["step"], meta["steps"],
            example))
    return episodes, index
