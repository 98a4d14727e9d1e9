import numpy as np
import pytest

from homesim.render.agent import AGENTS, JOINTS
from homesim.render.animate import Timeline
from homesim.render.flow import intrinsics
from homesim.render.gl import mujoco
from homesim.render.recorder import is_cut, record
from homesim.render.renderer import Renderer
from homesim.render.scene import build_scene

from .conftest import place_camera

pytestmark = pytest.mark.render


def _two_frames(scene, shift):
    q0 = scene.model.qpos0.copy()
    q1 = q0.copy()
    q1[0] += shift  # the agent's root moves along world x
    mocap = np.array(scene.model.body_pos[scene.model.body_mocapid >= 0])
    tl = Timeline([q0, q1], [mocap, mocap], [frozenset()] * 2, [frozenset()] * 2, [(0, 1)])
    return tl


def test_flow_of_a_known_agent_motion_seen_side_on(box_home, gl):
    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    start = scene.model.body("agent").pos.copy()
    data = mujoco.MjData(scene.model)
    # Camera 1.6 m to the agent's +y, looking along -y: image right is world -x.
    place_camera(scene, data, 0, (start[0], start[1] + 1.6, 1.0), (0.0, -1.0, 0.0))
    shift = 0.05
    with Renderer(scene, 64, 48) as r:
        frames = list(record(scene, _two_frames(scene, shift), r, fixed_camera=0))
    first = frames[0]
    on_agent = first.instance_seg == scene.character_id
    assert on_agent.sum() > 50
    f = first.intrinsics[0, 0]
    expect_u = -f * shift / first.depth[on_agent]  # moving along -image-right
    np.testing.assert_allclose(first.flow[..., 0][on_agent], expect_u, rtol=1e-3, atol=1e-3)
    np.testing.assert_allclose(first.flow[..., 1][on_agent], 0.0, atol=1e-3)
    assert not first.flow[~on_agent].any()  # walls and furniture stand still
    assert not first.cut and not frames[1].flow.any()  # the last frame has no successor
    np.testing.assert_array_equal(first.flow_valid, first.depth > 0)  # all stay in view
    assert not frames[1].flow_valid.any()


def test_every_channel_has_its_shape_and_dtype(box_home, gl):
    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    with Renderer(scene, 64, 48) as r:
        (f, _) = list(record(scene, _two_frames(scene, 0.0), r))
    assert f.rgb.shape == (48, 64, 3) and f.rgb.dtype == np.uint8
    assert f.depth.shape == (48, 64) and f.depth.dtype == np.float32
    assert f.class_seg.shape == (48, 64) and f.class_seg.dtype == np.uint16
    assert f.instance_seg.shape == (48, 64) and f.instance_seg.dtype == np.int32
    assert f.flow.shape == (48, 64, 2) and f.flow.dtype == np.float32
    assert f.flow_valid.shape == (48, 64) and f.flow_valid.dtype == bool
    assert f.intrinsics.shape == (3, 3) and f.world_to_cam.shape == (4, 4)
    assert f.joints3d.shape == (16, 3) and f.joints2d.shape == (16, 2)
    assert f.joints_visible.dtype == bool
    # Classes and instances agree pixel by pixel.
    for nid in np.unique(f.instance_seg):
        cls = set(np.unique(f.class_seg[f.instance_seg == nid]).tolist())
        assert len(cls) == 1
    # The camera chosen sees the agent and its visible joints project where it is.
    assert (f.instance_seg == scene.character_id).any()
    vis = f.joints_visible
    assert vis.any()
    uv = np.round(f.joints2d[vis]).astype(int)
    assert np.all((uv >= 0) & (uv < [64, 48]))


def test_a_chosen_room_camera_is_aimed_at_the_agent_and_holds_still(box_home, gl):
    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    with Renderer(scene, 64, 48) as r:
        first, second = list(record(scene, _two_frames(scene, 0.3), r))
    pelvis = first.joints2d[JOINTS.index("pelvis")]
    assert abs(pelvis[0] - 31.5) < 0.1 * 64 and abs(pelvis[1] - 23.5) < 0.25 * 48
    assert first.camera == second.camera and not first.cut  # held, not aimed anew
    np.testing.assert_array_equal(first.world_to_cam, second.world_to_cam)
    still = first.flow_valid & (first.instance_seg != scene.character_id)
    assert still.any() and not first.flow[still].any()  # so still things stay still


def test_a_camera_aimed_anew_is_a_cut():
    k, w2c = intrinsics(64, 48, 60.0), np.eye(4)
    turned = w2c.copy()
    turned[:3, :3] = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    assert not is_cut(3, k, w2c, 3, k.copy(), w2c.copy())
    assert is_cut(3, k, w2c, 4, k, w2c)  # another camera
    assert is_cut(3, k, w2c, 3, k, turned)  # the same one turned
    assert is_cut(3, k, w2c, 3, intrinsics(64, 48, 40.0), w2c)  # or zoomed


def test_a_view_blocked_close_to_the_camera_scores_less(box_home, gl):
    """Two cameras on one wall that both see the agent across the room: the one standing
    beside the fridge (which fills a side of its view) scores less, by what it blocks."""
    from homesim.render.recorder import BLOCK_PENALTY, NEAR, view_score

    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    data = mujoco.MjData(scene.model)
    mujoco.mj_forward(scene.model, data)
    agent = data.xpos[scene.model.body("agent").id].copy()
    blocked_at = np.array([-1.15, 1.85, 1.5])  # the fridge: x -1.9..-1.3, y 1.1..1.7
    clear_at = np.array([0.6, 1.85, 1.5])  # along the same wall, nothing near
    for cam, pos in ((0, clear_at), (1, blocked_at)):
        place_camera(scene, data, cam, pos, agent - pos)
        scene.model.cam_fovy[cam] = 60.0
    mujoco.mj_camlight(scene.model, data)
    with Renderer(scene, 64, 48) as r:
        clear, blocked = (r.probe_view(data, c, (scene.character_id,), near=NEAR)
                          for c in (0, 1))
        scores = [view_score(r, data, scene, c) for c in (0, 1)]
    assert clear.shares[0] > 0.01 and blocked.shares[0] > 0.01  # both see the agent
    assert clear.near < 0.02 < 0.15 < blocked.near
    assert scores[0] - scores[1] > 0.5 * BLOCK_PENALTY * blocked.near
