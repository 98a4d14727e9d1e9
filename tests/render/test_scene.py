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


def test_a_home_over_the_node_limit_is_refused_before_compiling(box_home):
    """D11: a 100 000-node home made MuJoCo compile for 15+ min, deaf to SIGTERM."""
    import time

    from homesim.errors import LimitError
    from homesim.limits import MAX_RENDER_NODES
    from homesim.world.graph import EnvironmentGraph

    data = box_home.to_dict()
    first = max(n["id"] for n in data["nodes"]) + 1
    data["nodes"] += [{"id": first + i, "class_name": "cup",
                       "bounding_box": {"center": [0, 0.5, 0], "size": [0.1, 0.1, 0.1]}}
                      for i in range(MAX_RENDER_NODES)]
    big = EnvironmentGraph.from_dict(data)
    t0 = time.monotonic()
    with pytest.raises(LimitError, match="over the limit of 4,000 for rendering"):
        build_scene(big, AGENTS["male1"])
    assert time.monotonic() - t0 < 1


def test_small_frames_draw_round_shapes_with_fewer_sides(box_home):
    """Frames up to `SMALL_FRAME` pixels tall (the learn profile's 64x48) get the coarser
    tessellation of spheres, cylinders and capsules; larger ones (320x240, the default)
    keep the finer one."""
    from homesim.render.scene import SMALL_TESSELLATION, TESSELLATION

    assert SMALL_TESSELLATION < TESSELLATION
    for size, want in [((64, 48), SMALL_TESSELLATION), ((160, 120), SMALL_TESSELLATION),
                       ((320, 240), TESSELLATION), ((640, 480), TESSELLATION)]:
        q = build_scene(box_home, AGENTS["male1"], max_size=size).model.vis.quality
        assert (q.numslices, q.numstacks) == want, size
