"""Floor plans: which rooms, their rectangles, the doors between them and the windows.

Each room gets a size drawn from the floors of its kind in the built-in homes (jittered,
its area kept within the kind's range). Rooms are placed one by one against the room
their purpose hangs off (`PARENTS`: a hall or the living room is the hub; the kitchen
goes beside the dining room or the living room; bedrooms, the office and bathrooms open
onto the hub), flush with one of its sides and overlapping it enough for a door, the
plan kept compact. Each room's door opens onto that room, so the doors form a tree by
purpose; a few more join the day rooms (kitchen, dining and living room) where they
share a wall. A bathroom has one door: it is never the way between two other rooms.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from homesim.errors import GraphError
from homesim.world.procedural.geometry import Rect, grow
from homesim.world.procedural.stats import KINDS, kind_area, kind_sizes

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


PARENTS: dict[str, tuple[str, ...]] = {
    "entrance_hall": ("living_room",),
    "living_room": ("entrance_hall",),
    "dining_room": ("living_room", "entrance_hall", "kitchen"),
    "kitchen": ("dining_room", "living_room", "entrance_hall"),
    "bedroom": ("entrance_hall", "living_room"),
    "kids_bedroom": ("entrance_hall", "living_room"),
    "home_office": ("entrance_hall", "living_room"),
    "bathroom": ("entrance_hall", "living_room"),
}
"""Room kind -> the kinds whose room its door opens onto, preferred first (a second
bathroom may open onto a bedroom instead: en suite)."""
FALLBACK: dict[str, tuple[str, ...]] = {
    "bathroom": ("bedroom", "kids_bedroom", "dining_room", "home_office", "kitchen"),
    "bedroom": ("dining_room", "home_office", "kitchen", "bedroom", "kids_bedroom"),
    "kids_bedroom": ("dining_room", "home_office", "kitchen", "bedroom", "kids_bedroom"),
    "home_office": ("dining_room", "kitchen", "bedroom", "kids_bedroom"),
}
"""Where a room's door opens when no room of its `PARENTS` kinds has a free wall (day
rooms: any other day room first, then the rest)."""
DAY_ROOMS = frozenset({"living_room", "kitchen", "dining_room", "entrance_hall"})
"""Rooms that may also share a door with a neighbour of this set (beside their tree door)."""
HUBS = frozenset({"living_room", "entrance_hall"})
PLACE_ORDER = ("entrance_hall", "living_room", "dining_room", "kitchen", "bedroom",
               "kids_bedroom", "home_office", "bathroom")
MIN_SIDE = 2.6
"""Metres: no room is narrower than this."""
DOOR_MARGIN = 0.3
"""Metres of wall kept on either side of a door."""


def _size(rng: random.Random, kind: str) -> tuple[float, float]:
    """A room's outer width and depth: a floor of its kind in the built-in homes, a little
    jittered, its interior area kept within the kind's range."""
    w, d = rng.choice(kind_sizes(kind))
    lo_f = 0.95 if kind in HUBS else 0.8  # a hub has many doors: it keeps its size
    w, d = max(MIN_SIDE, w * rng.uniform(lo_f, 1.1)), max(MIN_SIDE, d * rng.uniform(lo_f, 1.1))
    lo, hi = kind_area(kind)
    area = (w - 2 * WALL) * (d - 2 * WALL)
    if not lo <= area <= hi:
        f = math.sqrt(min(max(area, lo * 1.02), hi * 0.98) / area)
        w, d = max(MIN_SIDE, w * f), max(MIN_SIDE, d * f)
    return round(w, 2), round(d, 2)


def make_plan(rng: random.Random, kinds: list[str]) -> Plan:
    """Lay out rooms of these kinds, with doors and windows."""
    order = sorted(kinds, key=lambda k: (PLACE_ORDER.index(k) if k in PLACE_ORDER
                                         else len(PLACE_ORDER)))
    rooms: list[RoomPlan] = []
    tree: list[tuple[int, int]] = []  # (room, the room its door opens onto)
    for kind in order:
        w, d = _size(rng, kind)
        if rng.random() < 0.5:
            w, d = d, w
        if not rooms:
            rooms.append(RoomPlan(kind, (0.0, 0.0, w, d)))
            continue
        parent, rect = _attach(rng, rooms, kind, w, d)
        rooms.append(RoomPlan(kind, rect))
        tree.append((len(rooms) - 1, parent))
    doors = _doors(rng, rooms, tree)
    return Plan(rooms, doors, _windows(rng, rooms, doors))


