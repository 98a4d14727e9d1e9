"""What the hands touch: classes round the wrists, and their join to frame features."""

import numpy as np

from homesim.learn.video.hands import HAND_RADIUS, WRISTS, hand_context, with_hands
from homesim.render.agent import JOINTS


def joints_at(points: list[tuple[float, float]]) -> np.ndarray:
    """(N, J, 3) joints with every joint at the frame's corner and both wrists at
    (x, y) shares of the frame, all visible."""
    joints = np.zeros((len(points), len(JOINTS), 3), np.float16)
    joints[..., 2] = 1
    for i, (x, y) in enumerate(points):
        joints[i, list(WRISTS), :2] = (x, y)
    return joints


def test_the_classes_round_the_wrists_are_counted_and_the_agent_is_left_out():
    maps = np.zeros((2, 24, 32), np.uint8)
    maps[0, 10:15, 14:19] = 3  # a 5 x 5 thing round cell (12, 16)
    maps[0, 12, 16] = 7  # the agent's own hand at its centre
    maps[1, 0:5, 0:5] = 5  # another thing in the far corner
    joints = joints_at([(16.5 / 32, 12.5 / 24), (0.9, 0.9)])
    hands = hand_context(maps, joints, 8, own_class=7)
    assert hands.shape == (2, 8) and hands.dtype == np.float32
    cells = (2 * HAND_RADIUS + 1) ** 2
    assert np.isclose(hands[0, 3], (cells - 1) / cells)  # both wrists see the same window
    assert hands[0, 7] == 0 and hands[0, 0] == 0
    assert hands[1, 5] == 0 and np.isclose(hands[1, 0], 1)  # the corner thing is far away


def test_a_wrist_outside_the_map_reads_its_edge():
    maps = np.zeros((1, 24, 32), np.uint8)
    maps[0, :, 31] = 2  # the right edge column
    hands = hand_context(maps, joints_at([(1.4, 0.5)]), 4)
    # the wrist's cell is the last column; the window's columns 29, 30, 31, 31, 31
    assert np.isclose(hands[0, 2], (HAND_RADIUS + 1) / (2 * HAND_RADIUS + 1))


def test_joined_hands_keep_the_features_and_share_their_spread():
    rng = np.random.default_rng(0)
    features = rng.normal(0, 2, (60, 6)).astype(np.float16)
    hands = rng.dirichlet(np.ones(5), 60).astype(np.float32)
    train = np.arange(50)
    joined = with_hands(features, hands, train)
    assert joined.shape == (60, 11) and joined.dtype == np.float16
    assert np.array_equal(joined[:, :6], features)
    block = joined[train, 6:].astype(np.float32)
    assert np.isclose(block.std(), features[train].astype(np.float32).std(), rtol=0.01)
    assert (block >= 0).all()
