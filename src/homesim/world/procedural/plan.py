"""Floor plans: which rooms, their rectangles, the doors between them and the windows.

Rooms are laid out in rows along x; rows are stacked along z. Each room keeps the floor
area drawn for its kind (sizes fitted from the built-in apartments) and takes its row's
depth, so rooms in a row share walls and rows share walls where they overlap. Doors
follow a random spanning tree of the rooms that share at least `MIN_SHARED` m of wall
(so every room can be reached), plus a few extra doors.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from homesim.errors import GraphError
from homesim.world.procedural.geometry import Rect, grow
from homesim.world.procedural.stats import KINDS, kind_sizes

WALL = 0.1
"""Wall thickness (m), inside each room's rectangle."""
HEIGHT = 2.5
"""Floor-to-ceiling height (m)."""
DOOR_WIDTH = 0.9
DOOR_HEIGHT = 2.1
MIN_SHARED = DOOR_WIDTH + 0.6
CORE = ("living_room", "kitchen", "bedroom", "bathroom")
"""Kinds every generated home has unless --rooms says otherwise (the kinds real programs
walk to: home_office and dining_room resolve to the living room and kitchen)."""
OPTIONAL = ("dining_room", "home_office", "kids_bedroom", "entrance_hall", "bedroom",
            "bathroom")


@dataclass(frozen=True)
class RoomPlan:
    kind: str
    rect: Rect
    """Outer rectangle, walls included."""

    @property
    def interior(self) -> Rect:
        return grow(self.rect, -WALL)


@dataclass(frozen=True)
class Opening:
    """A door or window in the wall of room `room` on `side` (``x0``, ``x1``, ``z0``,
    ``z1``: the side where x or z is smallest or largest), spanning [lo, hi] along it."""

    room: int
    side: str
    lo: float
    hi: float
    other: int | None = None
    """For a door: the room on the other side."""


@dataclass(frozen=True)
class Plan:
    rooms: list[RoomPlan]
    doors: list[Opening]
    windows: list[Opening]


def room_kinds(rng: random.Random, rooms: list[str] | None) -> list[str]:
    """The kinds of the rooms of a home: given, or the core kinds plus 0-4 optional ones."""
    if rooms:
        unknown = [r for r in rooms if r not in KINDS]
        if unknown:
            raise GraphError(f"unknown room kind {unknown[0]!r}; choose from "
                             f"{', '.join(KINDS)}")
        if len(rooms) > 12:
            raise GraphError(f"{len(rooms)} rooms asked for; a generated home has at most 12")
        return list(rooms)
    extra = rng.sample(OPTIONAL, rng.randint(0, 4))
    return list(CORE) + extra


def _size(rng: random.Random, kind: str) -> tuple[float, float]:
    w, d = rng.choice(kind_sizes(kind))
    f = rng.uniform(0.85, 1.15)
    return max(2.6, w * f), max(2.6, d * f)


def make_plan(rng: random.Random, kinds: list[str]) -> Plan:
    """Lay out rooms of these kinds, with doors and windows."""
    order = list(kinds)
    rng.shuffle(order)
    n_rows = 1 if len(order) <= 2 else 2 if len(order) <= 6 else 3
    rows: list[list[tuple[str, float]]] = [[] for _ in range(n_rows)]
    depths: list[list[float]] = [[] for _ in range(n_rows)]
    for i, kind in enumerate(order):
        w, d = _size(rng, kind)
        if rng.random() < 0.5:
            w, d = d, w
        rows[i % n_rows].append((kind, w * d))
        depths[i % n_rows].append(d)
    rooms: list[RoomPlan] = []
    z = 0.0
    for row, ds in zip(rows, depths, strict=True):
        depth = round(sum(ds) / len(ds), 2)
        x = 0.0
        for kind, area in row:
            width = round(max(2.6, area / depth), 2)
            rooms.append(RoomPlan(kind, (x, z, round(x + width, 2), round(z + depth, 2))))
            x = round(x + width, 2)
        z = round(z + depth, 2)
    doors = _doors(rng, rooms)
    return Plan(rooms, doors, _windows(rng, rooms, doors))


