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


def _plain_solve(ik, pose, side, target, grip, lean, grasp):
    """The solver as first written (the Jacobian and error stacked anew each iteration,
    `np.linalg.solve`, every iteration run): what `ArmIK._solve` must equal bit for bit."""
    import mujoco

    from homesim.render import ik as mod
    from homesim.render.poses import write_qpos

    names = mod.arm_joints(side, lean) + (mod.wrist_joints(side) if grasp else ())
    values = np.array([float(pose.joints.get(n, 0.0)) for n in names])
    site = (ik.scene.palm_sites if grasp else ik.scene.hand_sites)[side]
    body = int(ik.model.site_bodyid[site])
    offset = np.zeros(3) if grip is None else np.asarray(grip, float)
    model, data = ik._solver, mujoco.MjData(ik._solver)
    jacp, jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
    cols = [ik._dof[n] for n in names]
    addrs = np.array([ik.scene.joint_qpos[n] for n in names])
    lo, hi = np.array([ik._range[n] for n in names]).T
    eye = mod.DAMPING**2 * np.eye(9 if grasp is not None else 3)
    write_qpos(data.qpos, pose, ik.scene.joint_qpos)
    err = np.inf
    for _ in range(mod.ITERATIONS * (2 if grasp else 1)):
        data.qpos[addrs] = values
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        rot = data.xmat[body].reshape(3, 3)
        point = data.site_xpos[site] + rot @ offset
        e = target - point
        err = float(np.linalg.norm(e))
        mujoco.mj_jac(model, data, jacp, jacr, point, body)
        jac = jacp[:, cols]
        if grasp is not None:
            palm = rot[:, 1] * (-1.0 if side == "l" else 1.0)
            turns = [np.cross(palm, grasp.palm), np.cross(-rot[:, 2], grasp.fingers)]
            if err < mod.TOLERANCE and max(np.linalg.norm(t) for t in turns) < 0.1:
                break
            e = np.concatenate([e] + [w * t for w, t in zip(mod.ORIENT_WEIGHT, turns, strict=True)])
            jac = np.vstack([jac] + [w * jacr[:, cols] for w in mod.ORIENT_WEIGHT])
        elif err < mod.TOLERANCE:
            break
        dq = jac.T @ np.linalg.solve(jac @ jac.T + eye, e)
        values = np.minimum(np.maximum(values + np.minimum(np.maximum(dq, -0.3), 0.3), lo), hi)
    return pose.with_joints(**dict(zip(names, values.tolist(), strict=True))), err


def test_a_solve_is_the_plain_loops_arithmetic_bit_for_bit(box_home, monkeypatch):
    """The solver's buffers, direct LAPACK call and stop at a repeat (issue 42's speed)
    give the very bits of the plain loop: reaches and grasps met, missed (run to the
    last iteration) and cycling (the values of an earlier iteration come back), with and
    without a held point's offset, leaning or not."""
    from homesim.render import ik as mod
    from homesim.render.ik import Grasp

    cycles = []
    end = mod._cycle_end
    monkeypatch.setattr(mod, "_cycle_end", lambda *a: cycles.append(a[1:3]) or end(*a))
    shape = AGENTS["male1"]
    ik = ArmIK(build_scene(box_home, shape, max_size=(32, 24)))
    pose = standing(shape, (0.0, 0.0), 0.3)
    cases = [("r", np.array([0.45, -0.2, 1.0]), None, True, None),
             ("l", np.array([3.0, 0.5, 1.0]), None, True, None),
             ("r", np.array([0.4, -0.3, 0.5]), np.array([0.0, 0.05, -0.1]), False, None)]
    for i, (x, y, z) in enumerate([(0.42, -0.25, 0.95), (0.9, 0.6, 0.2), (-0.5, 0.1, 1.9),
                                   (0.3, 0.3, 1.2), (1.4, -0.9, 0.6)]):
        palm, fingers = np.array([0.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0])
        for side in "lr":
            cases.append((side, np.array([x, y, z]), None, i % 2 == 0,
                          Grasp(np.array([x, y, z]), palm, fingers)))
    for side, target, grip, lean, grasp in cases:
        got = ik._solve(pose, side, target, grip, lean, grasp)
        want = _plain_solve(ik, pose, side, target, grip, lean, grasp)
        assert got[0] == want[0] and got[1] == want[1], (side, target, grasp)
    assert cycles  # the stop at a repeat was taken


def test_a_cycle_ends_where_running_it_to_the_limit_would():
    """`_cycle_end` from a history whose values come back `period` steps later: the
    values after the last of `limit` steps and the error measured at the last."""
    from homesim.render.ik import _cycle_end

    for first, period, limit in [(0, 1, 10), (3, 2, 10), (3, 2, 11), (5, 4, 160), (2, 7, 80)]:
        def state(i, first=first, period=period):  # iteration i of a loop cycling at first
            j = i if i < first else first + (i - first) % period
            return np.array([float(j)]), 10.0 + j
        history = [state(i) for i in range(first + period)]
        values, err = _cycle_end(history, first, period, limit)
        assert values[0] == state(limit)[0][0] and err == state(limit - 1)[1]
