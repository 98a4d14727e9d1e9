"""Write a recording to a folder, and read it back (`load_recording`).

Layout of a recording folder (see docs/render.md)::

    meta.json          program, home, seed, sizes, fps, steps with their frames,
                       cameras, class and instance legends, joint names, units
    video.mp4          RGB, H.264 (yuv420p)
    frames/000000.npz  depth (H,W) float32 m; class (H,W) uint16; instance (H,W) int32
                       (graph node ids); flow (H,W,2) float32 px to the next frame;
                       flow_valid (H,W) bool (in front of the next camera, on screen,
                       no cut after this frame)
    frames.npz         per-frame arrays: camera (T,) int16, intrinsics (T,3,3),
                       world_to_cam (T,4,4), joints3d (T,J,3), joints2d (T,J,2),
                       joints_visible (T,J) bool, cut (T,) bool
"""

from __future__ import annotations

import json
import zipfile
from collections.abc import Iterable
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from homesim.errors import DataError
from homesim.files import write_text
from homesim.render.recorder import FrameTruth
from homesim.render.video import H264Writer, decode_video, iter_video

FORMAT_VERSION = 2
"""2: frames carry `flow_valid`."""
ZIP_LEVEL = 1
"""Deflate level of the frame files: level 1 is ~3x faster than numpy's default 6 and
the files are ~3x larger; writing must keep up with rendering."""


def write_npz(path: Path, arrays: dict[str, np.ndarray]) -> None:
    """A `.npz` (readable by `numpy.load`) compressed at `ZIP_LEVEL`."""
    tmp = path.with_suffix(".tmp")
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED, compresslevel=ZIP_LEVEL) as zf:
        for name, arr in arrays.items():
            with zf.open(f"{name}.npy", "w", force_zip64=True) as f:
                np.lib.format.write_array(f, np.ascontiguousarray(arr), allow_pickle=False)
    tmp.replace(path)


class RecordingWriter:
    """Streams frames into a recording folder; `close(meta)` finishes it.

    Video encoding (`video.H264Writer`) and compression run on a worker thread (PyAV's
    encoder and zlib release the GIL), so they overlap with rendering the next frames.
    """

    def __init__(self, out_dir: str | Path, width: int, height: int, fps: int):
        self.out = Path(out_dir)
        (self.out / "frames").mkdir(parents=True, exist_ok=True)
        self._video = H264Writer(width, height, fps, self.out / "video.mp4")
        self._pool = ThreadPoolExecutor(max_workers=1)
        self._pending: list[Future] = []
        self._per_frame: dict[str, list] = {k: [] for k in (
            "camera", "intrinsics", "world_to_cam", "joints3d", "joints2d", "joints_visible",
            "cut")}

    def _write(self, f: FrameTruth) -> None:
        assert f.flow is not None and f.flow_valid is not None  # `add` checked
        self._video.add(f.rgb)
        write_npz(self.out / "frames" / f"{f.index:06d}.npz", {
            "depth": f.depth, "class": f.class_seg, "instance": f.instance_seg,
            "flow": f.flow, "flow_valid": f.flow_valid})

    def add(self, f: FrameTruth) -> None:
        if f.flow is None or f.flow_valid is None:
            raise AssertionError("a recording keeps the flow: play it with flow=True")
        # Frames are written in order by the single worker (video and frame files); at
        # most 8 wait, so memory stays bounded when writing is slower than rendering.
        self._pending.append(self._pool.submit(self._write, f))
        while len(self._pending) > 8:
            self._pending.pop(0).result()
        if len(self._pending) > 8:
            self._pending.pop(0).result()
        pf = self._per_frame
        pf["camera"].append(f.camera)
        pf["intrinsics"].append(f.intrinsics)
        pf["world_to_cam"].append(f.world_to_cam)
        pf["joints3d"].append(f.joints3d)
        pf["joints2d"].append(f.joints2d)
        pf["joints_visible"].append(f.joints_visible)
        pf["cut"].append(f.cut)

    def close(self, meta: dict) -> None:
        for fut in self._pending:
            fut.result()
        self._pool.shutdown()
        self._video.close()
        pf = self._per_frame
        np.savez_compressed(
            self.out / "frames.npz", camera=np.asarray(pf["camera"], np.int16),
            intrinsics=np.asarray(pf["intrinsics"]), world_to_cam=np.asarray(pf["world_to_cam"]),
            joints3d=np.asarray(pf["joints3d"]), joints2d=np.asarray(pf["joints2d"]),
            joints_visible=np.asarray(pf["joints_visible"], bool),
            cut=np.asarray(pf["cut"], bool))
        meta = {"format": FORMAT_VERSION, **meta}
        write_text(self.out / "meta.json", json.dumps(meta, indent=1))  # last, atomically

    def abort(self) -> None:
        """Stop writing without finishing (the folder is left incomplete, no meta.json)."""
        try:
            self._pool.shutdown(cancel_futures=True)
        finally:
            self._video.close()