def _shared(a: Rect, b: Rect) -> tuple[str, float, float] | None:
    """The side of `a` it shares with `b` and the shared span, if long enough."""
    for side, axis_a, axis_b, lo_i, hi_i in (("x1", a[2], b[0], 1, 3), ("x0", a[0], b[2], 1, 3),
                                             ("z1", a[3], b[1], 0, 2), ("z0", a[1], b[3], 0, 2)):
        if abs(axis_a - axis_b) < 1e-6:
            lo, hi = max(a[lo_i], b[lo_i]), min(a[hi_i], b[hi_i])
            if hi - lo >= MIN_SHARED:
                return side, lo, hi
    return None


_OPPOSITE = {"x0": "x1", "x1": "x0", "z0": "z1", "z1": "z0"}


def _doors(rng: random.Random, rooms: list[RoomPlan]) -> list[Opening]:
    pairs = [(i, j) for i in range(len(rooms)) for j in range(i + 1, len(rooms))
             if _shared(rooms[i].rect, rooms[j].rect)]
    rng.shuffle(pairs)
    group = list(range(len(rooms)))

    def find(i: int) -> int:
        while group[i] != i:
            i = group[i]
        return i

    chosen = []
    for i, j in pairs:
        if find(i) != find(j):
            group[find(i)] = find(j)
            chosen.append((i, j))
        elif rng.random() < 0.2 and "bathroom" not in (rooms[i].kind, rooms[j].kind):
            chosen.append((i, j))
    if len({find(i) for i in range(len(rooms))}) > 1:
        raise GraphError("floor plan: rooms do not all share walls")  # rows always do
    doors = []
    for i, j in sorted(chosen):
        shared = _shared(rooms[i].rect, rooms[j].rect)
        assert shared is not None
        side, lo, hi = shared
        mid = rng.uniform(lo + DOOR_WIDTH / 2 + 0.3, hi - DOOR_WIDTH / 2 - 0.3)
        a, b = round(mid - DOOR_WIDTH / 2, 3), round(mid + DOOR_WIDTH / 2, 3)
        doors.append(Opening(i, side, a, b, j))
        doors.append(Opening(j, _OPPOSITE[side], a, b, i))
    return doors


def _windows(rng: random.Random, rooms: list[RoomPlan], doors: list[Opening]
             ) -> list[Opening]:
    """One window per room on a side that borders no other room, where there is one."""
    windows = []
    for i, room in enumerate(rooms):
        outside = []
        for side in ("x0", "x1", "z0", "z1"):
            lo_hi = (room.rect[1], room.rect[3]) if side[0] == "x" else (room.rect[0],
                                                                        room.rect[2])
            if any(_touches(room.rect, other.rect, side)
                   for k, other in enumerate(rooms) if k != i):
                continue
            if lo_hi[1] - lo_hi[0] > 2.0:
                outside.append((side, *lo_hi))
        if outside and (room.kind != "bathroom" or rng.random() < 0.6):
            side, lo, hi = rng.choice(outside)
            width = min(1.2, (hi - lo) - 1.0)
            mid = rng.uniform(lo + width / 2 + 0.4, hi - width / 2 - 0.4)
            windows.append(Opening(i, side, round(mid - width / 2, 3),
                                   round(mid + width / 2, 3)))
    return windows


def _touches(a: Rect, b: Rect, side: str) -> bool:
    """Whether `b` borders side `side` of `a` anywhere."""
    k = {"x0": (0, 2), "x1": (2, 0), "z0": (1, 3), "z1": (3, 1)}[side]
    if abs(a[k[0]] - b[k[1]]) > 1e-6:
        return False
    lo_i, hi_i = (1, 3) if side[0] == "x" else (0, 2)
    return min(a[hi_i], b[hi_i]) - max(a[lo_i], b[lo_i]) > 1e-6


def floor_area(plan: Plan) -> float:
    return math.fsum((r.rect[2] - r.rect[0]) * (r.rect[3] - r.rect[1]) for r in plan.rooms)
