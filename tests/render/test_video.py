"""The one H.264 writer and reader: in-process, the same frames give the same bytes."""

import numpy as np
import pytest

pytest.importorskip("av")

from homesim.render.video import H264Writer, iter_video


def frames(n: int = 6) -> list[np.ndarray]:
    y, x = np.mgrid[0:48, 0:64]
    return [np.stack([(x * 4 + 10 * t) % 256, (y * 5) % 256, np.full_like(x, 60 * (t % 4))],
                     axis=-1).astype(np.uint8) for t in range(n)]


def encode(images: list[np.ndarray], **x264: str) -> bytes:
    """The mp4 of `images`, with `x264` options added to the writer's for this call."""
    from homesim.render import video

    saved = dict(video.X264_OPTIONS)
    video.X264_OPTIONS.update(x264)
    try:
        writer = H264Writer(images[0].shape[1], images[0].shape[0], 15)
        for image in images:
            writer.add(image)
        return writer.close()
    finally:
        video.X264_OPTIONS.clear()
        video.X264_OPTIONS.update(saved)


def test_frames_round_trip_nearly_unchanged():
    images = frames()
    decoded = list(iter_video(encode(images)))
    assert len(decoded) == len(images)
    for before, after in zip(images, decoded, strict=True):
        assert after.shape == before.shape
        assert np.abs(after.astype(int) - before.astype(int)).mean() < 6


def test_the_same_frames_give_the_same_bytes():
    assert encode(frames()) == encode(frames())
    assert encode(frames()) != encode(frames()[::-1])


def test_rgb_to_yuv420p_matches_bt601_limited_range_and_any_memory_layout():
    from homesim.render.video import rgb_to_yuv420p

    flat = np.zeros((4, 6, 3), np.uint8)
    flat[:] = (255, 255, 255)
    planes = rgb_to_yuv420p(flat).ravel()
    assert planes[:24].tolist() == [235] * 24 and planes[24:].tolist() == [128] * 12
    black = rgb_to_yuv420p(np.zeros((4, 6, 3), np.uint8)).ravel()
    assert black[:24].tolist() == [16] * 24
    # The same frame at another address and alignment gives the same planes.
    frame = np.random.default_rng(1).integers(0, 256, (24, 32, 3), dtype=np.uint8)
    buffer = np.empty(frame.size + 7, np.uint8)
    shifted = buffer[3:3 + frame.size].reshape(frame.shape)
    shifted[:] = frame
    assert np.array_equal(rgb_to_yuv420p(shifted), rgb_to_yuv420p(frame))


def noise_frames(n: int = 12, size: tuple[int, int] = (32, 32)) -> list[np.ndarray]:
    rng = np.random.default_rng(0)
    base = rng.integers(0, 256, (*size, 3), dtype=np.uint8)
    return [np.roll(base, 2 * t, axis=1) for t in range(n)]


def test_x264_gives_the_bytes_of_its_plain_c_code():
    """Machine-independent bytes: x264's SIMD code as pinned equals its C code (AVX2 and
    AVX-512 code give other bytes for these frames)."""
    for images in (noise_frames(), noise_frames(8, (48, 64)), frames()):
        assert encode(images) == encode(images, **{"x264-params": "asm=0"})



@pytest.mark.parametrize(("size", "pattern"), [
    ((33, 24), "must be even"), ((64, 2), "out of range")])
def test_a_size_h264_cannot_take_is_refused_in_one_line(size, pattern):
    from homesim.errors import HomesimError

    with pytest.raises(HomesimError, match=pattern):
        H264Writer(*size, 15)


def test_a_file_and_memory_hold_the_same_frames(tmp_path):
    from homesim.render.video import decode_video

    images = frames()
    path = tmp_path / "v.mp4"
    writer = H264Writer(64, 48, 15, path)
    for image in images:
        writer.add(image)
    assert writer.close() == b""
    assert np.array_equal(decode_video(path, 64, 48), decode_video(encode(images), 64, 48))


def test_frames_of_another_size_than_expected_are_an_error():
    from homesim.errors import DataError
    from homesim.render.video import decode_video

    with pytest.raises(DataError, match="video frames are 64x48, expected 32x24"):
        decode_video(encode(frames()), 32, 24)
