import io
import re

import numpy as np
from PIL import Image

from homesim.render.agent import agent_shape
from homesim.render.materials import FINE_TEXTURE, TEXTURE_SIZE, Look, planks, tiles
from homesim.render.scene import build_scene
from homesim.world.homes import load_home

ROOMS = {1: "bathroom", 2: "livingroom", 3: "kitchen", 4: "bedroom"}


def test_textures_are_small_seeded_images():
    assert planks(1).shape == (TEXTURE_SIZE, TEXTURE_SIZE, 3)
    np.testing.assert_array_equal(planks(1), planks(1))
    assert not np.array_equal(planks(1), planks(2))
    t = tiles(0)
    assert t.min() < 0.7 < 0.9 < t.max() <= 1.0  # grout lines and tiles


def test_look_is_seeded_and_tiles_wet_rooms():
    a, b = Look(3, ROOMS), Look(3, ROOMS)
    assert a.floor == b.floor and a.wall == b.wall and a.wood == b.wood
    assert a.floor[1][0] == "tiles" and a.floor[3][0] == "tiles"
    looks = {(Look(s, ROOMS).wood, tuple(Look(s, ROOMS).wall.values())) for s in range(8)}
    assert len(looks) > 2  # the seed changes the home's look


def test_every_role_names_a_material_of_the_assets():
    look = Look(0, ROOMS)
    xml, files = look.assets()
    materials = set(re.findall(r'<material name="(\w+)"', "".join(xml)))
    roles = ["body", "front", "accent", "wood", "darkwood", "fabric", "cushion", "metal",
             "chrome", "glass", "glass_dark", "white", "black", "stone", "screen_dark", "paper",
             "leaf", "coffee", "label", "ceiling", "books", "book2", "art1", "floor@1",
             "floor@2", "wall@4", "unknown"]
    for role in roles:
        name, rgba = look.material(role, (0.2, 0.4, 0.6, 1.0))
        assert name in materials, role
        assert all(0.0 <= c <= 1.0 for c in rgba)
    assert look.material("glass", (0, 0, 0, 1))[1][3] < 0.5  # see-through
    for png in files.values():
        assert Image.open(io.BytesIO(png)).size[0] in (TEXTURE_SIZE, FINE_TEXTURE)


def test_ceiling_lamps_drive_their_rooms_light_and_table_lamps_their_own():
    from homesim.render.layout import render_kind

    graph = load_home("scene1")
    scene = build_scene(graph, agent_shape("male1"))
    assert set(scene.room_light) == set(scene.layout.room_floors)
    assert all(lid >= 0 for lid in scene.room_light.values())
    lamps = [p for p in scene.layout.parts if p.lamp]
    own = [p for p in lamps if render_kind(p.class_name) == "lamp"]
    assert own and len(own) < len(lamps)
    for p in lamps:
        room = graph.room_of(p.node_id)
        if p in own:
            assert scene.lamp_light[p.node_id] not in scene.room_light.values()
            assert scene.light_room[scene.lamp_light[p.node_id]] == room
        elif room in scene.room_light:
            assert scene.lamp_light[p.node_id] == scene.room_light[room]
    assert scene.model.ntex >= 9 and scene.model.nlight == len(scene.room_light) + len(own)
    m = scene.model  # each room's light hangs under its ceiling lamps, warm
    assert all(m.light_diffuse[lid][0] > m.light_diffuse[lid][2] for lid in range(m.nlight))


def test_a_camera_draws_with_at_most_eight_lights_its_rooms_first():
    from homesim.render.renderer import MAX_LIGHTS, Renderer

    graph = load_home("gen-4")  # eight rooms
    scene = build_scene(graph, agent_shape("male1"), max_size=(32, 24))
    assert scene.model.nlight > MAX_LIGHTS  # the check below has something to choose
    with Renderer(scene, 32, 24) as r:
        for cam, spec in enumerate(scene.cameras):
            mask = r._light_masks[cam]
            assert mask.sum() == MAX_LIGHTS
            assert mask[scene.room_light[spec.room_id]]
