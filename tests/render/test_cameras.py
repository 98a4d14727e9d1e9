import numpy as np
import pytest

from homesim.render.agent import AGENTS
from homesim.render.cameras import AIM_HEIGHT, FRAMED_HEIGHT, MIN_AIMED_FOVY, aimed, look_at
from homesim.render.gl import mujoco
from homesim.render.scene import build_scene

pytestmark = pytest.mark.render


def test_look_at_gives_orthonormal_axes_facing_the_target():
    pos, target = np.array([0.0, 0.0, 2.0]), np.array([3.0, 1.0, 1.0])
    x, y = look_at(pos, target)
    forward = np.cross(y, x)
    np.testing.assert_allclose([x @ x, y @ y, x @ y], [1, 1, 0], atol=1e-12)
    np.testing.assert_allclose(forward, (target - pos) / np.linalg.norm(target - pos))
    assert y[2] > 0  # image up points up


def _forward(quat: np.ndarray) -> np.ndarray:
    mat = np.zeros(9)
    mujoco.mju_quat2Mat(mat, quat)
    return -mat.reshape(3, 3)[:, 2]  # MuJoCo cameras look along their -z axis


@pytest.mark.parametrize("agent", [(1.0, 0.5, 0.9), (-6.0, 4.0, 0.5), (0.3, -0.2, 0.9)])
def test_an_aimed_camera_faces_the_agent_and_zooms_with_distance(agent):
    pos, base = np.array([2.0, 2.0, 2.15]), 70.0
    quat, fovy = aimed(pos, np.array(agent), base)
    target = np.array(agent) + np.array([0.0, 0.0, AIM_HEIGHT])
    distance = np.linalg.norm(target - pos)
    np.testing.assert_allclose(_forward(quat), (target - pos) / distance, atol=1e-9)
    assert MIN_AIMED_FOVY <= fovy <= base
    if fovy < base:  # zoomed: the view spans FRAMED_HEIGHT at the agent
        assert 2 * distance * np.tan(np.radians(fovy) / 2) == pytest.approx(
            max(FRAMED_HEIGHT, 2 * distance * np.tan(np.radians(MIN_AIMED_FOVY) / 2)))
    near, far = aimed(pos, np.array([1.5, 1.5, 0.9]), base)[1], \
        aimed(pos, np.array([-4.0, -4.0, 0.9]), base)[1]
    assert far < near  # farther agents are zoomed in on more


def test_cameras_per_room_are_randomised_by_seed(box_home):
    a = build_scene(box_home, AGENTS["male1"], seed=0, max_size=(64, 48)).cameras
    b = build_scene(box_home, AGENTS["male1"], seed=0, max_size=(64, 48)).cameras
    c = build_scene(box_home, AGENTS["male1"], seed=1, max_size=(64, 48)).cameras
    assert 6 <= len(a) <= 8
    assert [x.pos.tolist() for x in a] == [x.pos.tolist() for x in b]
    assert [x.pos.tolist() for x in a] != [x.pos.tolist() for x in c]
    assert all(x.pos[2] > 1.8 for x in a)  # high up, looking in and down
    assert all(x.forward[2] < 0 for x in a)


