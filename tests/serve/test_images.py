import struct
import zlib

import pytest

from homesim.serve.images import encode_png, png_data_url


def _decode(png: bytes) -> tuple[int, int, bytes]:
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, size = 8, b"", None
    while pos < len(png):
        (length,) = struct.unpack(">I", png[pos:pos + 4])
        kind, data = png[pos + 4:pos + 8], png[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", png[pos + 8 + length:pos + 12 + length])
        assert crc == zlib.crc32(kind + data)
        if kind == b"IHDR":
            size = struct.unpack(">II", data[:8])
        elif kind == b"IDAT":
            idat += data
        pos += 12 + length
    return size[0], size[1], zlib.decompress(idat)


def test_png_round_trips_pixels():
    frame = [[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [10, 20, 30]]]
    width, height, raw = _decode(encode_png(frame))
    assert (width, height) == (2, 2)
    assert raw == b"\x00" + bytes([255, 0, 0, 0, 255, 0]) + b"\x00" + bytes([0, 0, 255, 10, 20, 30])


def test_numpy_frames_encode_like_lists():
    np = pytest.importorskip("numpy")
    frame = np.arange(4 * 3 * 3, dtype=np.uint8).reshape(4, 3, 3)
    assert encode_png(frame) == encode_png(frame.tolist())
    assert png_data_url(frame).startswith("data:image/png;base64,")


@pytest.mark.parametrize("bad", [[], [[]], [[[1, 2, 3]], [[1, 2, 3], [4, 5, 6]]]])
def test_bad_frames_are_refused(bad):
    with pytest.raises(ValueError, match="non-empty"):
        encode_png(bad)
