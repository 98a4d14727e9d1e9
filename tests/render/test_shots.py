import numpy as np
import pytest

import homesim
from homesim.render.api import animate
from homesim.render.recorder import SceneState, record, shot_camera
from homesim.render.renderer import Renderer
from homesim.render.shots import LOW_HEIGHT, RING_HEIGHTS, shot_frames

pytestmark = pytest.mark.render

PROGRAM = "[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Walk] <tv> (22)\n[SwitchOn] <tv> (22)\n"


@pytest.fixture(scope="module")
def prepared():
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict, ran

    g = EnvironmentGraph.from_dict(box_home_dict())
    a = animate(ran(PROGRAM, g), width=64, height=48, fps=6, seed=0, agent="male1")
    return a.scene, a.timeline, a.agent


def test_each_interaction_gets_a_close_up_from_its_own_room(prepared):
    scene, tl, _ = prepared
    assert [it.step for it in tl.interactions] == [1, 3]
    shots = [c for c in scene.cameras if c.shot >= 0]
    assert [c.step for c in shots] == [1, 3]
    rooms = [c for c in scene.cameras if c.shot < 0]
    for cam in shots:
        it = tl.interactions[cam.shot]
        assert cam.room_id == it.room == 1
        # placed where a camera of the room is, or on the way from one to the action, at
        # its height or lowered to see into furniture, or on a ring around the action
        assert any(np.allclose(cam.pos[2], c.pos[2]) for c in rooms) or np.isclose(
            cam.pos[2], LOW_HEIGHT) or np.isclose(cam.pos[2], RING_HEIGHTS).any()
    assert shots[0].fovy < 0.75 * min(c.fovy for c in rooms)  # the cup: narrowed to it


def test_recording_films_interactions_with_their_close_up(prepared, gl):
    scene, tl, _ = prepared
    per_frame = shot_frames(scene, tl)
    with Renderer(scene, 64, 48) as r:
        frames = list(record(scene, tl, r))
    for it in tl.interactions:
        cams = {frames[f].camera for f in range(it.start, it.end + 1)}
        (cam,) = cams
        assert scene.cameras[cam].shot >= 0 and scene.cameras[cam].room_id == it.room
        assert per_frame[it.peak] == cam
        seen = frames[it.peak].instance_seg == it.nodes[0]
        assert seen.mean() >= 0.005  # the object fills a fair part of the frame
    others = {f.camera for f in frames if per_frame[f.index] < 0}
    assert all(scene.cameras[c].shot < 0 for c in others)


@pytest.mark.parametrize(("share", "hand", "close_ups"), [(0.0, False, 0), (0.0, True, 2),
                                                          (0.01, False, 2)])
def test_a_step_no_candidate_view_shows_gets_no_close_up(monkeypatch, gl, share, hand,
                                                         close_ups):
    """Where every drawn candidate shows neither the object nor the hand (a counter in
    front of the camera), the room camera films the step instead."""
    from homesim.render import shots
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict, ran

    monkeypatch.setattr(shots._SpareCamera, "view", lambda *a: (share, hand, 0.1))
    g = EnvironmentGraph.from_dict(box_home_dict())
    a = animate(ran(PROGRAM, g), width=64, height=48, fps=6, seed=0, agent="male1")
    scene, tl = a.scene, a.timeline
    assert len(tl.interactions) == 2
    assert sum(c.shot >= 0 for c in scene.cameras) == close_ups


def test_switching_a_screen_is_filmed_from_the_screen_side(gl):
    """In scene 1 the room camera nearest the TV sees its back: the close-up of switching
    it on must show the panel that lights up, not the set's back."""
    run = homesim.run_program("[Walk] <television> (1)\n[SwitchOn] <television> (1)", "scene1",
                              seed=0, trace=True)
    a = animate(run, width=64, height=48, fps=6, seed=0, agent="male1")
    scene, tl = a.scene, a.timeline
    (it,) = tl.interactions
    cam = shot_camera(scene, tl, it.peak)
    assert cam is not None and scene.cameras[cam].shot == 0
    with Renderer(scene, 64, 48) as r:
        ids, _ = r.ids_depth(SceneState(scene, tl).apply(it.peak), cam)
    assert (ids == scene.screen_geom[it.nodes[0]]).mean() >= 0.05


