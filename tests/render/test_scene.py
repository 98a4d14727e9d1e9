import pytest

from homesim.errors import HomesimError
from homesim.render.agent import AGENTS, HINGES, JOINTS
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


def test_trimmed_home_without_geometry_is_refused(tiny_home):
    with pytest.raises(HomesimError, match="no floor boxes"):
        build_scene(tiny_home, AGENTS["male1"])
