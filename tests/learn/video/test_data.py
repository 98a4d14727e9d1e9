"""Reading a data set into the frame store."""

from __future__ import annotations

import pytest

pytest.importorskip("torch")


def test_the_store_holds_frames_and_maps_of_every_part(tiny_plan, tmp_path):
    from homesim.learn.video.cache import VideoFormat
    from homesim.learn.video.data import read_store

    store, split = read_store(str(tiny_plan), VideoFormat(16, 12, 2), tmp_path)
    assert split.roles == {"train": "train", "val": "val", "test": "test"}
    assert [len(store.part(p)) for p in ("train", "val", "test")] == [2, 1, 1]
    assert store.frames.shape[1:] == (3, 12, 16) and store.maps.shape[1:] == (6, 8)
    assert store.classes[0] == "background" and store.maps.max() < len(store.classes)
    assert store.part("val")[0].key == "val/ep-000000" and store.part("val")[0].fps == 2
    again, _ = read_store(str(tiny_plan), VideoFormat(16, 12, 2), tmp_path)
    assert again.root == store.root  # built once, then read


def test_a_folder_that_is_not_a_data_set_is_refused(tmp_path):
    from homesim.errors import HomesimError
    from homesim.learn.video.cache import VideoFormat
    from homesim.learn.video.data import read_store

    with pytest.raises(HomesimError, match="not a data set folder"):
        read_store(str(tmp_path), VideoFormat(), tmp_path / "cache")
