import numpy as np
import torch
from torch.utils.data import DataLoader

from homesim.dataset.loader import ActivityClips
from homesim.dataset.read import read_episodes


def test_episodes_read_back_with_every_modality(tiny_dataset):
    eps = list(read_episodes(tiny_dataset, ("rgb", "depth", "class", "instance", "flow")))
    assert [e["key"] for e in eps] == ["ep-000000", "ep-000001", "ep-000002"]
    e = eps[0]
    t = e["meta"]["num_frames"]
    assert e["rgb"].shape == (t, 24, 32, 3) and e["depth"].shape == (t, 24, 32)
    assert e["flow"].shape == (t, 24, 32, 2) and e["flow_valid"].dtype == bool
    assert e["gt_frames"].tolist() == list(range(t))
    assert not e["flow_valid"][-1].any()  # the last frame has no next frame
    # Something is seen, and the ids index the legends.
    assert e["depth"].max() > 0.5
    assert e["class"].max() < len(e["meta"]["classes"])
    assert e["instance"].max() < len(e["meta"]["instances"])
    steps = e["meta"]["steps"]
    assert [s["action"] for s in steps] == ["WALK", "SWITCHON"]
    assert e["step"][steps[1]["end_frame"]] == 1


def test_clips_are_two_seconds_with_their_step(tiny_dataset):
    clips = list(ActivityClips(tiny_dataset, modalities=("rgb", "depth")))
    assert clips and all(c["rgb"].shape == (4, 24, 32, 3) for c in clips)  # 2 s at 2 fps
    assert all(c["depth"].shape == (4, 24, 32) for c in clips)
    c = clips[0]
    assert c["label"] == "[Walk] <television> (1)" and c["action"] == "WALK"
    assert c["step"].dtype == torch.int64 and c["program"].startswith("[Walk]")
    episodes = list(ActivityClips(tiny_dataset, clip_seconds=None))
    assert len(episodes) == 3 and "meta" in episodes[0]
    frames = episodes[0]["meta"]["num_frames"]
    assert sum(1 for c in clips if c["key"] == "ep-000000") == frames // 4


def test_dataloader_workers_split_the_shards(tiny_dataset):
    alone = [(c["key"], c["clip_start"]) for c in ActivityClips(tiny_dataset)]
    # forked workers (the default) after this process decoded videos itself (the tests
    # before); a worker that hangs fails the test in 120 s
    loader = DataLoader(ActivityClips(tiny_dataset), batch_size=2, num_workers=2, timeout=120)
    seen = []
    for batch in loader:
        assert batch["rgb"].shape[1:] == (4, 24, 32, 3)
        seen += list(zip(batch["key"], batch["clip_start"].tolist(), strict=True))
    assert sorted(seen) == sorted(alone)  # each clip once, none twice


def test_webdataset_reads_the_shards_without_homesim(tiny_dataset):
    import webdataset as wds

    shard = str(tiny_dataset / "shards" / "shard-000000.tar")
    samples = list(wds.WebDataset(shard, shardshuffle=False).decode())
    assert [s["__key__"] for s in samples] == ["ep-000000", "ep-000001"]
    s = samples[0]
    assert isinstance(s["json"], dict) and s["json"]["key"] == "ep-000000"
    assert isinstance(s["step.npy"], np.ndarray) and "000000.depth.png" in s
