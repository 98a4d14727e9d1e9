import math

import numpy as np
import pytest

import homesim
from homesim.errors import HomesimError
from homesim.render.agent import (
    AGENTS,
    FINGER_CLOSED,
    HINGES,
    JOINTS,
    agent_mjcf,
    agent_shape,
)


def test_four_agents_are_two_men_and_two_women_who_look_different():
    agents = list(AGENTS.values())
    assert sorted(a.sex for a in agents) == ["female", "female", "male", "male"]
    assert len({a.height for a in agents}) == 4
    assert len({a.outfit.top for a in agents}) == 4 and len({a.skin for a in agents}) == 4
    assert len({a.hair.style for a in agents}) == 4
    assert {a.outfit.skirt for a in agents if a.sex == "female"} == {True}
    with pytest.raises(HomesimError, match="unknown agent 'robot'"):
        agent_shape("robot")


def test_agent_mjcf_names_every_hinge_and_keypoint():
    for shape in AGENTS.values():
        xml = agent_mjcf(shape)
        assert all(f'name="a:{h}"' in xml for h in HINGES)
        assert xml.count('<site name="j:') == len(JOINTS) == 16


pytestmark = pytest.mark.render


def _standing_data(scene, shape, grip=0.0):
    from homesim.render.gl import mujoco
    from homesim.render.poses import standing, write_qpos

    data = mujoco.MjData(scene.model)
    pose = standing(shape, scene.model.body("agent").pos[:2], 0.0)
    write_qpos(data.qpos, pose.with_grip("l", grip).with_grip("r", grip), scene.joint_qpos)
    mujoco.mj_kinematics(scene.model, data)
    return data


def _agent_z_range(scene, data) -> tuple[float, float]:
    """Lowest and highest point of the agent's geoms (world z)."""
    m = scene.model
    lo, hi = np.inf, -np.inf
    for g in range(m.ngeom):
        if not m.geom(g).name.startswith("agent:"):
            continue
        centre, half = m.geom_aabb[g, :3], m.geom_aabb[g, 3:]
        rot = data.geom_xmat[g].reshape(3, 3)
        z = data.geom_xpos[g, 2] + rot[2] @ centre
        reach = np.abs(rot[2]) @ half
        lo, hi = min(lo, z - reach), max(hi, z + reach)
    return lo, hi


@pytest.mark.parametrize("name", list(AGENTS))
def test_each_agent_compiles_stands_its_height_and_is_all_character(box_home, name):
    from homesim.render.scene import build_scene

    shape = AGENTS[name]
    scene = build_scene(box_home, shape, max_size=(64, 48))
    m = scene.model
    agent_geoms = [g for g in range(m.ngeom) if m.geom(g).name.startswith("agent:")]
    assert len(agent_geoms) > 30  # head, face, hair, hands with fingers, clothes...
    assert {int(scene.geom_node[g]) for g in agent_geoms} == {scene.character_id}
    assert {scene.classes[int(scene.geom_class[g])] for g in agent_geoms} == {"character"}
    lo, hi = _agent_z_range(scene, _standing_data(scene, shape))
    assert abs(lo) < 0.015  # soles on the floor (knees a little bent)
    assert abs(hi - shape.height) < 0.03  # top of the head (or hair)


def _project(data, cam: int, points: np.ndarray, w: int, h: int, fovy: float) -> np.ndarray:
    """Pinhole projection from MuJoCo's camera pose (OpenCV pixels, centres at integers),
    computed here independently of the recorder."""
    rot = data.cam_xmat[cam].reshape(3, 3)  # columns: camera x, y, z (z looks backward)
    local = (points - data.cam_xpos[cam]) @ rot
    x, y, z = local[:, 0], -local[:, 1], -local[:, 2]
    f = 0.5 * h / math.tan(math.radians(fovy) / 2)
    return np.stack([(w - 1) / 2 + f * x / z, (h - 1) / 2 + f * y / z], axis=1)


@pytest.mark.parametrize("name", list(AGENTS))
def test_joints_reproject_exactly_and_lie_inside_the_body(box_home, gl, name):
    from homesim.render.animate import Timeline
    from homesim.render.recorder import record
    from homesim.render.renderer import Renderer
    from homesim.render.scene import build_scene

    from .conftest import place_camera

    shape = AGENTS[name]
    scene = build_scene(box_home, shape, max_size=(160, 120))
    data = _standing_data(scene, shape, grip=1.0)
    start = scene.model.body("agent").pos
    place_camera(scene, data, 0, (start[0] + 2.6, start[1], 1.0), (-1.0, 0.0, 0.0))
    mocap = np.array(scene.model.body_pos[scene.model.body_mocapid >= 0])
    timeline = Timeline([data.qpos.copy()], [mocap], [frozenset()], [frozenset()], [(0, 0)])
    with Renderer(scene, 160, 120) as r:
        (f,) = list(record(scene, timeline, r, fixed_camera=0))
    expect = _project(data, 0, data.site_xpos[scene.joint_sites], 160, 120,
                      float(scene.model.cam_fovy[0]))
    # 0.005 px: the scene's MJCF writes fovy to 0.01 degree, the intrinsics use it unrounded.
    np.testing.assert_allclose(f.joints2d, expect, atol=5e-3)
    np.testing.assert_allclose(f.joints3d, data.site_xpos[scene.joint_sites], atol=1e-6)
    assert f.joints_visible.all()  # seen from the front, standing: every joint
    uv = np.round(f.joints2d).astype(int)
    on = f.instance_seg[uv[:, 1], uv[:, 0]]
    assert (on == scene.character_id).all(), [j for j, n in zip(JOINTS, on, strict=True)
                                              if n != scene.character_id]


def test_grip_closes_the_hand_that_holds_and_opens_it_when_put_down(box_home):
    from homesim.render.animate import Animator
    from homesim.render.scene import build_scene

    shape = AGENTS["female2"]
    scene = build_scene(box_home, shape, max_size=(64, 48))
    program = homesim.parse_program("[Walk] <cup> (21)\n[Grab] <cup> (21)\n"
                                    "[Walk] <tv> (22)\n[Drop] <cup> (21)\n")
    result = homesim.execute(program, box_home, trace=True, reference=True)
    tl = Animator(scene, box_home, shape, fps=10).run(result)
    open_, closed = FINGER_CLOSED["fingers"]
    fingers = {s: scene.joint_qpos[f"{s}_fingers"] for s in ("l", "r")}
    walking, carrying = tl.step_frames[0][1], tl.step_frames[2][1]
    assert tl.qpos[walking][fingers["r"]] == pytest.approx(open_)
    assert tl.qpos[carrying][fingers["r"]] == pytest.approx(closed)
    assert tl.qpos[carrying][fingers["l"]] == pytest.approx(open_)  # the free hand
    assert tl.qpos[-1][fingers["r"]] == pytest.approx(open_)  # dropped: open again
