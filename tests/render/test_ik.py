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


def test_grasp_puts_the_palm_on_the_point_facing_the_object(box_home):
    from homesim.render.ik import Grasp

    shape = AGENTS["female1"]
    ik = ArmIK(build_scene(box_home, shape, max_size=(32, 24)))
    pose = standing(shape, (0.0, 0.0), 0.0)
    grasp = Grasp(np.array([0.42, -0.25, 0.95]), np.array([0.0, 1.0, 0.0]),
                  np.array([1.0, 0.0, 0.0]))
    reached, err = ik.grasp(pose, "r", grasp)
    assert err < 0.01
    np.testing.assert_allclose(ik.site(reached, "r_palm"), grasp.point, atol=0.01)
    _, rot = ik.hand_frame(reached, "r")
    assert rot[:, 1] @ grasp.palm > 0.95  # the right palm (+y of the hand) faces +y
    assert -rot[:, 2] @ grasp.fingers > 0.9  # fingers forward
    wrist = ik.site(reached, "j:r_wrist")
    assert abs(wrist[1] - grasp.point[1]) < 0.025  # the wrist lies by the face, not behind
    assert any(abs(reached.joints.get(f"r_wrist_{j}", 0.0)) > 0.05
               for j in ("twist", "flex", "dev"))


def test_a_solve_asked_again_is_answered_from_memory_with_the_same_values(box_home,
                                                                          monkeypatch):
    """The reach planner asks the same solves again (a grasp from each point it weighs):
    the second answer is the first's values, solved once; other inputs solve anew, and
    changing an answer's joints does not change what is remembered."""
    from homesim.render.ik import Grasp

    shape = AGENTS["male1"]
    ik = ArmIK(build_scene(box_home, shape, max_size=(32, 24)))
    solves = []
    solve = ArmIK._solve
    monkeypatch.setattr(ArmIK, "_solve", lambda self, *a: solves.append(a) or solve(self, *a))
    pose = standing(shape, (0.0, 0.0), 0.0)
    grasp = Grasp(np.array([0.42, -0.25, 0.95]), np.array([0.0, 1.0, 0.0]),
                  np.array([1.0, 0.0, 0.0]))
    first, err = ik.grasp(pose, "r", grasp)
    first.joints["r_elbow"] = 9.0  # a caller's change stays its own
    again, err2 = ik.grasp(pose, "r", grasp)
    assert len(solves) == 1 and err2 == err and again.joints["r_elbow"] != 9.0
    assert again == ik._solve(pose, "r", grasp.point, None, True, grasp)[0]
    ik.grasp(pose, "l", grasp)  # the other hand
    ik.grasp(standing(shape, (0.0, 0.01), 0.0), "r", grasp)  # from elsewhere
    ik.reach(pose, "r", grasp.point)  # a reach, not a grasp
    ik.reach(pose, "r", grasp.point, lean=False)
    assert len(solves) == 6
