"""Geometric placement: a box for a new object on or inside a destination's box.

Boxes are axis-aligned, in metres, in the Unity frame (y up). An object put ON a
destination rests on the top face of the destination's box; one put INSIDE sits on the
floor of the destination's box. In both cases its footprint lies within the destination's
and does not overlap the boxes of the other objects already there.

>>> import random
>>> table = BoundingBox((0.0, 0.4, 0.0), (1.0, 0.8, 1.0))
>>> box = place_box((0.1, 0.2, 0.1), table, "ON", [], random.Random(0))
>>> round(box.center[1], 3), box.size
(0.9, (0.1, 0.2, 0.1))
>>> place_box((2.0, 0.2, 0.1), table, "ON", [], random.Random(0)) is None
True
"""

from __future__ import annotations

import math
import random
from collections.abc import Sequence

from homesim.world.graph import BoundingBox
from homesim.world.vocab import ON

Size = tuple[float, float, float]

_GAP = 0.01
"""Clearance (m) kept between a new object and its neighbours and the destination's edge."""
_TRIES = 48
"""Random footprint positions tried before giving up on a destination."""


def overlaps_xz(a: BoundingBox, b: BoundingBox, gap: float = 0.0) -> bool:
    """Whether the footprints (x, z) of two boxes overlap (closer than `gap`)."""
    return (abs(a.center[0] - b.center[0]) * 2 < a.size[0] + b.size[0] + 2 * gap
            and abs(a.center[2] - b.center[2]) * 2 < a.size[2] + b.size[2] + 2 * gap)


def overlaps_y(a: BoundingBox, b: BoundingBox) -> bool:
    """Whether the vertical extents of two boxes overlap."""
    return abs(a.center[1] - b.center[1]) * 2 < a.size[1] + b.size[1]


def place_box(size: Size, dest: BoundingBox, relation: str, others: Sequence[BoundingBox],
              rng: random.Random) -> BoundingBox | None:
    """A box of `size` ON or INSIDE `dest`, clear of `others`; None when it does not fit."""
    sx, sy, sz = size
    dx, dy, dz = dest.size
    room_x, room_z = dx - sx - 2 * _GAP, dz - sz - 2 * _GAP
    if room_x < 0 or room_z < 0:
        return None
    if relation == ON:
        y = dest.center[1] + dy / 2 + sy / 2
    else:
        if sy > dy - 2 * _GAP:
            return None
        y = dest.center[1] - dy / 2 + _GAP + sy / 2
    # The centre first (where a person would put it), then random spots.
    spots = [(0.0, 0.0)] + [(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5))
                            for _ in range(_TRIES - 1)]
    for fx, fz in spots:
        box = BoundingBox((dest.center[0] + fx * room_x, y, dest.center[2] + fz * room_z),
                          (sx, sy, sz))
        if not all(map(math.isfinite, box.center)):
            return None  # a destination so large that the arithmetic overflowed
        if not any(overlaps_y(box, o) and overlaps_xz(box, o, _GAP) for o in others):
            return box
    return None
