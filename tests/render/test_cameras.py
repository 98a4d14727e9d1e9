import numpy as np
import pytest

from homesim.render.agent import AGENTS
from homesim.render.cameras import look_at
from homesim.render.scene import build_scene

pytestmark = pytest.mark.render


def test_look_at_gives_orthonormal_axes_facing_the_target():
    pos, target = np.array([0.0, 0.0, 2.0]), np.array([3.0, 1.0, 1.0])
    x, y = look_at(pos, target)
    forward = np.cross(y, x)
    np.testing.assert_allclose([x @ x, y @ y, x @ y], [1, 1, 0], atol=1e-12)
    np.testing.assert_allclose(forward, (target - pos) / np.linalg.norm(target - pos))
    assert y[2] > 0  # image up points up


def test_cameras_per_room_are_randomised_by_seed(box_home):
    a = build_scene(box_home, AGENTS["male1"], seed=0, max_size=(64, 48)).cameras
    b = build_scene(box_home, AGENTS["male1"], seed=0, max_size=(64, 48)).cameras
    c = build_scene(box_home, AGENTS["male1"], seed=1, max_size=(64, 48)).cameras
    assert 6 <= len(a) <= 8
    assert [x.pos.tolist() for x in a] == [x.pos.tolist() for x in b]
    assert [x.pos.tolist() for x in a] != [x.pos.tolist() for x in c]
    assert all(x.pos[2] > 1.8 for x in a)  # high up, looking in and down
    assert all(x.forward[2] < 0 for x in a)


