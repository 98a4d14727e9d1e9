"""Doors in their frames: the closed leaf of a door frame and the box a door takes.

A door frame (``doorjamb``) spans a doorway: two posts and the opening between them. Its
door's leaf, closed, fills the opening (`door_leaf`); open, it stands at a right angle to
the wall on one side. A door's box in a home is the box of its swing (`door_swing`): the
closed leaf and the open one, so whatever angle the door is drawn at, it lies in its box
(the renderer hinges the leaf so it does, `homesim.render.layout`). Unity frame: metres,
y up; boxes are `BoundingBox` (centre, size).
"""

from __future__ import annotations

from homesim.world.graph import BoundingBox

POST = 0.06
"""Metres: each post of a door frame is this wide; the leaf fills the space between."""
LEAF_THICKNESS = 0.025
HEAD = 0.02
"""Metres between the top of the leaf and the top of the frame's opening."""


def door_leaf(jamb: BoundingBox) -> BoundingBox:
    """The closed leaf of a door frame: between its posts, as tall as the opening, in the
    middle of the wall."""
    (cx, cy, cz), (sx, sy, sz) = jamb.center, jamb.size
    height = sy - 2 * HEAD
    bottom = cy - sy / 2
    if sx >= sz:  # the frame runs along x
        return BoundingBox((cx, bottom + height / 2, cz), (sx - 2 * POST, height, LEAF_THICKNESS))
    return BoundingBox((cx, bottom + height / 2, cz), (LEAF_THICKNESS, height, sz - 2 * POST))


def door_swing(jamb: BoundingBox, toward: tuple[float, float]) -> BoundingBox:
    """The box of a door's swing: its closed leaf and, at a right angle to it on the side
    of the floor point `toward` (x, z), the leaf open into that room."""
    leaf = door_leaf(jamb)
    (cx, cy, cz), (sx, sy, sz) = leaf.center, leaf.size
    t = LEAF_THICKNESS
    if sx >= sz:  # along x: it opens toward +z or -z (the hinge's leaf edge: t/2 wider)
        width = sx
        lo, hi = (cz - t / 2, cz + width) if toward[1] >= cz else (cz - width, cz + t / 2)
        return BoundingBox((cx, cy, (lo + hi) / 2), (sx + t, sy, hi - lo))
    width = sz
    lo, hi = (cx - t / 2, cx + width) if toward[0] >= cx else (cx - width, cx + t / 2)
    return BoundingBox(((lo + hi) / 2, cy, cz), (hi - lo, sy, sz + t))


__all__ = ["LEAF_THICKNESS", "POST", "door_leaf", "door_swing"]