@dataclass(frozen=True)
class StepSpan:
    """A program step and the frames (inclusive) that show it."""

    index: int
    step: str
    start_frame: int
    end_frame: int


class Recording:
    """A recording folder read back (see `load_recording`); frames load lazily."""

    def __init__(self, path: Path, meta: dict, per_frame: dict[str, np.ndarray]):
        self.path, self.meta, self.per_frame = path, meta, per_frame

    @property
    def num_frames(self) -> int:
        return int(self.meta["num_frames"])

    @property
    def steps(self) -> list[StepSpan]:
        return [StepSpan(s["index"], s["step"], s["start_frame"], s["end_frame"])
                for s in self.meta["steps"]]

    @property
    def classes(self) -> dict[int, str]:
        """Class index -> class name (0 is background)."""
        return {int(k): v for k, v in self.meta["classes"].items()}

    @property
    def instances(self) -> dict[int, str]:
        """Graph node id -> class name of every instance that can appear."""
        return {int(k): v["class"] for k, v in self.meta["instances"].items()}

    def frame(self, i: int) -> dict[str, np.ndarray]:
        """Dense ground truth of frame `i`: depth, class, instance, flow, flow_valid."""
        if not 0 <= i < self.num_frames:
            raise DataError(f"{self.path}: frame {i} out of range 0..{self.num_frames - 1}")
        with np.load(self.path / "frames" / f"{i:06d}.npz") as z:
            return {k: z[k] for k in z.files}

    def rgb(self) -> np.ndarray:
        """All RGB frames (T, H, W, 3) uint8, decoded from video.mp4."""
        return decode_video(self.path / "video.mp4", self.meta["width"], self.meta["height"])

    def rgb_frames(self, wanted: Iterable[int]) -> dict[int, np.ndarray]:
        """Some RGB frames by index, decoded one at a time from video.mp4 (memory for the
        frames asked for only, however long the video)."""
        wanted = set(wanted)
        out: dict[int, np.ndarray] = {}
        size = (self.meta["width"], self.meta["height"])
        for i, frame in enumerate(iter_video(self.path / "video.mp4", size)):
            if i in wanted:
                out[i] = frame
                if len(out) == len(wanted):
                    break
        return out


def load_recording(out_dir: str | Path) -> Recording:
    """Read a recording folder written by `render_program`."""
    path = Path(out_dir)
    meta_path = path / "meta.json"
    if not meta_path.is_file():
        raise DataError(f"{path}: not a recording (no meta.json; was the render finished?)")
    try:
        meta = json.loads(meta_path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        raise DataError(f"{meta_path}: cannot read ({e})") from None
    if meta.get("format") != FORMAT_VERSION:
        raise DataError(f"{meta_path}: format {meta.get('format')!r}, expected {FORMAT_VERSION}")
    try:
        with np.load(path / "frames.npz") as z:
            per_frame = {k: z[k] for k in z.files}
    except OSError as e:
        raise DataError(f"{path / 'frames.npz'}: cannot read ({e})") from None
    return Recording(path, meta, per_frame)
