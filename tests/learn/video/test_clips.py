"""Clips: labels at the middle frame, mean per-class accuracy, the TRN from its config."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("torch")


def test_a_clip_is_labelled_by_its_middle_frame():
    from homesim.learn.video.clips import FRAMES, clip_set

    ep = SimpleNamespace(key="k", start=10, length=12, fps=4,
                         steps=["[Walk] <tv> (1)", "[SwitchOn] <tv> (1)"])
    step = np.full(30, -1)
    step[10:13], step[13:22] = 0, 1  # frames 0-2 walk, 3-11 switch on: [0, 8) shows
    # walking least, but its middle frame (4) switches on
    clips = clip_set([ep], step)  # windows [0, 8) and no second one (12 frames)
    assert clips.steps == ["[SwitchOn] <tv>"] and clips.actions == ["SwitchOn"]
    assert clips.rows.shape == (1, FRAMES) and clips.rows[0, 0] == 10
    hopped = clip_set([ep], step, hop=1.0)  # [0, 8) and [4, 12)
    assert hopped.steps == ["[SwitchOn] <tv>", "[SwitchOn] <tv>"]
    step[14:22] = -1  # the middle frame shows nothing: no clip
    assert clip_set([ep], step).steps == []


def test_mean_class_accuracy_weighs_classes_equally():
    from homesim.learn.video.clips import mean_class_accuracy

    # class a: 2 of 3 right; class b: 0 of 1
    assert mean_class_accuracy(["a", "a", "b", "a"], ["a", "a", "a", "b"]) == pytest.approx(
        100 * (2 / 3 + 0) / 2)


def test_a_clip_model_is_built_from_its_settings():
    """The TRN's scales, subsets and widths are its config's, saved with the weights."""
    import torch

    from homesim.learn.video.clips import FRAMES, ClipConfig, ClipModel

    cfg = ClipConfig("trn", "seg", 2, 3, 4, max_scale=3, subsets=2, hidden=16, feature=8)
    model = ClipModel(cfg)
    assert model.scales == [2, 3] and model.relations[0][0].out_features == 16
    assert model.features(torch.zeros(5, FRAMES, 2)).shape == (5, 8)
    assert ClipConfig(**cfg.to_dict()) == cfg


def test_an_end_to_end_clip_model_reads_maps_and_trains_its_backbone():
    """With a backbone the clip model reads class maps itself, starts from the given
    frame encoder's weights and fine-tunes them: a label shown only by which class
    fills the frames is learnt."""
    import torch

    from homesim.learn.video.clips import (
        FRAMES,
        ClipConfig,
        ClipSet,
        Labels,
        predict_clips,
        train_clip_model,
    )
    from homesim.learn.video.framecnn import FrameCNN, FrameCNNConfig

    rng = np.random.default_rng(0)
    n = 64
    maps = np.zeros((n * FRAMES, 6, 8), np.uint8)
    names = []
    for i in range(n):
        cls = i % 2
        maps[i * FRAMES:(i + 1) * FRAMES] = rng.integers(0, 2, (FRAMES, 6, 8)) + 2 * cls
        names.append("Open" if cls else "Grab")
    rows = np.arange(n * FRAMES).reshape(n, FRAMES)
    data = ClipSet(rows, [str(i) for i in range(n)], names, [f"[{a}] <x>" for a in names])
    labels = Labels.build(data)
    backbone = FrameCNNConfig(2, 2, "map", num_classes=4, feature=8)
    start = FrameCNN(backbone).state_dict()
    cfg = ClipConfig("trn", "oracle", 8, 2, 2, feature=8, hidden=16, epochs=8, lr=5e-3,
                     batch_size=8, dropout=0.0,
                     backbone=backbone.to_dict())
    model, _ = train_clip_model(cfg, maps, data, labels, backbone_state=start)
    actions, _ = predict_clips(model, maps, data, labels)
    assert actions == names
    moved = model.backbone.state_dict()
    assert any(not torch.equal(moved[k], start[k]) for k in start if k.endswith("weight"))
    assert ClipConfig(**cfg.to_dict()) == cfg


def test_a_step_is_chosen_with_its_actions_probability():
    import torch

    from homesim.learn.video.clips import ClipSet, Labels, predict_clips

    class FixedHeads(torch.nn.Module):
        """Action logits favour Open; the step head slightly prefers a Close step."""

        def __init__(self) -> None:
            super().__init__()
            self.unused = torch.nn.Parameter(torch.zeros(1))

        def forward(self, clips: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
            n = len(clips)
            return (torch.tensor([[0.0, 3.0]]).repeat(n, 1),  # Close, Open
                    torch.tensor([[1.2, 1.0, 0.0]]).repeat(n, 1))  # steps below

    labels = Labels(["Close", "Open"], ["[Close] <door>", "[Open] <door>", "[Open] <tv>"])
    assert labels.step_actions().tolist() == [0, 1, 1]
    data = ClipSet(np.zeros((2, 8), np.int64), ["a", "b"], ["Open"] * 2,
                   ["[Open] <door>"] * 2)
    actions, steps = predict_clips(FixedHeads(), np.zeros((1, 4), np.float32), data, labels)
    assert actions == ["Open", "Open"]
    assert steps == ["[Open] <door>", "[Open] <door>"]  # the step head alone: Close
