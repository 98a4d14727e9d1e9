import numpy as np
import pytest

from homesim.render.agent import AGENTS
from homesim.render.ik import ArmIK
from homesim.render.poses import standing
from homesim.render.scene import build_scene

pytestmark = pytest.mark.render


def test_reaches_a_point_in_front_and_reports_what_it_cannot(box_home):
    shape = AGENTS["male1"]
    ik = ArmIK(build_scene(box_home, shape, max_size=(32, 24)))
    pose = standing(shape, (0.0, 0.0), 0.0)
    target = np.array([0.45, -0.2, 1.0])
    reached, err = ik.reach(pose, "r", target)
    assert err < 0.02
    np.testing.assert_allclose(ik.hand(reached, "r"), target, atol=0.02)
    assert reached.x == pose.x and reached.yaw == pose.yaw  # only the arm and spine move
    _, far = ik.reach(pose, "l", np.array([3.0, 0.0, 1.0]))
    assert far > 1.5
