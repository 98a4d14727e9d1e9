"""The segmentation network: its scores on a hand-made confusion, and that it learns a
map that colour decides."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("torch")

from homesim.learn.video.segment import (
    SegConfig,
    confusion,
    predict_maps,
    scores_from_confusion,
    segmentation_scores,
    train_segnet,
)


def test_pixel_accuracy_and_mean_iou_by_hand():
    truth = np.array([[0, 0, 1, 1]])
    pred = np.array([[0, 1, 1, 1]])
    s = scores_from_confusion(confusion(pred, truth, 3))
    assert s["pixel_accuracy"] == 75.0 and s["classes"] == 2
    # IoU class 0: 1 / 2; class 1: 2 / 3; class 2 never true: left out
    assert s["miou"] == pytest.approx(100 * (1 / 2 + 2 / 3) / 2)


def test_it_learns_classes_that_colour_decides():
    rng = np.random.default_rng(0)
    maps = rng.integers(0, 3, (96, 6, 8)).astype(np.uint8)
    colours = np.array([[0, 0, 0], [255, 0, 0], [0, 0, 255]], np.uint8)
    frames = colours[maps.repeat(2, 1).repeat(2, 2)].transpose(0, 3, 1, 2).copy()
    rows = np.arange(96)
    model, fitted = train_segnet(SegConfig(3, epochs=12, batch_size=16, lr=1e-2), frames,
                                 maps, rows[:80], rows[80:])
    assert fitted.best_epoch is not None and len(fitted.scores) == 12
    assert segmentation_scores(model, frames, maps, rows[80:])["pixel_accuracy"] > 60
    assert predict_maps(model, frames, rows[:5]).shape == (5, 6, 8)
