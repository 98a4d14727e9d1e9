import numpy as np
import pytest

from homesim.render.agent import AGENTS
from homesim.render.gl import mujoco
from homesim.render.renderer import Renderer
from homesim.render.scene import build_scene

from .conftest import place_camera

pytestmark = pytest.mark.render


@pytest.fixture
def scene(box_home, gl):
    return build_scene(box_home, AGENTS["male1"], max_size=(64, 48))


def test_depth_of_a_known_wall(scene):
    data = mujoco.MjData(scene.model)
    # From (-1, 1, 1.6) straight along +x: the wall's inner face is at x = 1.95.
    place_camera(scene, data, 0, (-1.0, 1.0, 1.6), (1.0, 0.0, 0.0))
    with Renderer(scene, 64, 48) as r:
        ids, depth = r.ids_depth(data, 0)
    assert depth.shape == (48, 64) and depth.dtype == np.float32
    assert abs(float(depth[24, 32]) - 2.95) < 0.01
    assert scene.geom_node[ids[24, 32]] == 3  # the +x wall's node id
    # A plane seen head-on has the same depth everywhere along the optical axis.
    rows = depth[20:28, 28:36]
    assert np.ptp(rows) < 0.01


def test_segmentation_ids_are_graph_node_ids(scene, box_home):
    data = mujoco.MjData(scene.model)
    # Look down at the table and cup from above.
    place_camera(scene, data, 0, (1.0, -1.0, 2.3), (0.0, 0.001, -1.0))
    with Renderer(scene, 64, 48) as r:
        ids, _ = r.ids_depth(data, 0)
        rgb = r.rgb(data, 0)
    nodes = set(np.unique(scene.geom_node[ids[ids >= 0]]).tolist())
    assert {20, 21} <= nodes  # table and cup
    assert nodes <= set(box_home.nodes)
    assert rgb.shape == (48, 64, 3) and rgb.dtype == np.uint8 and rgb.std() > 1


def test_probe_sees_the_agent(scene):
    data = mujoco.MjData(scene.model)
    mujoco.mj_forward(scene.model, data)
    start = scene.model.body("agent").pos.copy()
    cam = np.array([1.6, -1.7, 1.4])  # across the room, beside the table
    place_camera(scene, data, 0, cam, start - cam)
    with Renderer(scene, 64, 48) as r:
        share = r.probe(data, 0, scene.character_id)
    assert share > 0.02


def test_renderer_rejects_sizes_the_scene_was_not_built_for(scene):
    from homesim.errors import HomesimError

    with pytest.raises(HomesimError, match="larger than the scene was built for"):
        Renderer(scene, 128, 96)


def test_a_camera_moved_after_the_renderer_was_made_sees_what_it_now_faces(scene):
    """Culling follows a moved camera by itself (room cameras turn to track the agent,
    close-up candidates are drawn by moving one): culled for where camera 0 was, the wall
    it now faces would be missing."""
    data = mujoco.MjData(scene.model)
    place_camera(scene, data, 0, (-1.0, 1.0, 1.6), (-1.0, 0.0, 0.0))  # away from +x wall
    with Renderer(scene, 64, 48) as r:
        away, _ = r.ids_depth(data, 0)
        place_camera(scene, data, 0, (-1.0, 1.0, 1.6), (1.0, 0.0, 0.0))  # now toward it
        ids, depth = r.ids_depth(data, 0)
    assert scene.geom_node[away[24, 32]] != 3
    assert scene.geom_node[ids[24, 32]] == 3  # the +x wall
    assert abs(float(depth[24, 32]) - 2.95) < 0.01


def test_probe_measures_what_stands_close_in_front_of_the_camera(scene):
    """What blocks a room camera's view: pixels nearer than a distance, not counting the
    nodes asked about (the agent walking up to the camera blocks nothing)."""
    data = mujoco.MjData(scene.model)
    mujoco.mj_forward(scene.model, data)
    place_camera(scene, data, 0, (1.45, 1.0, 1.6), (1.0, 0.0, 0.0))  # 0.5 m from the wall
    agent = scene.character_id
    with Renderer(scene, 64, 48) as r:
        blocked = r.probe_view(data, 0, (agent,), near=1.0)
        farther = r.probe_view(data, 0, (agent,), near=0.3)
        start = scene.model.body("agent").pos.copy()
        cam = np.array([start[0], start[1] + 0.7, 1.0])  # level with the agent's chest
        place_camera(scene, data, 0, cam, (0.0, -1.0, 0.0))  # the wall 0.55 m behind it
        close_agent = r.probe_view(data, 0, (agent,), near=1.0)
        not_asked = r.probe_view(data, 0, (), near=1.0)
        assert close_agent.shares == r.probe_nodes(data, 0, (agent,))
    assert blocked.near > 0.95 and farther.near == 0.0
    assert close_agent.shares[0] > 0.1 and close_agent.near < 0.02
    assert not_asked.near > close_agent.shares[0] - 0.02
