"""The pose network: the descriptor of joints by hand, and that it learns to find joints
drawn as bright dots."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("torch")

from homesim.learn.video.pose import (
    PoseConfig,
    pose_descriptor,
    pose_scores,
    predict_joints,
    train_posenet,
)


def test_the_descriptor_is_each_joint_from_the_centre_in_body_heights():
    # a head at the top, feet 0.5 of the frame below it, a hidden hand between them
    joints = np.array([[[0.5, 0.2, 1.0], [0.5, 0.7, 1.0], [0.8, 0.45, 0.0]]], np.float32)
    d = pose_descriptor(joints)
    assert d.shape == (1, 3 * 3 + 3)
    rel, vis, centre, height = d[0, :6], d[0, 6:9], d[0, 9:11], d[0, 11]
    assert rel.tolist() == pytest.approx([-0.2, -0.5, -0.2, 0.5, 0.4, 0], abs=1e-6)
    assert vis.tolist() == [1, 1, 0]
    assert centre.tolist() == pytest.approx([0.6, 0.45]) and height == pytest.approx(0.5)


def test_a_frame_without_joints_in_view_has_a_finite_descriptor():
    d = pose_descriptor(np.zeros((2, 4, 3), np.float32))
    assert np.isfinite(d).all() and d[:, :8].max() == 0


def _dots(n: int, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Frames 16x12 with a red and a blue dot (2x2 px): joint 0 and joint 1; joint 1
    missing (invisible) in a third of the frames."""
    frames = np.zeros((n, 3, 12, 16), np.uint8)
    joints = np.zeros((n, 2, 3), np.float16)
    for i in range(n):
        for j, channel in enumerate((0, 2)):
            if j == 1 and i % 3 == 0:
                continue
            x, y = rng.integers(1, 15), rng.integers(1, 11)
            frames[i, channel, y - 1:y + 1, x - 1:x + 1] = 255
            joints[i, j] = (x / 16, y / 12, 1.0)
    return frames, joints


def test_it_learns_to_place_joints_it_can_see():
    rng = np.random.default_rng(0)
    frames, joints = _dots(240, rng)
    rows = np.arange(240)
    cfg = PoseConfig(2, epochs=10, batch_size=16, lr=1e-2)
    untrained = pose_scores(train_posenet(PoseConfig(2, epochs=0), frames, joints, rows[:200],
                                          None)[0], frames, joints, rows[200:])
    model, fitted = train_posenet(cfg, frames, joints, rows[:200], rows[200:])
    assert fitted.best_epoch is not None and len(fitted.scores) == 10
    scores = pose_scores(model, frames, joints, rows[200:])
    assert scores["error_px"] < untrained["error_px"] / 2
    assert scores["visibility"] > 90
    pred = predict_joints(model, frames, rows[:5])
    assert pred.shape == (5, 2, 3) and pred.dtype == np.float16
    assert ((pred[..., :2] >= 0) & (pred[..., :2] <= 1)).all()


def test_joined_features_keep_the_features_and_bring_the_joints_to_their_spread():
    from homesim.learn.video.table import with_pose

    rng = np.random.default_rng(1)
    features = rng.normal(0, 3, (50, 4)).astype(np.float16)
    joints = np.concatenate([rng.uniform(0, 1, (50, 2, 2)), np.ones((50, 2, 1))], 2)
    train = np.arange(40)
    joined = with_pose(features, joints.astype(np.float16), train)
    assert joined.shape == (50, 4 + 3 * 2 + 3) and joined.dtype == np.float16
    assert np.array_equal(joined[:, :4], features)
    desc = joined[train, 4:].astype(np.float32)
    spread = float(features[train].astype(np.float32).std())
    moving = desc.std(0) > 0.01  # the visibilities are all 1: constant columns stay 0
    assert np.allclose(desc.mean(0), 0, atol=0.02)
    assert np.allclose(desc.std(0)[moving], spread, rtol=0.02)
