"""Episodes reduced once to small frames and class shares, and cached."""

import pytest


def test_frames_are_resampled_to_the_clip_rate():
    from homesim.learn.video.cache import VideoFormat, kept_frames

    assert kept_frames(31, 15, 8).tolist() == [0, 2, 4, 6, 8, 9, 11, 13, 15, 17, 19, 21, 22,
                                               24, 26, 28, 30]
    assert kept_frames(5, 2, 8).tolist() == [0, 1, 2, 3, 4]  # never more than the source
    assert VideoFormat.parse("96X72").tag == "96x72@4"


def test_bad_frame_size_is_one_clear_error():
    from homesim.errors import HomesimError
    from homesim.learn.video.cache import VideoFormat

    with pytest.raises(HomesimError, match="WIDTHxHEIGHT"):
        VideoFormat.parse("64by48")


def test_reduced_shards_are_cached(tiny_video, tmp_path):
    import numpy as np

    from homesim.dataset.layout import Layout
    from homesim.learn.video.cache import VideoFormat, episode_rows, shard_episodes

    fmt = VideoFormat(16, 12, 4)
    shard = Layout(tiny_video).finished_shards()[0]
    path, rows = tiny_video / "shards" / shard["name"], episode_rows(shard["rows"])
    first = shard_episodes(path, rows, fmt, tmp_path)
    assert len(list(tmp_path.glob("16x12@4/*.npz"))) == len(rows)  # one per episode
    again = shard_episodes(path, rows, fmt, tmp_path)
    assert all(np.array_equal(a["frames"], b["frames"]) and np.array_equal(a["maps"], b["maps"])
               for a, b in zip(first, again, strict=True))
    ep = first[0]
    assert ep["frames"].shape[1:] == (3, 12, 16) and ep["meta"]["fps"] == 2
    assert ep["maps"].shape[1:] == (6, 8) and ep["maps"].max() < len(ep["meta"]["classes"])


def test_staged_episodes_of_a_running_generation_are_cached(tiny_video, tmp_path):
    import json
    import shutil

    from homesim.learn.video.cache import VideoFormat, cache_file, warm_staged

    shard = json.loads((tiny_video / "shards" / "shard-000000.json").read_text())
    row = shard["rows"][0]
    running = tmp_path / "running"
    (running / "staging").mkdir(parents=True)
    shutil.copy(tiny_video / "shards" / "shard-000000.tar", running / "staging" / "ep-000000.tar")
    (running / "staging" / "ep-000000.json").write_text(json.dumps(row))
    (running / "staging" / "ep-000009.json").write_text(json.dumps({**row, "key": "ep-000009",
                                                                    "sha256": "gone"}))
    fmt, cache = VideoFormat(16, 12, 4), tmp_path / "cache"
    assert warm_staged(running, fmt, cache) >= 1
    assert cache_file(cache, row["sha256"], fmt).is_file()
    assert not cache_file(cache, "gone", fmt).exists()  # its tar was not there: skipped
