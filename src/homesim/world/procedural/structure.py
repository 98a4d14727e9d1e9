"""The shell of a home from its plan: room boxes, walls with door gaps, doors, windows,
floor and ceiling tiles."""

from __future__ import annotations

import math

from homesim.world.doors import door_swing
from homesim.world.graph import BoundingBox
from homesim.world.procedural.geometry import Rect
from homesim.world.procedural.parts import Part, box3
from homesim.world.procedural.plan import (
    DOOR_HEIGHT,
    HEIGHT,
    WALL,
    Opening,
    Plan,
)

TILE = 2.5
"""Largest side (m) of a floor or ceiling tile, as in the built-in homes."""


def side_box(rect: Rect, side: str, lo: float, hi: float, depth: float, y0: float,
             y1: float) -> tuple[float, float, float, float, float, float]:
    """The box of thickness `depth` against side `side` of `rect`, spanning [lo, hi]."""
    x0, z0, x1, z1 = rect
    if side == "x0":
        return box3(x0, y0, lo, x0 + depth, y1, hi)
    if side == "x1":
        return box3(x1 - depth, y0, lo, x1, y1, hi)
    if side == "z0":
        return box3(lo, y0, z0, hi, y1, z0 + depth)
    return box3(lo, y0, z1 - depth, hi, y1, z1)


def side_span(rect: Rect, side: str) -> tuple[float, float]:
    return (rect[1], rect[3]) if side[0] == "x" else (rect[0], rect[2])


INWARD = {"x0": (1.0, 0.0), "x1": (-1.0, 0.0), "z0": (0.0, 1.0), "z1": (0.0, -1.0)}
"""The direction into the room from each side."""


def build_shell(plan: Plan) -> list[Part]:
    """Rooms (parts 0..n-1, in plan order), then walls, doors, windows, floors, ceilings."""
    parts = [Part(r.kind, i, box3(r.rect[0], 0.0, r.rect[1], r.rect[2], HEIGHT, r.rect[3]),
                  kind="room") for i, r in enumerate(plan.rooms)]
    for i, room in enumerate(plan.rooms):
        for side in ("x0", "x1", "z0", "z1"):
            gaps = sorted((d.lo, d.hi) for d in plan.doors if d.room == i and d.side == side)
            lo, hi = side_span(room.rect, side)
            for a, b in _segments(lo, hi, gaps):
                parts.append(Part("wall", i, side_box(room.rect, side, a, b, WALL, 0.0,
                                                      HEIGHT), normal=INWARD[side],
                                  kind="structure"))
    for d in plan.doors:
        if d.other is not None and d.room < d.other:
            jamb, door = _door(plan, d)
            parts += [jamb, door]
            # A floor tile across the threshold: walking (and the renderer's grid) needs
            # floor under the doorway, between the two rooms' tiles.
            # It reaches 0.3 m into both rooms so it overlaps their tiles on any grid.
            db = jamb.box
            dx, dz = (0.3, 0.0) if d.side[0] == "x" else (0.0, 0.3)
            parts.append(Part("floor", d.room, box3(db[0] - dx, -0.001, db[2] - dz,
                                                    db[3] + dx, 0.0, db[5] + dz),
                              kind="structure"))
    for w in plan.windows:
        box = side_box(plan.rooms[w.room].rect, w.side, w.lo, w.hi, WALL, 0.9, 2.0)
        parts.append(Part("window", w.room, box, normal=INWARD[w.side], kind="structure"))
    for i, room in enumerate(plan.rooms):
        for tile in _tiles(room.interior):
            parts.append(Part("floor", i, box3(tile[0], -0.001, tile[1], tile[2], 0.0,
                                               tile[3]), kind="structure"))
            parts.append(Part("ceiling", i, box3(tile[0], HEIGHT, tile[1], tile[2],
                                                 HEIGHT + 0.001, tile[3]), kind="structure"))
    return parts


def _door(plan: Plan, d: Opening) -> tuple[Part, Part]:
    """The door frame of an opening (across both rooms' walls) and its door: OPEN, BETWEEN
    the two rooms, its box the box of its swing into room `d.room`
    (`homesim.world.doors.door_swing`)."""
    rect = plan.rooms[d.room].rect
    box = side_box(rect, d.side, d.lo, d.hi, WALL, 0.0, DOOR_HEIGHT)
    # The door leaf spans both rooms' walls: extend the box across the boundary.
    axis = 0 if d.side[0] == "x" else 2
    lo, hi = list(box[:3]), list(box[3:])
    if d.side.endswith("1"):
        hi[axis] = round(hi[axis] + WALL, 4)
    else:
        lo[axis] = round(lo[axis] - WALL, 4)
    assert d.other is not None
    frame = (lo[0], lo[1], lo[2], hi[0], hi[1], hi[2])
    jamb = Part("doorjamb", d.room, frame, normal=INWARD[d.side], kind="structure")
    inner = plan.rooms[d.room].interior
    swing = door_swing(_bbox(frame), ((inner[0] + inner[2]) / 2, (inner[1] + inner[3]) / 2))
    (cx, cy, cz), (sx, sy, sz) = swing.center, swing.size
    box = (round(cx - sx / 2, 4), round(cy - sy / 2, 4), round(cz - sz / 2, 4),
           round(cx + sx / 2, 4), round(cy + sy / 2, 4), round(cz + sz / 2, 4))
    return jamb, Part("door", d.room, box, normal=INWARD[d.side], states=("OPEN",),
                      kind="structure", between=(d.room, d.other))


def _bbox(b: tuple[float, ...]) -> BoundingBox:
    return BoundingBox(((b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2),
                       (b[3] - b[0], b[4] - b[1], b[5] - b[2]))


def _segments(lo: float, hi: float, gaps: list[tuple[float, float]]
              ) -> list[tuple[float, float]]:
    out, start = [], lo
    for a, b in gaps:
        if a - start > 1e-6:
            out.append((start, a))
        start = b
    if hi - start > 1e-6:
        out.append((start, hi))
    return out


def _tiles(r: Rect) -> list[Rect]:
    nx = math.ceil((r[2] - r[0]) / TILE - 1e-9)
    nz = math.ceil((r[3] - r[1]) / TILE - 1e-9)
    w, d = (r[2] - r[0]) / nx, (r[3] - r[1]) / nz
    return [(r[0] + i * w, r[1] + j * d, r[0] + (i + 1) * w, r[1] + (j + 1) * d)
            for i in range(nx) for j in range(nz)]


def door_rects(plan: Plan, room: int) -> list[Rect]:
    """The doorways of a room as thin rectangles at the inner face of its walls."""
    out = []
    inner = plan.rooms[room].interior
    for d in plan.doors:
        if d.room == room:
            b = side_box(inner, d.side, d.lo, d.hi, 0.01, 0.0, 0.0)
            out.append((b[0], b[2], b[3], b[5]))
    return out
