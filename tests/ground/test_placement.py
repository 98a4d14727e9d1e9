import random

from homesim.ground.placement import overlaps_xz, overlaps_y, place_box
from homesim.world.graph import BoundingBox

TABLE = BoundingBox((0.0, 0.4, 0.0), (1.0, 0.8, 0.6))
CABINET = BoundingBox((2.0, 0.5, 0.0), (0.6, 1.0, 0.5))


def test_on_rests_on_the_top_face_inside_the_footprint():
    box = place_box((0.2, 0.1, 0.2), TABLE, "ON", [], random.Random(0))
    assert box is not None
    assert abs(box.center[1] - box.size[1] / 2 - 0.8) < 1e-9
    assert abs(box.center[0]) <= 0.4 and abs(box.center[2]) <= 0.2


def test_inside_sits_within_the_container():
    box = place_box((0.2, 0.3, 0.2), CABINET, "INSIDE", [], random.Random(0))
    assert box is not None
    assert box.center[1] - box.size[1] / 2 >= 0.0
    assert box.center[1] + box.size[1] / 2 <= 1.0
    assert place_box((0.2, 1.2, 0.2), CABINET, "INSIDE", [], random.Random(0)) is None


def test_too_big_does_not_fit():
    assert place_box((1.2, 0.1, 0.1), TABLE, "ON", [], random.Random(0)) is None


def test_avoids_objects_already_there():
    rng = random.Random(1)
    others = []
    for _ in range(4):
        box = place_box((0.2, 0.1, 0.2), TABLE, "ON", others, rng)
        assert box is not None
        assert not any(overlaps_xz(box, o) and overlaps_y(box, o) for o in others)
        others.append(box)


def test_full_surface_gives_none():
    full = [BoundingBox((0.0, 0.85, 0.0), (1.0, 0.1, 0.6))]
    assert place_box((0.2, 0.1, 0.2), TABLE, "ON", full, random.Random(0)) is None


def test_same_rng_same_box():
    others = [BoundingBox((0.0, 0.85, 0.0), (0.3, 0.1, 0.3))]
    a = place_box((0.2, 0.1, 0.2), TABLE, "ON", others, random.Random(5))
    b = place_box((0.2, 0.1, 0.2), TABLE, "ON", others, random.Random(5))
    assert a == b
