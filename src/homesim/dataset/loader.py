"""`ActivityClips`: a PyTorch `IterableDataset` that streams the shards of a data set.

It yields whole episodes (``clip_seconds=None``) or fixed-length clips (default 2 s,
non-overlapping unless `clip_hop` is smaller) with the modalities asked for, as tensors:

    key (str), clip_start (int, frame), fps (int)
    rgb (T, H, W, 3) uint8; depth (T, H, W) float32 m; class, instance (T, H, W) int32;
    flow (T, H, W, 2) float32 px, flow_valid (T, H, W) bool   (each only if asked)
    joints2d (T, J, 2), joints3d (T, J, 3), joints_visible (T, J), intrinsics (T, 3, 3),
    world_to_cam (T, 4, 4), camera (T,) : always
    step (T,) int64: the program step each frame shows (-1 for none)
    label (str): the step shown in most of the clip's frames (``[Grab] <cup> (1)``)
    action (str): its action (``GRAB``); steps (str): the clip's steps, one per line
    program, description (str): the whole episode's

Whole episodes add ``meta`` (the episode json; use ``batch_size=None``). With
``DataLoader(num_workers=k)`` each worker reads every k-th shard, so no episode is read
twice; under torch.distributed, ranks split the shards first.
"""

from __future__ import annotations

import random
from collections import Counter
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import torch
from torch.utils.data import IterableDataset, get_worker_info

from homesim.dataset.read import MAPS, EncodedEpisode, shard_paths
from homesim.dataset.verify import iter_episodes
from homesim.errors import HomesimError

_PER_FRAME = ("camera", "intrinsics", "world_to_cam", "joints3d", "joints2d",
              "joints_visible")


class ActivityClips(IterableDataset):
    """Clips (or episodes) of an activity data set; see the module docstring.

    >>> ActivityClips([], modalities=("rgb", "depth")).clip_seconds
    2.0
    """

    def __init__(self, source: str | Path | Iterable[str | Path], *,
                 clip_seconds: float | None = 2.0, clip_hop: float | None = None,
                 modalities: Iterable[str] = ("rgb",), shuffle_shards: bool = False,
                 seed: int = 0):
        self.shards = shard_paths(source)
        self.clip_seconds, self.clip_hop = clip_seconds, clip_hop
        self.modalities = tuple(modalities)
        unknown = [m for m in self.modalities if m not in ("rgb", *MAPS)]
        if unknown:
            raise HomesimError(f"unknown modality {unknown[0]!r}; choose from rgb, "
                               f"{', '.join(MAPS)}")
        self.shuffle_shards, self.seed, self.epoch = shuffle_shards, seed, 0

    def set_epoch(self, epoch: int) -> None:
        """Reshuffle the shard order (with `shuffle_shards`) for another epoch."""
        self.epoch = epoch

    def my_shards(self) -> list[Path]:
        """The shards this process and DataLoader worker reads."""
        shards = list(self.shards)
        if self.shuffle_shards:
            random.Random(f"{self.seed}-{self.epoch}").shuffle(shards)
        if torch.distributed.is_available() and torch.distributed.is_initialized():
            shards = shards[torch.distributed.get_rank()::torch.distributed.get_world_size()]
        info = get_worker_info()
        return shards if info is None else shards[info.id::info.num_workers]

    def __iter__(self) -> Iterator[dict[str, Any]]:
        for shard in self.my_shards():
            for key, members in iter_episodes(shard):
                ep = EncodedEpisode(key, members)
                if self.clip_seconds is None:
                    item = _window(ep, self.modalities, 0, ep.num_frames, _RgbWindow(ep))
                    item["meta"] = ep.meta
                    yield item
                else:
                    yield from _clips(ep, self.modalities, self.clip_seconds,
                                      self.clip_hop or self.clip_seconds)


class _RgbWindow:
    """Frames of the episode's video decoded in order, keeping only those still needed
    (clips come in order): memory holds one clip, not the episode."""

    def __init__(self, ep: EncodedEpisode):
        self.frames_iter = ep.iter_rgb() if ep.video is not None else None
        self.base = 0
        self.frames: list[np.ndarray] = []

    def get(self, a: int, b: int) -> np.ndarray:
        assert self.frames_iter is not None  # asked for only when there is a video
        while self.base < a:
            if self.frames:
                self.frames.pop(0)
            else:
                next(self.frames_iter)
            self.base += 1
        while self.base + len(self.frames) < b:
            self.frames.append(next(self.frames_iter))
        return np.stack(self.frames[:b - a])


def _clips(ep: EncodedEpisode, modalities: tuple[str, ...], seconds: float, hop: float
           ) -> Iterator[dict[str, Any]]:
    fps = ep.meta["fps"]
    length, step = max(1, round(seconds * fps)), max(1, round(hop * fps))
    video = _RgbWindow(ep)
    for start in range(0, ep.num_frames - length + 1, step):
        yield _window(ep, modalities, start, start + length, video)


def _window(ep: EncodedEpisode, modalities: tuple[str, ...], a: int, b: int,
            video: _RgbWindow) -> dict[str, Any]:
    """Frames [a, b) of an episode as a clip (see the module docstring)."""
    meta = ep.meta
    steps = ep.arrays["step"][a:b].astype(np.int64)
    shown = [int(s) for s in steps if s >= 0]
    texts = meta["steps"]
    main = Counter(shown).most_common(1)[0][0] if shown else -1
    item: dict[str, Any] = {
        "key": ep.key, "clip_start": a, "fps": meta["fps"],
        "step": torch.from_numpy(steps),
        "label": texts[main]["step"] if main >= 0 else "",
        "action": texts[main]["action"] if main >= 0 else "",
        "steps": "\n".join(texts[i]["step"] for i in sorted(set(shown))),
        "program": meta["program"], "description": meta["description"],
    }
    for name in _PER_FRAME:
        item[name] = torch.from_numpy(np.ascontiguousarray(ep.arrays[name][a:b]))
    if "rgb" in modalities:
        item["rgb"] = torch.from_numpy(video.get(a, b))
    for name, array in ep.decode_maps(modalities, a, b).items():
        item[name] = torch.from_numpy(array)
    return item
