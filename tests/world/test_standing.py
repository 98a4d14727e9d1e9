import json
import math
import random

import pytest

from homesim.world import load_home
from homesim.world.standing import AGENT_SIZE, FloorPlan, has_geometry


def test_has_geometry():
    assert has_geometry(load_home("scene1"))
    assert not has_geometry(load_home("scene1_trimmed"))


def test_spot_near_is_free_floor_next_to_the_object():
    home = load_home("scene1")
    plan = FloorPlan(home)
    for cls in ("tv", "sofa", "fridge", "computer", "bed", "toilet"):
        for node in home.nodes_of_class(cls):
            spot = plan.spot_near(node.id)
            assert spot is not None, node.label()
            room = home.room_of(node.id)
            assert plan.is_free(room, *spot)
            box = node.bounding_box
            # outside the object's footprint, and within reach of it
            dx = max(0.0, abs(spot[0] - box.center[0]) - box.size[0] / 2)
            dz = max(0.0, abs(spot[1] - box.center[2]) - box.size[2] / 2)
            assert math.hypot(dx, dz) >= AGENT_SIZE / 2 - 1e-9
            assert math.hypot(dx, dz) <= 1.6


def test_obstacles_and_walls_are_not_free():
    home = load_home("scene1")
    plan = FloorPlan(home)
    fridge = home.nodes_of_class("fridge")[0]
    room = home.room_of(fridge.id)
    assert not plan.is_free(room, fridge.bounding_box.center[0], fridge.bounding_box.center[2])
    far = home.node(room).bounding_box
    assert not plan.is_free(room, far.center[0] + far.size[0], far.center[2])


def test_free_floor_finds_room_for_a_footprint():
    import random

    home = load_home("scene1")
    plan = FloorPlan(home)
    room = home.room_ids and sorted(home.room_ids)[0]
    spot = plan.free_floor(room, 0.5, 0.5, random.Random(0))
    assert spot is not None and plan.is_free(room, *spot, 0.5, 0.5)


@pytest.mark.parametrize("cls", ["tv", "kitchen", "floor"])
def test_huge_finite_boxes_ground_or_fail_clearly_never_overflow(cls, monkeypatch):
    # Squares of 1e308 coordinates overflowed (issue 12). Loading now refuses them
    # (MAX_COORD); grounding stays robust for graphs built around that check.
    from homesim.world import graph as graph_module

    monkeypatch.setattr(graph_module, "MAX_COORD", math.inf)
    monkeypatch.setattr(graph_module, "MAX_SIZE", math.inf)
    from homesim.errors import GroundingError
    from homesim.ground import prepare_and_ground
    from homesim.program import parse_program
    from homesim.world.graph import EnvironmentGraph

    d = load_home("scene1").to_dict()
    for node in d["nodes"]:
        if node["class_name"] == cls:
            node["bounding_box"] = {"center": [1e308, 1.0, 1e308], "size": [1e308] * 3}
    home = EnvironmentGraph.from_dict(d)
    for text in ("[Walk] <television> (1)\n[SwitchOn] <television> (1)\n[Walk] <couch> (1)",
                 "[Walk] <kitchen> (1)\n[Walk] <cup> (1)\n[Grab] <cup> (1)"):
        try:
            prepared, grounding = prepare_and_ground(parse_program(text), home)
        except GroundingError:
            continue
        assert all(math.isfinite(c) for s in grounding.standing.values() for c in s)
        json.dumps(prepared.graph.to_dict(), allow_nan=False)  # no inf box was added


def test_square_distance_is_inf_instead_of_overflow():
    from homesim.world.standing import square_distance

    assert square_distance((1.0, 5.0, 2.0), (4.0, 0.0, 6.0)) == 25.0
    assert square_distance((1e308, 0.0, 0.0), (-1e308, 0.0, 0.0)) == float("inf")


def test_what_preparation_puts_on_the_floor_keeps_clear_of_doorways():
    """Added things stand `_DOOR_CLEAR` from every door (a television prepared before a
    door cut a generated room's floor in two): near a door, the nearest spot is farther."""
    from homesim.world.graph import BoundingBox
    from homesim.world.standing import _DOOR_CLEAR

    home = load_home("scene1")
    plan = FloorPlan(home)
    door = next(n for n in home.nodes_of_class("door") if n.bounding_box is not None)
    room = next(r for r in home.room_ids if door.id in home.sources(r, "INSIDE")
                or r in home.targets(door.id, "BETWEEN"))
    probe = BoundingBox(door.bounding_box.center, (0.1, 0.1, 0.1))
    spot = plan.free_floor_near(room, probe, 0.4, 0.4)
    assert spot is not None
    for d in plan._door_boxes:
        gap = max(abs(spot[0] - d.center[0]) - (0.4 + d.size[0]) / 2,
                  abs(spot[1] - d.center[2]) - (0.4 + d.size[2]) / 2)
        assert gap >= _DOOR_CLEAR - 1e-9
    spots = [plan.free_floor(room, 0.4, 0.4, random.Random(s)) for s in range(20)]
    assert all(not plan._by_door(*xy, 0.4, 0.4) for xy in spots if xy is not None)