def _parents(rng: random.Random, rooms: list[RoomPlan], kind: str) -> list[int]:
    """The rooms a new room of `kind` may open onto, preferred first: those of its
    `PARENTS` kinds (a second bathroom sometimes a bedroom), then any room but a bathroom."""
    want = list(PARENTS.get(kind, ()))
    if kind == "bathroom" and any(r.kind == "bathroom" for r in rooms) and rng.random() < 0.5:
        want.insert(0, "bedroom")
    want += FALLBACK.get(kind, tuple(sorted(DAY_ROOMS)))
    ranked = [i for k in want for i, r in enumerate(rooms) if r.kind == k]
    ranked += [i for i, r in enumerate(rooms) if i not in ranked and r.kind != "bathroom"]
    return list(dict.fromkeys(ranked))


def _attach(rng: random.Random, rooms: list[RoomPlan], kind: str, w: float, d: float
            ) -> tuple[int, Rect]:
    """A rectangle w x d flush against a side of a parent room, sharing enough of it for
    a door and overlapping no room; of the parent's places the one keeping the plan
    most compact. Raises GraphError when no room has a free side."""
    for parent in _parents(rng, rooms, kind):
        places = [r for r in _places(rooms[parent].rect, w, d, rng)
                  if not any(_overlap(r, other.rect) for other in rooms)]
        if places:
            return parent, min(places, key=lambda r: (_extent(rooms, r), rng.random()))
    raise GraphError(f"floor plan: no room has a free wall for the {kind}")


def _places(p: Rect, w: float, d: float, rng: random.Random) -> list[Rect]:
    """Rectangles w x d (either way round) against each side of `p`, sliding along it
    (aligned to either end, centred, every 0.6 m and at a random offset) while they
    share at least a door and its margins with it."""
    need = DOOR_WIDTH + 2 * DOOR_MARGIN + 2 * WALL
    out = []
    for a, b in ((w, d), (d, w)):
        for side in ("x0", "x1", "z0", "z1"):
            along = b if side[0] == "x" else a  # the new room's extent along the side
            lo, hi = (p[1], p[3]) if side[0] == "x" else (p[0], p[2])
            first, last = lo - along + need, hi - need
            if last < first:
                continue
            steps = max(1, math.ceil((last - first) / 0.6))
            for start in sorted({lo, hi - along, (lo + hi - along) / 2,
                                 *(first + (last - first) * k / steps for k in range(steps + 1)),
                                 rng.uniform(first, last)}):
                start = round(min(max(start, first), last), 2)
                if side == "x0":
                    out.append((round(p[0] - a, 2), start, p[0], round(start + b, 2)))
                elif side == "x1":
                    out.append((p[2], start, round(p[2] + a, 2), round(start + b, 2)))
                elif side == "z0":
                    out.append((start, round(p[1] - b, 2), round(start + a, 2), p[1]))
                else:
                    out.append((start, p[3], round(start + a, 2), round(p[3] + b, 2)))
    return out


def _overlap(a: Rect, b: Rect) -> bool:
    return min(a[2], b[2]) - max(a[0], b[0]) > 1e-6 and min(a[3], b[3]) - max(a[1], b[1]) > 1e-6


def _extent(rooms: list[RoomPlan], r: Rect) -> float:
    """Area of the box around the plan with `r` added (smaller: more compact)."""
    rects = [x.rect for x in rooms] + [r]
    return ((max(x[2] for x in rects) - min(x[0] for x in rects))
            * (max(x[3] for x in rects) - min(x[1] for x in rects)))


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


def _doors(rng: random.Random, rooms: list[RoomPlan], tree: list[tuple[int, int]]
           ) -> list[Opening]:
    """A door for each room onto its parent, and some between neighbouring day rooms."""
    chosen = [tuple(sorted(pair)) for pair in tree]
    for i in range(len(rooms)):
        for j in range(i + 1, len(rooms)):
            if ((i, j) not in chosen and rooms[i].kind in DAY_ROOMS
                    and rooms[j].kind in DAY_ROOMS and _shared(rooms[i].rect, rooms[j].rect)
                    and rng.random() < 0.6):
                chosen.append((i, j))
    doors = []
    for i, j in sorted(chosen):
        shared = _shared(rooms[i].rect, rooms[j].rect)
        assert shared is not None
        side, lo, hi = shared
        edge = DOOR_WIDTH / 2 + DOOR_MARGIN + WALL
        mid = rng.uniform(lo + edge, max(lo + edge, hi - edge))
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
