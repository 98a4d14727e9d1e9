"""The frame store: episodes' frames and maps in one memory-mapped array, class ids of
every episode made global."""

from __future__ import annotations

import json

import numpy as np

from homesim.learn.video.store import FrameStore, build_store, store_name


def _episode(path, key, classes, n, value):
    meta = {"key": key, "home": "scene1", "agent": "male1", "title": "T", "description": "D",
            "program": "[Walk] <tv> (1)", "classes": classes, "fps": 4,
            "steps": ["[Walk] <tv> (1)"]}
    np.savez(path, meta=np.array(json.dumps(meta)),
             frames=np.full((n, 3, 4, 6), value, np.uint8),
             maps=np.tile(np.arange(len(classes), dtype=np.uint8), (n, 2, 1))[:, :, :3],
             step=np.zeros(n, np.int64),
             joints=np.full((n, 2, 3), value / 4, np.float16))
    return path


def test_a_store_holds_every_frame_with_global_classes(tmp_path):
    a = _episode(tmp_path / "a.npz", "ep-0", ["background", "tv", "sofa"], 3, 1)
    b = _episode(tmp_path / "b.npz", "ep-1", ["background", "cup", "tv"], 2, 2)
    items = [("train", "train/ep-0", a), ("test", "test/ep-0", b)]
    root = tmp_path / store_name([(p, k, f.name) for p, k, f in items], "6x4@4")
    store = build_store(root, items)
    assert store.classes == ["background", "cup", "sofa", "tv"]
    assert store.frames.shape == (5, 3, 4, 6) and isinstance(store.frames, np.memmap)
    assert store.frames[3:].max() == 2 and store.frames[:3].max() == 1
    # episode a: local [bg, tv, sofa] -> global [0, 3, 2]; b: [bg, cup, tv] -> [0, 1, 3]
    assert store.maps[0, 0].tolist() == [0, 3, 2] and store.maps[4, 0].tolist() == [0, 1, 3]
    assert store.joints.shape == (5, 2, 3) and store.joints[3:].max() == 0.5
    assert [e.key for e in store.part("test")] == ["test/ep-0"]
    assert store.rows(store.episodes).tolist() == [0, 1, 2, 3, 4]
    again = build_store(root, items)  # built once: read back
    assert again.episodes == store.episodes and FrameStore(root).classes == store.classes
