"""The frame encoders."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("torch")


def test_class_weights_balance_classes():
    from homesim.learn.video.framecnn import class_weights

    w = class_weights(np.array([0, 0, 0, 1, -100]), 3)
    assert w[0] * 3 == pytest.approx(w[1] * 1) and w[2] == 0


def test_map_and_rgb_encoders_give_features_of_their_width():
    import torch

    from homesim.learn.video.framecnn import FrameCNN, FrameCNNConfig

    rgb = FrameCNN(FrameCNNConfig(3, 4, feature=8))
    maps = FrameCNN(FrameCNNConfig(3, 4, "map", num_classes=5, feature=8))
    assert rgb(torch.zeros(2, 3, 12, 16, dtype=torch.uint8)).shape == (2, 8)
    assert maps(torch.full((2, 6, 8), 4, dtype=torch.uint8)).shape == (2, 8)
    a, s = maps.heads(torch.zeros(2, 6, 8, dtype=torch.uint8))
    assert a.shape == (2, 3) and s.shape == (2, 4)
