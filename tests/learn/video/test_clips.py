"""Clip models: scores that weigh classes alike, and the settings they are built with."""

import pytest

pytest.importorskip("torch")


def test_mean_class_accuracy_weighs_classes_equally():
    from homesim.learn.video.clips import mean_class_accuracy

    # class a: 2 of 3 right; class b: 0 of 1
    assert mean_class_accuracy(["a", "a", "b", "a"], ["a", "a", "a", "b"]) == pytest.approx(
        100 * (2 / 3 + 0) / 2)


def test_class_weights_balance_classes():
    import torch

    from homesim.learn.video.clips import class_weights

    w = class_weights(torch.tensor([0, 0, 0, 1]), 3)
    assert w[0] * 3 == pytest.approx(w[1] * 1) and w[2] == 0


def test_a_clip_model_is_built_from_its_settings():
    """The frames a clip is read at, the TRN's scales and subsets are its config's, and the
    config is saved with the weights (`table.save_clip_model`)."""
    import torch

    from homesim.learn.video.clips import ClipConfig, ClipModel, clip_inputs

    vectors = torch.arange(40.0).reshape(20, 2).numpy()
    assert clip_inputs(vectors, 4, 10, 3)[:, 0].tolist() == [8.0, 12.0, 18.0]  # frames 4, 6, 9
    cfg = ClipConfig("trn", "oracle", 2, 3, 4, frames=6, max_scale=3, subsets=2, hidden=16)
    model = ClipModel(cfg)
    assert model.scales == [2, 3] and model.frames.scale == cfg.oracle_scale
    assert model.features(torch.zeros(5, 6, 2)).shape == (5, cfg.feature)
    assert ClipConfig(**cfg.to_dict()) == cfg