def test_a_view_the_body_fills_is_widened():
    from homesim.render import shots
    from homesim.render.cameras import CameraSpec

    class Spare:  # the body covers 60 % of a tight view, 20 % once the view is wider
        def view(self, renderer, data, spec, it, arm, seen):
            return 0.03, True, 0.6 if spec.fovy < 30 else 0.2

    tight = CameraSpec("shot0", 1, np.zeros(3), np.array([1.0, 0, 0]), np.array([0, 0, -1.0]),
                       20.0, 0, 1)
    best = shots._best_view(Spare(), None, None, None, frozenset(), None, [(tight, tight)])
    assert best is not None and best.fovy == pytest.approx(20.0 * shots.WIDER[0])


@pytest.mark.parametrize(("far_share", "chosen"), [(0.004, 8.0), (0.03, 30.0)])
def test_a_small_object_is_framed_at_the_effect_only(far_share, chosen):
    """Where no view framing the whole reach shows the object well (a cellphone put back:
    0.4 % of the view), the view framing only the hand and the object at the effect is
    drawn and kept; where the object shows well, it is not needed."""
    from homesim.render import shots
    from homesim.render.cameras import CameraSpec

    class Spare:
        def view(self, renderer, data, spec, it, arm, seen):
            return (far_share if spec.fovy > 10 else 0.04), True, 0.1

    def spec(fovy):
        return CameraSpec("shot0", 1, np.zeros(3), np.array([1.0, 0, 0]),
                          np.array([0, 0, -1.0]), fovy, 0, 1)

    best = shots._best_view(Spare(), None, None, None, frozenset(), None,
                            [(spec(30.0), spec(8.0))])
    assert best is not None and best.fovy == pytest.approx(chosen)


def test_a_ray_stopped_by_where_the_object_goes_does_not_see_it(monkeypatch):
    """Ranking close-up positions for a put, a ray that meets the bookshelf the phone goes
    into before the phone does not see the phone (side views of the shelf ranked first)."""
    import types

    from homesim.render import shots
    from homesim.render.animate import Interaction
    from homesim.render.cameras import CameraSpec

    asked = []
    monkeypatch.setattr(shots, "visible", lambda scene, data, eye, point, nodes, *a, **k:
                        asked.append(nodes) or True)
    scene = types.SimpleNamespace(hand_sites={"r": 0})
    data = types.SimpleNamespace(site_xpos=np.zeros((1, 3)))

    it = Interaction(2, (254, 260), "r", 0, 5, 9, 1)  # the phone, then the bookshelf
    cam = CameraSpec("c", 1, np.ones(3), np.array([1.0, 0, 0]), np.array([0, 0, -1.0]), 40.0)
    shots._score(scene, data, cam, it, [np.zeros(3)], frozenset())
    assert asked and all(nodes == (254,) for nodes in asked)


def test_rays_among_points_leave_out_only_geoms_they_cannot_meet(prepared):
    """Ranking close-up positions casts rays among a few points (cameras, the object,
    the hand) against the geoms near them only (`_rays_among`): every ray between two
    of the points sees what it sees against every geom, and the model's groups come
    back as they were."""
    from homesim.render import shots
    from homesim.render.gl import mujoco

    scene, tl, _ = prepared
    m = scene.model
    data = mujoco.MjData(m)
    it = tl.interactions[0]
    shots._pose(scene, tl, it.peak, data)
    cams = shots._positions(scene, it.room, data.site_xpos[scene.hand_sites[it.side]])[:6]
    targets = shots._targets(scene, it, data)
    ends = np.array([*(c.pos for c in cams), *targets])
    before = m.geom_group.copy()
    pairs = [(a, b) for a in ends[:len(cams)] for b in ends[len(cams):]]
    nodes = (it.nodes[0],)
    want = [shots.visible(scene, data, a, b, nodes) for a, b in pairs]
    with shots._rays_among(scene, data, ends) as groups:
        assert groups is not None and np.count_nonzero(m.geom_group == shots.RAY_HIDDEN)
        got = [shots.visible(scene, data, a, b, nodes, groups=groups) for a, b in pairs]
    assert got == want and any(want) and not all(want)
    np.testing.assert_array_equal(m.geom_group, before)
