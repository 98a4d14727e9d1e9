"""Episodes of an activity data set (`homesim dataset generate`) held small for learning.

Each episode keeps, per frame, its RGB image average-pooled to `FRAME_SIZE` and the
share of pixels of every object class (the *oracle perception* input: the ground-truth
class segmentation instead of RGB), with the step each frame shows. 2-second clips are
cut from it, labelled with the step they mostly show; the whole episode is a
video -> program example.
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from homesim.dataset.read import read_episodes
from homesim.errors import HomesimError
from homesim.learn.data import Example
from homesim.program.parse import parse_program

FRAME_SIZE = (24, 32)
"""(height, width) of the frames the clip models read."""
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


def _pool(rgb: np.ndarray) -> np.ndarray:
    """(T, H, W, 3) uint8 -> (T, 3, h, w) uint8 averaged over blocks to `FRAME_SIZE`."""
    t, height, width, _ = rgb.shape
    h, w = FRAME_SIZE
    if height % h or width % w:
        raise HomesimError(f"frames of {width}x{height} do not pool to {w}x{h}: generate "
                           f"with a size that is a multiple of it (e.g. --width 64 --height 48)")
    blocks = rgb.reshape(t, h, height // h, w, width // w, 3).mean((2, 4))
    return blocks.transpose(0, 3, 1, 2).round().astype(np.uint8)


def _class_shares(classes: np.ndarray, names: list[str], index: dict[str, int]) -> np.ndarray:
    """(T, H, W) per-episode class ids -> (T, len(index)) pixel shares of global classes."""
    local_to_global = np.array([index.get(n, 0) for n in names], np.int64)
    ids = local_to_global[np.clip(classes, 0, len(names) - 1)]
    t = ids.shape[0]
    out = np.zeros((t, len(index)), np.float32)
    for i in range(t):
        out[i] = np.bincount(ids[i].ravel(), minlength=len(index))[:len(index)]
    return out / max(1, ids[0].size)


def class_index(names: list[str]) -> dict[str, int]:
    """Global class name -> column (0 is background and unknown classes)."""
    return {n: i for i, n in enumerate(["background", *sorted(set(names) - {"background"})])}


def _read(folders: list[Path]) -> list[dict]:
    """Episodes of the folders; with several, keys become ``<folder name>/<key>``."""
    raw = []
    for folder in folders:
        got = list(read_episodes(folder, ("rgb", "class")))
        if not got:
            raise HomesimError(f"{folder}: no finished shards (run 'homesim dataset generate')")
        for r in got:
            r["key"] = f"{folder.name}/{r['key']}" if len(folders) > 1 else r["key"]
        raw += got
    return raw


def load_episodes(source: Path | str) -> tuple[list[Episode], dict[str, int]]:
    """Every episode of a data set folder, or of several separated by commas (needs the
    rgb and class modalities)."""
    folders = [Path(p) for p in str(source).split(",")]
    raw = _read(folders)
    folder = source
    index = class_index([n for r in raw for n in r["meta"]["classes"]])
    episodes = []
    for r in raw:
        meta = r["meta"]
        if "class" not in r or "rgb" not in r:
            raise HomesimError(f"{folder}: episodes need --modalities rgb,class")
        if meta["gt_stride"] != 1:
            raise HomesimError(f"{folder}: class maps are needed on every frame (--gt-stride 1)")
        program = parse_program(f"{meta['title']}\n{meta['description']}\n\n{meta['program']}")
        example = Example(r["key"], program, source=str(folder), home=meta["home"])
        episodes.append(Episode(
            r["key"], meta["home"], meta["agent"], int(meta["fps"]), _pool(r["rgb"]),
            _class_shares(r["class"], meta["classes"], index), np.asarray(r["step"], np.int64),
            [s["step"] for s in meta["steps"]], example))
    return episodes, index
