"""PNG encoding of RGB frames for JSON answers (stdlib only: zlib and struct)."""

from __future__ import annotations

import base64
import struct
import zlib
from typing import Any


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def encode_png(rgb: Any) -> bytes:
    """Encode an (height, width, 3) uint8 array-like as an 8-bit RGB PNG.

    >>> encode_png([[[255, 0, 0]]])[:8]
    b'\\x89PNG\\r\\n\\x1a\\n'
    """
    if hasattr(rgb, "tobytes"):  # numpy: one copy per row instead of a Python loop per pixel
        rows = [row.astype("uint8").tobytes() for row in rgb] if getattr(rgb, "ndim", 0) == 3 \
            else []
    else:
        rows = [bytes(int(v) for px in row for v in px) for row in rgb]
    height, width = len(rows), (len(rows[0]) // 3 if rows else 0)
    if not height or not width or any(len(r) != 3 * width for r in rows):
        raise ValueError("a frame must be a non-empty (height, width, 3) RGB array")
    raw = b"".join(b"\x00" + r for r in rows)  # filter type 0 (none) on every row
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)  # 8 bit, RGB
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header)
            + _chunk(b"IDAT", zlib.compress(raw, 6)) + _chunk(b"IEND", b""))


def png_data_url(rgb: Any) -> str:
    """A ``data:image/png;base64,...`` URL for an RGB frame."""
    return "data:image/png;base64," + base64.b64encode(encode_png(rgb)).decode("ascii")
