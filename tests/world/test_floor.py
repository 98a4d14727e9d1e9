"""The floor model: free floor per room, doorways joining rooms, pockets left out."""

from __future__ import annotations

import pytest

from homesim.world.floor import AGENT_SIZE, FloorModel, doorways
from homesim.world.graph import EnvironmentGraph
from homesim.world.standing import FloorPlan


def _box(x0, z0, x1, z1, y0=0.0, y1=1.0):
    return {"center": [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2],
            "size": [x1 - x0, y1 - y0, z1 - z0]}


def two_rooms(door: bool = True) -> EnvironmentGraph:
    """Rooms 1 (x 0-4) and 2 (x 4-8), z 0-4, a door at x = 4, z 1.5-2.5. In room 1, a
    shelf (x 0-1.5, z 1.0-1.3) and a cabinet (x 1.2-1.5, z 0-1.3) wall off the corner
    x < 1.2, z < 1.0: a pocket with free floor that cannot be walked into."""
    nodes = [
        {"id": 1, "class_name": "livingroom", "category": "Rooms",
         "bounding_box": _box(0, 0, 4, 4, 0, 2.5)},
        {"id": 2, "class_name": "kitchen", "category": "Rooms",
         "bounding_box": _box(4, 0, 8, 4, 0, 2.5)},
        {"id": 3, "class_name": "floor", "category": "Floors",
         "bounding_box": _box(0.1, 0.1, 3.9, 3.9, 0, 0)},
        {"id": 4, "class_name": "floor", "category": "Floors",
         "bounding_box": _box(4.1, 0.1, 7.9, 3.9, 0, 0)},
        {"id": 10, "class_name": "bookshelf", "category": "Furniture",
         "bounding_box": _box(0.1, 1.0, 1.5, 1.3)},
        {"id": 11, "class_name": "cabinet", "category": "Furniture",
         "bounding_box": _box(1.2, 0.1, 1.5, 1.3)},
        {"id": 12, "class_name": "rug", "category": "Decor",
         "bounding_box": _box(2.0, 2.0, 3.5, 3.5, 0.0, 0.01)},
    ]
    if door:
        nodes.append({"id": 20, "class_name": "door", "category": "Doors",
                      "bounding_box": _box(3.9, 1.55, 4.1, 2.45, 0, 2.1)})
    edges = [{"from_id": n["id"], "relation_type": "INSIDE", "to_id": 1 if n["id"] != 4 else 2}
             for n in nodes if n["id"] in (3, 4, 10, 11, 12, 20)]
    return EnvironmentGraph.from_dict({"nodes": nodes, "edges": edges})


def test_doorway_joins_rooms_and_pockets_are_left_out():
    model = FloorModel(two_rooms())
    assert model.rooms_on_main() == {1, 2}
    assert model.reachable(3.0, 3.0) and model.reachable(6.0, 2.0)
    assert model.reachable(4.0, 2.0)  # in the doorway
    assert not model.reachable(4.0, 3.5)  # through the wall beside it
    assert not model.reachable(0.6, 0.5)  # the pocket: free floor, walled off
    assert not model.reachable(0.8, 1.15)  # on the shelf


def test_without_a_door_one_room_is_cut_off():
    model = FloorModel(two_rooms(door=False))
    assert len(model.rooms_on_main()) == 1


def test_free_cells_follow_the_agent_square():
    model = FloorModel(two_rooms())
    half = AGENT_SIZE / 2
    assert model.reachable(0.1 + half + 0.05, 3.0)  # the square fits beside the wall
    i, j = model.index(0.1 + half - 0.1, 3.0)
    assert not model.walkable(i, j)  # the square would stick out of the floor
    assert model.reachable(2.7, 2.7)  # rugs do not block


def test_standing_spots_avoid_pockets():
    home = two_rooms()
    plan = FloorPlan(home)
    assert plan.is_free(1, 0.6, 0.5) and not plan.reachable(0.6, 0.5)
    for obj in (10, 11):
        spot = plan.spot_near(obj)
        assert spot is not None and plan.reachable(*spot)
        assert not (spot[0] < 1.2 and spot[1] < 1.0), spot


def test_doorways_take_frames_and_doors_without_frames():
    assert doorways(two_rooms()) == [pytest.approx((3.9, 1.55, 4.1, 2.45))]
    assert doorways(two_rooms(door=False)) == []
