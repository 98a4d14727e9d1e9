"""The renderer leaves out what cannot show (`Renderer._frame_groups`, `_probe_groups`):
the same pixels as drawing every geom of the view, at a fraction of the draws' cost."""

import numpy as np
import pytest

from homesim.render.agent import AGENTS
from homesim.render.gl import mujoco
from homesim.render.renderer import HIDDEN_GROUP, Renderer
from homesim.render.scene import build_scene

from .conftest import place_camera

pytestmark = pytest.mark.render


def _every_geom(monkeypatch) -> None:
    """Renderers made after this draw every geom in the view (frustum culling only)."""
    monkeypatch.setattr(Renderer, "_frame_groups", lambda self, data, cam: self._culled(data, cam))
    monkeypatch.setattr(Renderer, "_probe_groups",
                        lambda self, data, cam, nodes, near: self._culled(data, cam))


@pytest.fixture(scope="module")
def walk(gl):
    """An animation in scene1: the agent walks to the TV and switches it on."""
    import homesim
    from homesim.render import animate

    run = homesim.run_program("[Walk] <television> (1)\n[SwitchOn] <television> (1)",
                              "scene1", trace=True)
    return animate(run, width=32, height=24, fps=2, seed=1)


def test_leaving_out_what_does_not_show_changes_no_pixel(walk, monkeypatch):
    """Frames from fixed cameras while the agent walks past, drawn with the geoms that
    do not show left out (found once per camera pose) and with every geom in the view:
    the same colour, ids and depth (what the agent hid at the first draw shows later)."""
    from homesim.render.recorder import SceneState

    state = SceneState(walk.scene, walk.timeline, aim_cameras=False)
    frames = [(i, c) for i in range(0, len(walk), 3)
              for c in range(0, walk.scene.model.ncam, 5)]
    lean_drawn, culled = [], []
    with Renderer(walk.scene, 32, 24) as lean:
        for i, cam in frames:
            d = state.apply(i)
            culled.append((lean.rgb(d, cam), *lean.ids_depth(d, cam)))
            lean_drawn.append(int(np.count_nonzero(lean._drawn != HIDDEN_GROUP)))
    _every_geom(monkeypatch)
    full_drawn = []
    with Renderer(walk.scene, 32, 24) as full:
        for (i, cam), (rgb, ids, depth) in zip(frames, culled, strict=True):
            d = state.apply(i)
            np.testing.assert_array_equal(full.rgb(d, cam), rgb)
            full_drawn.append(int(np.count_nonzero(full._drawn != HIDDEN_GROUP)))
            ids_full, depth_full = full.ids_depth(d, cam)
            np.testing.assert_array_equal(ids_full, ids)
            np.testing.assert_array_equal(depth_full, depth)
    assert sum(lean_drawn) < 0.6 * sum(full_drawn)  # and the draws were lighter


def test_what_stands_behind_glass_is_drawn(box_home, gl, monkeypatch):
    """A transparent geom hides nothing: the TV seen from outside the room through a
    glass wall is drawn in colour, as when every geom is drawn."""
    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    m = scene.model
    wall = np.flatnonzero(scene.geom_node == 3)  # the +x wall, behind the TV
    m.geom_matid[wall] = -1
    m.geom_rgba[wall] = (0.8, 0.9, 1.0, 0.3)
    data = mujoco.MjData(m)
    place_camera(scene, data, 0, (3.5, 1.0, 1.0), (-1.0, 0.0, 0.0))  # outside, at the TV
    with Renderer(scene, 64, 48) as lean:
        rgb = lean.rgb(data, 0)
        tv_drawn = np.any(lean._drawn[scene.geom_node == 22] != HIDDEN_GROUP)
        ids, _ = lean.ids_depth(data, 0)
    assert np.any(scene.geom_node[ids[ids >= 0]] == 3)  # the glass in front of the camera
    assert tv_drawn  # behind it
    _every_geom(monkeypatch)
    with Renderer(scene, 64, 48) as full:
        np.testing.assert_array_equal(full.rgb(data, 0), rgb)


def test_an_object_moved_into_the_view_is_drawn(box_home, gl, monkeypatch):
    """A pose drawn from again after an object moved is searched again: the apple carried
    in front of a camera that saw only a wall shows, as when every geom is drawn."""
    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    m = scene.model
    data = mujoco.MjData(m)
    place_camera(scene, data, 0, (0.0, 0.0, 1.5), (-1.0, 0.0, 0.0))  # toward the -x wall
    apple = int(m.body_mocapid[m.geom_bodyid[np.flatnonzero(scene.geom_node == 24)[0]]])
    frames = []
    with Renderer(scene, 64, 48) as lean:
        for pos in (None, (-1.0, 0.0, 1.5)):
            if pos is not None:
                data.mocap_pos[apple] = pos
                mujoco.mj_kinematics(m, data)
            frames.append((lean.rgb(data, 0), *lean.ids_depth(data, 0)))
    before, after = (scene.geom_node[ids[ids >= 0]] for _, ids, _ in frames)
    assert not np.any(before == 24) and np.any(after == 24)  # the apple, in front now
    _every_geom(monkeypatch)
    with Renderer(scene, 64, 48) as full:
        rgb, ids, depth = frames[1]
        np.testing.assert_array_equal(full.rgb(data, 0), rgb)
        ids_full, depth_full = full.ids_depth(data, 0)
        np.testing.assert_array_equal(ids_full, ids)
        np.testing.assert_array_equal(depth_full, depth)


def test_probes_and_weighed_views_see_what_every_geom_shows(walk, monkeypatch):
    """A probe draws only what may cover the nodes asked about or come near the camera,
    and `ids_depth(nodes=...)` only what may cover the nodes: the shares, what is near,
    and every pixel of those nodes are those of a draw of every geom."""
    from homesim.render.recorder import SceneState

    scene = walk.scene
    agent, tv = scene.character_id, walk.timeline.focus[-1]
    state = SceneState(scene, walk.timeline)
    frames = [(i, c) for i in range(0, len(walk), 4) for c in range(0, scene.model.ncam, 3)]

    def views(renderer):
        out = []
        for i, cam in frames:
            state.apply(i)
            state.aim(cam)
            d = state.data
            probe = renderer.probe_view(d, cam, (agent, tv), (16, 12), near=1.0)
            ids, depth = renderer.ids_depth(d, cam, nodes=(tv, agent))
            out.append((probe, ids, depth, int(np.count_nonzero(renderer._drawn != HIDDEN_GROUP))))
        return out

    with Renderer(scene, 32, 24) as lean:
        culled = views(lean)
    _every_geom(monkeypatch)
    with Renderer(scene, 32, 24) as full:
        drawn = views(full)
    for (p0, ids0, depth0, _), (p1, ids1, depth1, _) in zip(culled, drawn, strict=True):
        assert p0 == p1
        mine = np.isin(scene.geom_node[ids1], (agent, tv)) & (ids1 >= 0)
        np.testing.assert_array_equal(ids0[mine], ids1[mine])
        np.testing.assert_array_equal(depth0[mine], depth1[mine])
    assert any(p.shares[0] > 0 for p, *_ in drawn) and any(p.near > 0 for p, *_ in drawn)
    assert sum(c[3] for c in culled) < 0.5 * sum(c[3] for c in drawn)
