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
import tempfile
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from homesim.dataset import encode
from homesim.dataset.episode import ARRAYS
from homesim.dataset.layout import Layout
from homesim.dataset.verify import iter_episodes

MAPS = ("depth", "class", "instance", "flow")


def decode_video(data: bytes, width: int, height: int) -> np.ndarray:
    """(T, H, W, 3) uint8 frames of an H.264 mp4 given as bytes."""
    import imageio_ffmpeg

    with tempfile.NamedTemporaryFile(suffix=".mp4") as f:
        f.write(data)
        f.flush()
        reader = imageio_ffmpeg.read_frames(f.name, pix_fmt="rgb24")
        next(reader)  # the header
        frames = [np.frombuffer(b, np.uint8).reshape(height, width, 3) for b in reader]
    return np.stack(frames) if frames else np.zeros((0, height, width, 3), np.uint8)


def _decode_map(kind: str, data: bytes) -> tuple[np.ndarray, ...]:
    if kind == "depth":
        return (encode.decode_depth(data),)
    if kind == "flow":
        return encode.decode_flow(data)
    return (encode.read_png16(data).astype(np.int32),)


def decode_episode(key: str, members: list[tuple[str, bytes]],
                   modalities: Iterable[str] = ("rgb",)) -> dict[str, Any]:
    """One episode's members -> the dict described in the module docstring."""
    wanted = set(modalities)
    by_name = dict(members)
    meta = json.loads(by_name[f"{key}.json"])
    out: dict[str, Any] = {"key": key, "meta": meta}
    for name in ARRAYS:
        out[name] = np.load(io.BytesIO(by_name[f"{key}.{name}.npy"]), allow_pickle=False)
    if "rgb" in wanted and f"{key}.mp4" in by_name:
        out["rgb"] = decode_video(by_name[f"{key}.mp4"], meta["width"], meta["height"])
    maps: dict[str, list[np.ndarray]] = {}
    frames: list[int] = []
    for name, data in members:
        parts = name.split(".")  # KEY.NNNNNN.kind.png
        if len(parts) != 4 or parts[2] not in wanted:
            continue
        index, kind = int(parts[1]), parts[2]
        decoded = _decode_map(kind, data)
        maps.setdefault(kind, []).append(decoded[0])
        if kind == "flow":
            maps.setdefault("flow_valid", []).append(decoded[1])
        if kind == _first_map(wanted):
            frames.append(index)
    for kind, arrays in maps.items():
        out[kind] = np.stack(arrays)
    if maps:
        out["gt_frames"] = np.asarray(frames, np.int64)
    return out


def _first_map(wanted: set[str]) -> str | None:
    return next((m for m in MAPS if m in wanted), None)


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
