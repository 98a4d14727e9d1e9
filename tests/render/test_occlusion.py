import numpy as np
import pytest

from homesim.render import occlusion
from homesim.render.gl import mujoco

pytestmark = pytest.mark.render

# A wall 4 m wide, 0.1 m thick, 2.5 m high at x = 2; boxes behind it, beside it, across
# its end, on its front and back faces, and a pane of glass and a ball further on.
MJCF = """<mujoco><worldbody>
  <geom name="wall" type="box" pos="2 0 1.25" size="0.05 2 1.25"/>
  <geom name="behind" type="box" pos="3 0 1" size="0.2 0.2 0.2"/>
  <geom name="beside" type="box" pos="3 3 1" size="0.2 0.2 0.2"/>
  <geom name="across" type="box" pos="2.5 2.6 1" size="0.2 0.3 0.2"/>
  <geom name="front" type="box" pos="1.9 0 1" size="0.05 0.2 0.2"/>
  <geom name="back" type="box" pos="2.1 0 1" size="0.05 0.2 0.2"/>
  <geom name="glass" type="box" pos="6 0 1" size="0.05 2 1.25" rgba="1 1 1 0.5"/>
  <geom name="far" type="sphere" pos="7 0 1" size="0.2"/>
</worldbody></mujoco>"""


@pytest.fixture(scope="module")
def world():
    model = mujoco.MjModel.from_xml_string(MJCF)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return model, data


def _hidden(world, eye, occluders=("wall", "glass")):
    model, data = world
    walls = np.array([model.geom(n).id for n in occluders])
    targets = occlusion.target_geoms(model, walls)
    boxes = occlusion.corners(model, data, targets)
    hidden = occlusion.shadowed(model, data, np.array(eye, float), walls, targets, boxes)
    return {model.geom(int(g)).name for g in hidden}


def test_only_what_lies_wholly_behind_one_wall_is_hidden(world):
    # across: partly past the wall's end (seen from the eye); front: on the eye's side.
    assert _hidden(world, (0, 0, 1.5), ("wall",)) == {"behind", "back", "glass", "far"}


def test_nothing_is_hidden_from_in_or_at_the_wall(world):
    assert _hidden(world, (2.0, 0, 1.0), ("wall",)) == set()  # inside the wall
    assert _hidden(world, (1.9, 0, 1.0), ("wall",)) == set()  # 5 cm from it
    assert _hidden(world, (4, 0, 1.0), ("wall",)) == {"front"}  # from the other side


def test_only_static_opaque_boxes_of_wall_classes_occlude(world):
    model, _ = world
    classes = ["background", "wall", "window", "apple"]
    geom_class = np.array([1, 3, 3, 3, 3, 3, 1, 3])  # the glass is of class wall too
    found = occlusion.occluder_geoms(model, geom_class, classes)
    assert [model.geom(int(g)).name for g in found] == ["wall"]  # the glass lets light in


def test_leaving_out_hidden_geoms_changes_no_pixel(gl, monkeypatch):
    """Frames of an animation in scene1, drawn with walls' shadows and moving geoms
    outside the view left out and with every geom given to MuJoCo: the same colour,
    ids and depth."""
    import homesim
    from homesim.render import animate
    from homesim.render.recorder import SceneState
    from homesim.render.renderer import Renderer

    run = homesim.run_program("[Walk] <television> (1)\n[SwitchOn] <television> (1)",
                              "scene1", trace=True)
    a = animate(run, width=32, height=24, fps=2, seed=1)
    state = SceneState(a.scene, a.timeline, aim_cameras=False)
    with Renderer(a.scene, 32, 24) as lean:
        frames = [(i, c) for i in range(0, len(a), 3) for c in range(0, a.scene.model.ncam, 5)]
        culled = []
        for i, cam in frames:
            d = state.apply(i)
            culled.append((lean.rgb(d, cam), *lean.ids_depth(d, cam)))
        assert lean._shadowed and any(len(h) for h in lean._shadowed.values())
    monkeypatch.setattr(Renderer, "_view_groups",
                        lambda self, data, cam: self._groups.get(cam, self._groups[-1]))
    with Renderer(a.scene, 32, 24) as full:
        for (i, cam), (rgb, ids, depth) in zip(frames, culled, strict=True):
            d = state.apply(i)
            np.testing.assert_array_equal(full.rgb(d, cam), rgb)
            ids_full, depth_full = full.ids_depth(d, cam)
            np.testing.assert_array_equal(ids_full, ids)
            np.testing.assert_array_equal(depth_full, depth)
