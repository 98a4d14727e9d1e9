"""RGB video: H.264 mp4 written and read in this process with PyAV, for recordings, the
editor's videos and data set episodes alike.

Encoding runs in the calling thread (one x264 thread, no helper process), so a task uses
the one CPU it declares. The same frames give the same bytes on any x86-64 machine with the
same PyAV build: bit-exact flags; RGB becomes YUV 4:2:0 here, in integer arithmetic, not in
FFmpeg's scaler (whose SIMD code depends on the processor); and x264 may use instructions
up to SSE2 only (`X264_ASM`), whose output equals its plain C code's. With its AVX-512
code, on a processor that has it, x264 gave other bytes for the same input now and then
(at 32x32, 16 to 170 of 2000 encodings in one process), and its AVX2 code gives other
bytes than its SSE2 and C code.
"""

from __future__ import annotations

import io
from collections.abc import Iterator
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from homesim.errors import DataError, HomesimError, LimitError
from homesim.limits import MAX_VIDEO_FPS, MAX_VIDEO_SIDE, MIN_VIDEO_SIDE

VIDEO_CRF = 18
"""x264 constant rate factor of the RGB video (lower is better; 18 is near-transparent)."""
X264_ASM = "SSE2"
"""The processor features x264 may use (module docstring)."""
X264_OPTIONS = {"preset": "veryfast", "crf": str(VIDEO_CRF), "flags": "+bitexact",
                "x264-params": f"asm={X264_ASM}"}


def check_size(width: int, height: int, fps: int) -> None:
    """Refuse a video size or frame rate out of the limits, or sides H.264 4:2:0 cannot
    take (odd), with a one-line error."""
    lo, hi = MIN_VIDEO_SIDE, MAX_VIDEO_SIDE
    if not (lo <= width <= hi and lo <= height <= hi):
        raise LimitError(f"image size {width}x{height} out of range ({lo}..{hi}; "
                         "MIN_VIDEO_SIDE, MAX_VIDEO_SIDE)", "MAX_VIDEO_SIDE")
    if width % 2 or height % 2:
        raise HomesimError(f"image size {width}x{height}: width and height must be even "
                           "(H.264 video)")
    if not 1 <= fps <= MAX_VIDEO_FPS:
        raise LimitError(f"fps {fps} out of range (1..{MAX_VIDEO_FPS}; MAX_VIDEO_FPS)",
                         "MAX_VIDEO_FPS")


class H264Writer:
    """Frames (H, W, 3 uint8, even sides) in, an mp4 (H.264, yuv420p) out: in memory,
    returned by `close`, or into the file `path` with its index at the front
    (``+faststart``), so a browser can play it while it downloads."""

    def __init__(self, width: int, height: int, fps: int, path: Path | None = None):
        import av

        check_size(width, height, fps)
        self._buffer = io.BytesIO()
        options = {"fflags": "+bitexact"}
        if path is not None:
            options["movflags"] = "+faststart"
        self._container: Any = av.open(self._buffer if path is None else str(path),
                                       mode="w", format="mp4", options=options)
        stream: Any = self._container.add_stream("libx264", rate=Fraction(fps))
        stream.width, stream.height, stream.pix_fmt = width, height, "yuv420p"
        stream.codec_context.thread_count = 1
        stream.codec_context.thread_type = "NONE"
        stream.options = dict(X264_OPTIONS)
        self._stream = stream
        self._frame_type = av.VideoFrame

    def add(self, rgb: np.ndarray) -> None:
        frame = self._frame_type.from_ndarray(rgb_to_yuv420p(rgb), format="yuv420p")
        self._container.mux(self._stream.encode(frame))

    def close(self) -> bytes:
        """Flush the encoder; the mp4's bytes when written in memory (b"" for a file)."""
        self._container.mux(self._stream.encode(None))
        self._container.close()
        return self._buffer.getvalue()


def rgb_to_yuv420p(rgb: np.ndarray) -> np.ndarray:
    """(H, W, 3) uint8 RGB (even H, W) as the (3H/2, W) uint8 planes Y, U, V of BT.601
    limited-range YUV 4:2:0, chroma the mean of each 2x2 block; integers only."""
    x = rgb.astype(np.int32)
    r, g, b = x[..., 0], x[..., 1], x[..., 2]
    y = ((66 * r + 129 * g + 25 * b + 128) >> 8) + 16
    h, w = r.shape
    rs, gs, bs = (c.reshape(h // 2, 2, w // 2, 2).sum(axis=(1, 3)) for c in (r, g, b))
    u = ((-38 * rs - 74 * gs + 112 * bs + 512) >> 10) + 128
    v = ((112 * rs - 94 * gs - 18 * bs + 512) >> 10) + 128
    planes = [np.clip(p, 0, 255).astype(np.uint8).ravel() for p in (y, u, v)]
    return np.concatenate(planes).reshape(h * 3 // 2, w)


def iter_video(source: bytes | Path, size: tuple[int, int] | None = None
               ) -> Iterator[np.ndarray]:
    """The (H, W, 3) uint8 frames of an mp4 (its bytes or its file), one at a time;
    with `size` (width, height), frames of another size are an error."""
    import av

    with av.open(io.BytesIO(source) if isinstance(source, bytes) else str(source),
                 mode="r") as container:
        stream = container.streams.video[0]
        stream.thread_type = "NONE"
        for frame in container.decode(stream):
            if size is not None and (frame.width, frame.height) != size:
                raise DataError(f"video frames are {frame.width}x{frame.height}, "
                                f"expected {size[0]}x{size[1]}")
            # threads=1: PyAV's default scales with a thread pool, which hangs in a
            # process forked after one was used (a DataLoader's forked workers)
            yield frame.to_ndarray(format="rgb24", threads=1)


def decode_video(source: bytes | Path, width: int, height: int) -> np.ndarray:
    """(T, H, W, 3) uint8: every frame of an mp4 (its bytes or its file)."""
    frames = list(iter_video(source, (width, height)))
    return np.stack(frames) if frames else np.zeros((0, height, width, 3), np.uint8)
