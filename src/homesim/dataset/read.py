"""Read episodes back from shards as numpy arrays (no PyTorch needed).

`read_episodes(shard)` yields one dict per episode:

    key, meta (the episode json: program, description, steps, legends, cameras...)
    step       (T,) int16   the step each frame shows (-1 for none)
    rgb        (T, H, W, 3) uint8        (from the H.264 video)
    depth      (T', H, W) float32 metres (0 = nothing seen)
    class      (T', H, W) int32 class index (meta["classes"])
    instance   (T', H, W) int32 instance index (meta["instances"])
    flow       (T', H, W, 2) float32 pixels to the next frame; flow_valid (T', H, W) bool
    gt_frames  (T',) int64  the frames the maps belong to (every gt_stride-th)
    camera, intrinsics, world_to_cam, joints3d, joints2d, joints_visible, cut: per frame

Only the modalities asked for are decoded (the arrays are always there).
"""

from __future__ import annotations

import io
import json
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from homesim.dataset import encode
from homesim.dataset.episode import ARRAYS
from homesim.dataset.layout import Layout
from homesim.dataset.verify import iter_episodes
from homesim.errors import DataError
from homesim.render.video import decode_video, iter_video

MAPS = ("depth", "class", "instance", "flow")


def _decode_map(kind: str, data: bytes) -> tuple[np.ndarray, ...]:
    if kind == "depth":
        return (encode.decode_depth(data),)
    if kind == "flow":
        return encode.decode_flow(data)
    return (encode.read_png16(data).astype(np.int32),)


class EncodedEpisode:
    """An episode's members held compressed (~35 KB a frame at 320x240), decoded on
    demand: a clip decodes only its own frames."""

    def __init__(self, key: str, members: list[tuple[str, bytes]]):
        by_name = dict(members)
        self.key = key
        self.meta: dict[str, Any] = json.loads(by_name[f"{key}.json"])
        self.arrays = {name: np.load(io.BytesIO(by_name[f"{key}.{name}.npy"]),
                                     allow_pickle=False) for name in ARRAYS}
        self.video = by_name.get(f"{key}.mp4")
        self.maps: dict[str, dict[int, bytes]] = {}  # kind -> frame -> PNG
        for name, data in members:
            parts = name.split(".")  # KEY.NNNNNN.kind.png
            if len(parts) == 4 and parts[2] in MAPS:
                self.maps.setdefault(parts[2], {})[int(parts[1])] = data

    @property
    def num_frames(self) -> int:
        return int(self.meta["num_frames"])

    def iter_rgb(self) -> Iterator[np.ndarray]:
        if self.video is None:
            raise DataError(f"{self.key}: the data set has no rgb video")
        return iter_video(self.video, (self.meta["width"], self.meta["height"]))

    def gt_frames(self, a: int, b: int) -> list[int]:
        """Frames in [a, b) that have dense maps (all of them unless --gt-stride)."""
        stride = self.meta["gt_stride"]
        return list(range(-(-a // stride) * stride, b, stride))

    def decode_maps(self, modalities: Iterable[str], a: int, b: int) -> dict[str, np.ndarray]:
        """The maps asked for, stacked over the frames of [a, b) that have them."""
        frames = self.gt_frames(a, b)
        out: dict[str, np.ndarray] = {}
        for kind in MAPS:
            if kind not in modalities:
                continue
            if kind not in self.maps:
                raise DataError(f"{self.key}: the data set has no {kind} maps")
            decoded = [_decode_map(kind, self.maps[kind][f]) for f in frames]
            out[kind] = np.stack([d[0] for d in decoded])
            if kind == "flow":
                out["flow_valid"] = np.stack([d[1] for d in decoded])
        return out


def decode_episode(key: str, members: list[tuple[str, bytes]],
                   modalities: Iterable[str] = ("rgb",)) -> dict[str, Any]:
    """One episode's members -> the dict described in the module docstring (every frame
    decoded: ~1.8 MB a frame at 320x240 with every modality; clips use `EncodedEpisode`)."""
    wanted = set(modalities)
    ep = EncodedEpisode(key, members)
    out: dict[str, Any] = {"key": key, "meta": ep.meta, **ep.arrays}
    if "rgb" in wanted and ep.video is not None:
        out["rgb"] = decode_video(ep.video, ep.meta["width"], ep.meta["height"])
    if wanted & set(MAPS):
        out.update(ep.decode_maps(wanted, 0, ep.num_frames))
        out["gt_frames"] = np.asarray(ep.gt_frames(0, ep.num_frames), np.int64)
    return out


def shard_paths(source: str | Path | Iterable[str | Path]) -> list[Path]:
    """The finished shards of a data set folder (all of them once the run is complete), or
    the given tar paths."""
    if isinstance(source, (str, Path)):
        root = Path(source)
        if root.is_dir():
            layout = Layout(root)
            return [layout.shards / s["name"] for s in layout.finished_shards()]
        return [root]
    return [Path(p) for p in source]


def read_episodes(source: str | Path | Iterable[str | Path],
                  modalities: Iterable[str] = ("rgb",)) -> Iterator[dict[str, Any]]:
    """Every episode of a data set folder or of the given shards, in order."""
    wanted = tuple(modalities)
    for shard in shard_paths(source):
        for key, members in iter_episodes(shard):
            yield decode_episode(key, members, wanted)
