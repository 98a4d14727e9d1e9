"""Episodes of a data set shard reduced once to what the clip models read, and cached.

A 320x240, 15 fps episode with every modality is ~50 MB compressed and several GB
decoded; the clip models read small frames at a few frames per second (a 2-s clip's
`clips.ClipConfig.frames` = 8 frames are every frame at the default 4 frames/s).
`shard_episodes(shard, fmt, cache)` streams each episode of a shard once: frames are kept
at `VideoFormat.fps` (the nearest source frame of each tick; never more than the source
has), RGB is area-scaled to the format's size by ffmpeg while decoding, and each kept
frame's ground-truth class map is sampled at half the format's size (the segmentation
network's target and the oracle's input, with layout), and its agent's 2-D joints as
shares of the frame with their visibility (the pose network's target). The result is
written to
``<cache>/<format>/<episode checksum>.npz`` and read from there the next time (an
episode is identified by its member checksum, so a cache file never goes stale, and the
episodes of a generation still running can be cached from its staging folder:
`warm_staged`); ~1 MB an episode of 100 frames at 64x48.
"""

from __future__ import annotations

import json
import logging
import tempfile
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from homesim.dataset import encode
from homesim.dataset.read import EncodedEpisode
from homesim.dataset.verify import iter_episodes
from homesim.errors import HomesimError
from homesim.files import atomic_write

CACHE_VERSION = 3
ARRAYS = ("frames", "maps", "step", "joints")
META_FIELDS = ("key", "home", "agent", "title", "description", "program", "classes")


@dataclass(frozen=True)
class VideoFormat:
    """Frame size and rate the clip models read."""

    width: int = 64
    height: int = 48
    fps: int = 4

    @classmethod
    def parse(cls, size: str, fps: int = 4) -> VideoFormat:
        """From ``WIDTHxHEIGHT`` (e.g. ``64x48``)."""
        try:
            w, h = (int(v) for v in size.lower().split("x"))
        except ValueError:
            raise HomesimError(f"frame size {size!r}: write WIDTHxHEIGHT, e.g. 64x48") from None
        if w < 8 or h < 8 or fps < 1:
            raise HomesimError(f"frame size {size!r} at {fps} fps: at least 8x8 and 1 fps")
        return cls(w, h, fps)

    @property
    def tag(self) -> str:
        return f"{self.width}x{self.height}@{self.fps}"


def kept_frames(num_frames: int, source_fps: int, fps: int) -> np.ndarray:
    """Indices of the source frames kept at `fps` (all of them if the source is slower)."""
    if source_fps <= fps:
        return np.arange(num_frames)
    ticks = np.arange(int((num_frames - 1) * fps / source_fps) + 1)
    return np.unique(np.minimum(np.round(ticks * source_fps / fps), num_frames - 1)
                     ).astype(np.int64)


def small_video(data: bytes, fmt: VideoFormat) -> np.ndarray:
    """(T, 3, height, width) uint8: every frame of an H.264 mp4 given as bytes, scaled by
    ffmpeg (area filter) while decoding: ~25x fewer bytes through the pipe at 320x240."""
    import imageio_ffmpeg  # deferred: the dataset extra's, needed only to decode

    logging.getLogger("imageio_ffmpeg").setLevel(logging.ERROR)  # "size differs": we ask it to
    with tempfile.NamedTemporaryFile(suffix=".mp4") as f:
        f.write(data)
        f.flush()
        reader = imageio_ffmpeg.read_frames(
            f.name, pix_fmt="rgb24",
            output_params=["-vf", f"scale={fmt.width}:{fmt.height}:flags=area"])
        try:
            next(reader)  # the header
            frames = [np.frombuffer(b, np.uint8) for b in reader]
        finally:
            reader.close()
    if not frames:
        return np.zeros((0, 3, fmt.height, fmt.width), np.uint8)
    return np.stack(frames).reshape(-1, fmt.height, fmt.width, 3).transpose(0, 3, 1, 2)


def _rgb(ep: EncodedEpisode, keep: np.ndarray, fmt: VideoFormat) -> np.ndarray:
    """The kept frames of the episode's video, scaled to `fmt`."""
    if ep.video is None:
        raise HomesimError(f"{ep.key}: the clip models need the rgb video "
                           "(generate with --modalities rgb,class)")
    frames = small_video(ep.video, fmt)
    if len(frames) <= keep[-1]:
        raise HomesimError(f"{ep.key}: the video has {len(frames)} frames, the episode "
                           f"{ep.num_frames}")
    return np.ascontiguousarray(frames[keep])


def _maps(ep: EncodedEpisode, keep: np.ndarray, fmt: VideoFormat) -> np.ndarray:
    """(kept, height/2, width/2) uint8: each kept frame's class map at half the format's
    size (the pixel nearest each cell's centre), in the episode's own class ids."""
    if ep.meta["gt_stride"] != 1 or "class" not in ep.maps:
        raise HomesimError(f"{ep.key}: the clip models need class maps on every frame "
                           "(generate with --modalities rgb,class and --gt-stride 1)")
    n = len(ep.meta["classes"])
    if n > 256:
        raise HomesimError(f"{ep.key}: {n} object classes; class maps hold at most 256")
    h, w = fmt.height // 2, fmt.width // 2
    out = np.zeros((len(keep), h, w), np.uint8)
    for row, f in enumerate(keep.tolist()):
        full = encode.read_png16(ep.maps["class"][f])
        ys = ((np.arange(h) + 0.5) * full.shape[0] / h).astype(np.int64)
        xs = ((np.arange(w) + 0.5) * full.shape[1] / w).astype(np.int64)
        out[row] = np.clip(full[np.ix_(ys, xs)], 0, n - 1)
    return out


