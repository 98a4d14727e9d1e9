import pytest

from homesim.errors import HomesimError
from homesim.render.agent import AGENTS, HINGES, JOINTS, agent_shape
from homesim.render.scene import build_scene

pytestmark = pytest.mark.render


def test_scene_maps_every_geom_to_a_node_and_class(box_home):
    scene = build_scene(box_home, AGENTS["female1"], max_size=(64, 48))
    m = scene.model
    assert set(scene.geom_node.tolist()) <= set(box_home.nodes)
    agent_geoms = [g for g in range(m.ngeom) if m.geom(g).name.startswith("agent:")]
    assert agent_geoms and all(scene.geom_node[g] == 10 for g in agent_geoms)
    assert scene.classes[0] == "background"
    assert scene.instances[21] == "cup" and scene.instances[10] == "character"
    assert set(scene.mocap) == {21, 24} and set(scene.hinge_qpos) == {23}
    assert set(scene.lamp_mat) == {25} and scene.lamp_light[25] >= 0
    assert set(scene.screen_geom) == {22}
    assert len(scene.joint_sites) == len(JOINTS) and set(scene.joint_qpos) == set(HINGES)


def test_cameras_per_room_are_randomised_by_seed(box_home):
    a = build_scene(box_home, AGENTS["male1"], seed=0, max_size=(64, 48)).cameras
    b = build_scene(box_home, AGENTS["male1"], seed=0, max_size=(64, 48)).cameras
    c = build_scene(box_home, AGENTS["male1"], seed=1, max_size=(64, 48)).cameras
    assert 6 <= len(a) <= 8
    assert [x.pos.tolist() for x in a] == [x.pos.tolist() for x in b]
    assert [x.pos.tolist() for x in a] != [x.pos.tolist() for x in c]
    assert all(x.pos[2] > 1.8 for x in a)  # high up, looking in and down
    assert all(x.forward[2] < 0 for x in a)


def test_four_agents_differ_and_unknown_agent_is_an_error():
    assert len(AGENTS) == 4 and len({a.height for a in AGENTS.values()}) == 4
    with pytest.raises(HomesimError, match="unknown agent 'robot'"):
        agent_shape("robot")


def test_trimmed_home_without_geometry_is_refused(tiny_home):
    with pytest.raises(HomesimError, match="no floor boxes"):
        build_scene(tiny_home, AGENTS["male1"])
