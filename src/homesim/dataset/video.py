"""RGB video of an episode: H.264 written and read in this process with PyAV.

Encoding runs in the calling thread (one x264 thread, no helper process), so an episode
task uses the one CPU it declares; bit-exact flags make the same frames give the same
bytes on any machine with the same PyAV build.
"""

from __future__ import annotations

import io
from collections.abc import Iterator
from fractions import Fraction
from typing import Any

import numpy as np

VIDEO_CRF = 18
"""x264 constant rate factor of the RGB video (lower is better; 18 is near-transparent)."""
X264_OPTIONS = {"preset": "veryfast", "crf": str(VIDEO_CRF), "flags": "+bitexact"}


class H264Writer:
    """Frames (H, W, 3 uint8) in, an mp4 (H.264, yuv420p) out as bytes at `close`."""

    def __init__(self, width: int, height: int, fps: int):
        import av

        self._buffer = io.BytesIO()
        self._container: Any = av.open(self._buffer, mode="w", format="mp4",
                                       options={"fflags": "+bitexact"})
        stream: Any = self._container.add_stream("libx264", rate=Fraction(fps))
        stream.width, stream.height, stream.pix_fmt = width, height, "yuv420p"
        stream.codec_context.thread_count = 1
        stream.codec_context.thread_type = "NONE"
        stream.options = dict(X264_OPTIONS)
        self._stream = stream
        self._frame_type = av.VideoFrame

    def add(self, rgb: np.ndarray) -> None:
        frame = self._frame_type.from_ndarray(np.ascontiguousarray(rgb), format="rgb24")
        self._container.mux(self._stream.encode(frame))

    def close(self) -> bytes:
        """Flush the encoder and return the file's bytes."""
        self._container.mux(self._stream.encode(None))
        self._container.close()
        return self._buffer.getvalue()


def iter_video(data: bytes) -> Iterator[np.ndarray]:
    """The (H, W, 3) uint8 frames of an mp4 given as bytes, one at a time."""
    import av

    with av.open(io.BytesIO(data), mode="r") as container:
        stream = container.streams.video[0]
        stream.thread_type = "NONE"
        for frame in container.decode(stream):
            yield frame.to_ndarray(format="rgb24")