def _joints(ep: EncodedEpisode, keep: np.ndarray) -> np.ndarray:
    """(kept, J, 3) float16: each kept frame's joints as shares of the frame's width and
    height, and their visibility (1 or 0)."""
    size = np.array([ep.meta["width"], ep.meta["height"]], np.float32)
    xy = np.asarray(ep.arrays["joints2d"], np.float32)[keep] / size
    seen = np.asarray(ep.arrays["joints_visible"], np.float32)[keep]
    return np.concatenate([xy, seen[..., None]], 2).astype(np.float16)


def reduce_episode(ep: EncodedEpisode, fmt: VideoFormat) -> dict[str, Any]:
    """One episode as arrays at `fmt`: frames, class maps at half size, step, joints, and
    its meta."""
    meta = ep.meta
    keep = kept_frames(ep.num_frames, int(meta["fps"]), fmt.fps)
    return {"frames": _rgb(ep, keep, fmt), "maps": _maps(ep, keep, fmt),
            "step": np.asarray(ep.arrays["step"], np.int64)[keep],
            "joints": _joints(ep, keep),
            "meta": {**{k: meta[k] for k in META_FIELDS},
                     "fps": min(int(meta["fps"]), fmt.fps),
                     "steps": [s["step"] for s in meta["steps"]]}}


def _write(path: Path, episode: dict[str, Any]) -> None:
    arrays = {"meta": np.array(json.dumps(episode["meta"])),
              **{name: episode[name] for name in ARRAYS}}
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_write(path, "wb") as f:
        np.savez(f, **arrays)


def _read(path: Path) -> dict[str, Any]:
    with np.load(path, allow_pickle=False) as data:
        return {"meta": json.loads(str(data["meta"])),
                **{name: data[name] for name in ARRAYS}}


def cache_file(cache: Path, sha256: str, fmt: VideoFormat) -> Path:
    """Where an episode (by its member checksum, `MemberHash`) is kept at `fmt`."""
    return cache / fmt.tag / f"{sha256}-v{CACHE_VERSION}.npz"


def episode_rows(rows: list[dict[str, Any]]) -> dict[str, str]:
    """Key -> member checksum of the episodes made (failed ones have no frames)."""
    return {r["key"]: r["sha256"] for r in rows if r["status"] == "ok"}


def shard_episodes(shard: Path, rows: dict[str, str], fmt: VideoFormat, cache: Path | None
                   ) -> list[dict[str, Any]]:
    """The reduced episodes of one shard, in order: from the cache when there, else made
    (and cached when `cache` is given). `rows` as `episode_rows` gives them."""
    paths = {k: cache_file(cache, sha, fmt) for k, sha in rows.items()} if cache else {}
    if paths and all(p.is_file() for p in paths.values()):
        return [_read(paths[k]) for k in rows]
    made = []
    for key, members in iter_episodes(shard):
        path = paths.get(key)
        if path is not None and path.is_file():
            made.append(_read(path))
            continue
        made.append(reduce_episode(EncodedEpisode(key, members), fmt))
        if path is not None:
            _write(path, made[-1])
    return made


def _cache_one(job: tuple[Path, dict[str, str], VideoFormat, Path]) -> None:
    shard_episodes(*job)


def fill_cache(shards: list[tuple[Path, dict[str, str]]], fmt: VideoFormat, cache: Path,
               workers: int) -> None:
    """Reduce the shards with episodes not yet in `cache`, `workers` processes at once."""
    todo = [(shard, rows, fmt, cache) for shard, rows in shards
            if not all(cache_file(cache, sha, fmt).is_file() for sha in rows.values())]
    if workers <= 1 or len(todo) <= 1:
        for job in todo:
            _cache_one(job)
        return
    with ProcessPoolExecutor(min(workers, len(todo))) as pool:
        list(pool.map(_cache_one, todo))


def warm_staged(folder: Path, fmt: VideoFormat, cache: Path) -> int:
    """Cache the episodes a generation still running has made but not yet put in a shard
    (its staging folder), so that reading the finished set later is quick; returns how
    many were reduced. An episode moved into a shard meanwhile is skipped."""
    done = 0
    for row_path in sorted((folder / "staging").glob("ep-*.json")):
        try:
            row = json.loads(row_path.read_text(encoding="utf-8"))
            path = cache_file(cache, row["sha256"], fmt) if row["status"] == "ok" else None
            if path is None or path.is_file():
                continue
            done += len(shard_episodes(row_path.with_suffix(".tar"),
                                       {row["key"]: row["sha256"]}, fmt, cache))
        except (OSError, ValueError, HomesimError):
            continue  # moved into its shard, or still being written
    return done
