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


def test_a_grid_of_cells_keeps_where_things_are_in_the_frame():
    """The spatial mean cannot tell a thing at the left of the map from the same thing
    further right (the convolutions are shift-equivariant, 4 map pixels a step, and the
    mean forgets where); the means of a 2x1 grid of cells can."""
    import torch

    from homesim.learn.video.framecnn import FrameCNN, FrameCNNConfig

    left = torch.zeros(1, 8, 48, dtype=torch.uint8)
    left[0, 3:5, 16:18] = 1
    right = torch.roll(left, 12, dims=2)  # 3 cells of the last convolution further right
    torch.manual_seed(0)
    mean = FrameCNN(FrameCNNConfig(2, 2, "map", num_classes=2, feature=8)).eval()
    torch.manual_seed(0)
    grid = FrameCNN(FrameCNNConfig(2, 2, "map", num_classes=2, feature=8, grid_w=2)).eval()
    with torch.no_grad():
        assert torch.allclose(mean(left), mean(right), atol=1e-5)
        assert not torch.allclose(grid(left), grid(right), atol=1e-3)
    assert grid.net[-2].in_features == 64 * 2
