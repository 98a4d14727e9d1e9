"""Ground truth on the model library: what the camera sees is exact against the graph."""

import numpy as np
import pytest

from homesim.render.agent import agent_shape
from homesim.render.flow import backproject, intrinsics, world_to_cam
from homesim.render.gl import mujoco
from homesim.render.layout import to_mujoco
from homesim.render.renderer import Renderer
from homesim.render.scene import build_scene
from homesim.world.homes import load_home

W, H = 160, 120
SLACK = 0.0101 + 0.003
"""Thin boxes are drawn 2 cm thick; plus the depth buffer's precision at a few metres."""


@pytest.fixture(scope="module", params=["scene1", "scene4"])
def views(request):
    """Segmentation and depth of every fifth camera of a home (doors closed, objects at
    their graph boxes)."""
    graph = load_home(request.param)
    scene = build_scene(graph, agent_shape("female1"), seed=3, max_size=(W, H))
    data = mujoco.MjData(scene.model)
    mujoco.mj_forward(scene.model, data)
    out = []
    with Renderer(scene, W, H) as r:
        for cam in range(0, len(scene.cameras), 5):
            ids, depth = r.ids_depth(data, cam)
            k = intrinsics(W, H, scene.cameras[cam].fovy)
            w2c = world_to_cam(data.cam_xpos[cam], data.cam_xmat[cam])
            out.append((ids, backproject(depth, k, w2c)))
    return graph, scene, out


def test_every_pixel_maps_to_its_nodes_id_and_class(views):
    graph, scene, out = views
    seen_nodes: set[int] = set()
    for ids, _ in out:
        for g in np.unique(ids[ids >= 0]):
            node = int(scene.geom_node[g])
            assert scene.classes[int(scene.geom_class[g])] == graph.node(node).class_name
            seen_nodes.add(node)
    assert len(seen_nodes) > 40  # the check looked at many objects
    many = [n for n in seen_nodes if sum(scene.geom_node == n) > 3]
    assert many  # and at models made of several geoms


def test_depth_back_projects_into_each_nodes_graph_box(views):
    graph, scene, out = views
    checked = 0
    for ids, points in out:
        seen = ids >= 0
        nodes = scene.geom_node[ids[seen]]
        pts = points[seen]
        for node in np.unique(nodes):
            if node == scene.character_id:
                continue
            box = to_mujoco(graph.node(int(node)))
            p = pts[nodes == node]
            outside = np.any((p < box.lo - SLACK) | (p > box.hi + SLACK), axis=1)
            assert not outside.any(), (graph.node(int(node)).label(), p[outside][:3])
            checked += len(p)
    assert checked > 0.5 * sum(ids.size for ids, _ in out)


def test_culling_changes_no_pixel_and_draws_fewer_geoms():
    graph = load_home("scene1")
    scene = build_scene(graph, agent_shape("male1"), seed=0, max_size=(W, H))
    data = mujoco.MjData(scene.model)
    mujoco.mj_forward(scene.model, data)
    with Renderer(scene, W, H) as culled, Renderer(scene, W, H) as full:
        full._groups = {c: full._groups[-1] for c in full._groups}  # nothing hidden
        hidden = [int((culled._groups[c] != full._groups[-1]).sum())
                  for c in range(len(scene.cameras))]
        assert max(hidden) > scene.model.ngeom // 4
        for cam in range(0, len(scene.cameras), 7):
            ids_a, depth_a = culled.ids_depth(data, cam)
            ids_b, depth_b = full.ids_depth(data, cam)  # interleaved: groups reset per draw
            np.testing.assert_array_equal(ids_a, ids_b)
            np.testing.assert_array_equal(depth_a, depth_b)
