"""Furniture: what each room holds (drawn from its kind's fitted statistics) and where it
stands, hangs or is mounted: against walls or beside its anchor (a chair at a desk),
by rejection sampling, without overlaps, keeping door ways and free floor to walk."""

from __future__ import annotations

import random
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from homesim.world.class_table import class_row, classes_where
from homesim.world.procedural.geometry import (
    DOOR_REACH,
    SLACK,
    FreeFloor,
    Rect,
    blocks,
    inside,
    overlaps,
)
from homesim.world.procedural.parts import Box3, Part, box3, overlap3
from homesim.world.procedural.plan import HEIGHT, Plan
from homesim.world.procedural.stats import class_info, kind_objects
from homesim.world.procedural.structure import INWARD, door_rects, side_box

CAP = {"floor": 3, "wall": 4, "ceiling": 2}
KEEP_OUT = 1.0
"""Depth (m) of the free zone in front of a door."""
TRIES = 60
ACROSS_SIDE = 1.5
"""Metres a piece facing its anchor across the floor may stand to the side of it (a sofa
still FACES the TV from there)."""


@dataclass
class Entry:
    cls: str
    mount: str
    count: int
    parents: dict[str, int]


def mount_of(cls: str, fitted: str) -> str:
    """Where a class goes: its class-table row's ``mount`` when it has one, else as
    fitted from the built-in homes (but what they hang on a wall or ceiling without a
    mount of its own stands on or in furniture)."""
    row = class_row(cls)
    if row is not None and row.mount:
        return row.mount
    return "item" if fitted in ("wall", "ceiling") else fitted


def _tagged(cls: str, tag: str) -> bool:
    row = class_row(cls)
    return row is not None and tag in row.tags


def anchors_of(cls: str) -> tuple[str, ...]:
    """The classes a class stands beside (the class table's ``beside``)."""
    row = class_row(cls)
    return () if row is None else row.beside


def draw_entries(rng: random.Random, kind: str) -> list[Entry]:
    """What a room of this kind holds: each fitted class with its probability, those the
    class table requires in this kind always; counts drawn from those seen."""
    required = classes_where(required=kind)
    out = []
    for obj in kind_objects(kind):
        cls = obj["class"]
        if cls not in required and rng.random() >= obj["p"]:
            continue
        row = class_row(cls)
        if row is not None and row.rooms and kind not in row.rooms and cls not in required:
            continue  # furniture by room type: no sofa or nightstand in a kitchen
        mount = mount_of(cls, obj["mount"])
        count = rng.choice(obj["counts"])
        if mount in CAP:
            count = min(count, CAP[mount])
        if _tagged(cls, "single"):
            count = 1
        out.append(Entry(cls, mount, count, obj["parents"]))
    return out


class RoomFurnisher:
    """Places the fixtures of one room into `parts` (appending)."""

    def __init__(self, rng: random.Random, plan: Plan, parts: list[Part], room: int):
        self.rng, self.plan, self.parts, self.room = rng, plan, parts, room
        self.interior = plan.rooms[room].interior
        self.doors = door_rects(plan, room)
        self.keep_out = [self._keep_out(d) for d in self.doors]
        self.fixtures: list[int] = []
        self._base: tuple[int, FreeFloor, list[Rect]] | None = None
        self._masks: dict[tuple[Rect, float], np.ndarray] = {}

    def _keep_out(self, d: Rect) -> Box3:
        x0, z0, x1, z1 = d
        r = self.interior
        if x1 - x0 < z1 - z0:  # a door in an x side
            x0, x1 = (x0, x0 + KEEP_OUT) if abs(x0 - r[0]) < 0.05 else (x1 - KEEP_OUT, x1)
            z0, z1 = z0 - 0.2, z1 + 0.2
        else:
            z0, z1 = (z0, z0 + KEEP_OUT) if abs(z0 - r[1]) < 0.05 else (z1 - KEEP_OUT, z1)
            x0, x1 = x0 - 0.2, x1 + 0.2
        return box3(x0, 0.0, z0, x1, 2.2, z1)

    def floor_tile(self, x: float, z: float, cls: str = "floor") -> int:
        """The floor (or ceiling) tile of this room under (x, z)."""
        best = None
        for k, p in enumerate(self.parts):
            if p.room == self.room and p.cls == cls:
                f = p.footprint
                if f[0] - 1e-6 <= x <= f[2] + 1e-6 and f[1] - 1e-6 <= z <= f[3] + 1e-6:
                    return k
                best = k if best is None else best
        assert best is not None
        return best

    def free(self, box: Box3, flat: bool = False) -> bool:
        fp = (box[0], box[2], box[3], box[5])
        if not inside(fp, self.interior):
            return False
        if any(overlap3(box, k, 0.0) for k in self.keep_out) and box[1] < 2.2:
            return False
        for k in self.fixtures:
            other = self.parts[k]
            if flat != (other.cls == "rug"):
                continue
            if overlap3(box, other.box, -0.02 if not flat else 0.0):
                return False
        return True

    def _floor(self, extra: Box3 | None) -> tuple[FreeFloor, list[Rect]]:
        """The room's free floor with its fixtures (and `extra`) as obstacles, and those
        obstacles. The floor of the fixtures placed so far is kept and copied."""
        if self._base is None or self._base[0] != len(self.fixtures):
            boxes = [self.parts[k].box for k in self.fixtures]
            obstacles = [(b[0], b[2], b[3], b[5]) for b in boxes if blocks(b)]
            self._base = (len(self.fixtures), FreeFloor(self.interior, obstacles, strict=True,
                                                        masks=self._masks), obstacles)
        floor, obstacles = self._base[1].copy(), list(self._base[2])
        if extra is not None and blocks(extra):
            floor.block((extra[0], extra[2], extra[3], extra[5]))
            obstacles.append((extra[0], extra[2], extra[3], extra[5]))
        return floor, obstacles

    def walkable(self, extra: Box3 | None = None) -> bool:
        floor, obstacles = self._floor(extra)
        return floor.walkable(self.doors, obstacles) is None

    def reachable(self, box: Box3) -> bool:
        """Whether the agent can walk from the doors to within reach of `box`."""
        floor, _ = self._floor(box)
        return floor.walkable(self.doors, [(box[0], box[2], box[3], box[5])]) is None

    def place_floor(self, cls: str) -> bool:
        w, h, d = class_info(cls)["size"]
        flat = cls == "rug"
        for box, normal in self._floor_candidates(cls, w, h, d):
            if self.free(box, flat) and (flat or self.walkable(box)):
                tile = self.floor_tile((box[0] + box[3]) / 2, (box[2] + box[5]) / 2)
                self.add(Part(cls, self.room, box, (tile, "ON"), normal, kind="fixture"))
                return True
        return False

    def _floor_candidates(self, cls: str, w: float, h: float, d: float
                          ) -> Iterator[tuple[Box3, tuple[float, float]]]:
        rng, r = self.rng, self.interior
        anchors = [k for k in self.fixtures if self.parts[k].cls in anchors_of(cls)]
        for t in range(TRIES):
            if anchors and t < TRIES - 10 and _tagged(cls, "across"):
                yield self._across(self.parts[rng.choice(anchors)], w, h, d)
            elif anchors and t < TRIES // 2:
                anchor = self.parts[rng.choice(anchors)]
                a = anchor.box
                side = rng.choice(_ends(anchor) if _tagged(cls, "end") else
                                  _front(anchor) if _tagged(anchor.cls, "faced") else
                                  ("x0", "x1", "z0", "z1"))
                gap = rng.uniform(0.05, 0.25)
                if side[0] == "x":
                    z = _along(rng, a[2], a[5], w)
                    x = a[0] - gap - d / 2 if side == "x0" else a[3] + gap + d / 2
                    yield box3(x - d / 2, 0, z - w / 2, x + d / 2, h, z + w / 2), (
                        (1.0, 0.0) if side == "x0" else (-1.0, 0.0))
                else:
                    x = _along(rng, a[0], a[3], w)
                    z = a[2] - gap - d / 2 if side == "z0" else a[5] + gap + d / 2
                    yield box3(x - w / 2, 0, z - d / 2, x + w / 2, h, z + d / 2), (
                        (0.0, 1.0) if side == "z0" else (0.0, -1.0))
            elif _tagged(cls, "centre"):
                m = 0.6
                x = rng.uniform(r[0] + m + w / 2, max(r[0] + m + w / 2, r[2] - m - w / 2))
                z = rng.uniform(r[1] + m + d / 2, max(r[1] + m + d / 2, r[3] - m - d / 2))
                yield box3(x - w / 2, 0, z - d / 2, x + w / 2, h, z + d / 2), (0.0, 1.0)
            else:
                side = rng.choice(self._facing_sides(cls, anchors))
                lo, hi = (r[1], r[3]) if side[0] == "x" else (r[0], r[2])
                if hi - lo < w:
                    continue
                start = rng.uniform(lo, hi - w)
                yield side_box(r, side, start, start + w, d, 0.0, h), INWARD[side]

    def _facing_sides(self, cls: str, anchors: list[int]) -> tuple[str, ...]:
        """The walls a piece may stand against: for one that faces its anchor across the
        floor (`across`), the wall facing the anchor when it has one; else any."""
        if anchors and _tagged(cls, "across"):
            n = self.parts[anchors[0]].normal
            back = [side for side, inward in INWARD.items()
                    if n is not None and inward == (-n[0], -n[1])]
            if back:
                return tuple(back)
        return ("x0", "x1", "z0", "z1")

    def _across(self, anchor: Part, w: float, h: float, d: float
                ) -> tuple[Box3, tuple[float, float]]:
        """A box w wide and d deep facing `anchor` (a sofa facing the TV stand) from
        1.3-3.2 m in front of it, its front toward the anchor."""
        a, n = anchor.box, anchor.normal or (0.0, 1.0)
        gap = self.rng.uniform(1.3, 3.2)
        if n[0]:  # the anchor faces along x: the box's width runs along z
            x = (a[3] if n[0] > 0 else a[0]) + n[0] * (gap + d / 2)
            z = (a[2] + a[5]) / 2 + self.rng.uniform(-ACROSS_SIDE, ACROSS_SIDE)
            return box3(x - d / 2, 0, z - w / 2, x + d / 2, h, z + w / 2), (-n[0], 0.0)
        z = (a[5] if n[1] > 0 else a[2]) + n[1] * (gap + d / 2)
        x = (a[0] + a[3]) / 2 + self.rng.uniform(-ACROSS_SIDE, ACROSS_SIDE)
        return box3(x - w / 2, 0, z - d / 2, x + w / 2, h, z + d / 2), (0.0, -n[1])

    def place_wall(self, cls: str) -> bool:
        info = class_info(cls)
        w, h, d = info["size"]
        y0 = min(max(0.2, info["height"]), HEIGHT - h - 0.05)
        walls = [(k, p) for k, p in enumerate(self.parts)
                 if p.room == self.room and p.cls == "wall"]
        stoves = [self.parts[k] for k in self.fixtures if self.parts[k].cls == "stove"]
        for t in range(TRIES):
            k, wall = self.rng.choice(walls)
            side = _side(wall.normal)
            lo, hi = (wall.box[2], wall.box[5]) if side[0] == "x" else (wall.box[0],
                                                                         wall.box[3])
            if cls == "stovefan" and stoves and t < TRIES // 2:
                s = stoves[0]
                side = _side(s.normal)
                on = self._wall_on(side, s.footprint)
                if on is None:
                    continue
                k = on
                mid = ((s.box[2] + s.box[5]) / 2 if side[0] == "x"
                       else (s.box[0] + s.box[3]) / 2)
                a = mid - w / 2
                y0 = 1.7
            else:
                lo, hi = max(lo, self._span(side)[0]), min(hi, self._span(side)[1])
                if hi - lo < w:
                    continue
                a = self.rng.uniform(lo, hi - w)
            box = side_box(self.interior, side, a, a + w, d, y0, y0 + h)
            if (self.free(box) and self.reachable(box)
                    and (not blocks(box) or self.walkable(box))):
                self.add(Part(cls, self.room, box, (k, "ON"), INWARD[side], kind="fixture"))
                return True
        return False

    def _span(self, side: str) -> tuple[float, float]:
        r = self.interior
        return (r[1], r[3]) if side[0] == "x" else (r[0], r[2])

    def _wall_on(self, side: str, fp: Rect) -> int | None:
        for k, p in enumerate(self.parts):
            if (p.room == self.room and p.cls == "wall" and _side(p.normal) == side
                    and (overlaps(p.footprint, fp, -0.2) or _spans(p, side, fp))):
                return k
        return None

    def place_ceiling(self, cls: str) -> bool:
        w, h, d = class_info(cls)["size"]
        r = self.interior
        for _ in range(TRIES):
            x = self.rng.uniform(r[0] + w, r[2] - w) if r[2] - r[0] > 2 * w else (r[0] + r[2]) / 2
            z = self.rng.uniform(r[1] + d, r[3] - d) if r[3] - r[1] > 2 * d else (r[1] + r[3]) / 2
            box = box3(x - w / 2, HEIGHT - h, z - d / 2, x + w / 2, HEIGHT, z + d / 2)
            if self.free(box):
                tile = self.floor_tile(x, z, "ceiling")
                self.add(Part(cls, self.room, box, (tile, "ON"), kind="fixture"))
                return True
        return False

    def prune(self) -> None:
        """Drop the fixtures the agent cannot walk to (a wall lamp behind a wardrobe);
        dropping one only frees floor, so the others stay reachable."""
        if not self.fixtures or not self.doors:
            return
        mine = [self.parts[k] for k in self.fixtures]
        floor = FreeFloor(self.interior, [p.footprint for p in mine if blocks(p.box)],
                          strict=True)
        comp = floor.reach_from(floor.near(self.doors[0], DOOR_REACH - SLACK))
        keep = [p for p in mine if (comp & floor.near(p.footprint, 0.7 - SLACK)).any()]
        first = self.fixtures[0]
        del self.parts[first:]
        self.parts.extend(keep)
        self.fixtures = list(range(first, len(self.parts)))
        self._base = None

    def add(self, part: Part) -> None:
        part.states = tuple(class_info(part.cls)["states"])
        self.parts.append(part)
        self.fixtures.append(len(self.parts) - 1)


def _along(rng: random.Random, lo: float, hi: float, width: float) -> float:
    """Where along an anchor's side [lo, hi] a piece `width` wide goes: within the side
    (its middle when it is the wider)."""
    if hi - lo <= width:
        return (lo + hi) / 2
    return rng.uniform(lo + width / 2, hi - width / 2)


def _front(anchor: Part) -> tuple[str, ...]:
    """The side before a piece's front (a desk's chair stands there)."""
    n = anchor.normal
    if n is None:
        return ("x0", "x1", "z0", "z1")
    if n[0]:
        return ("x1",) if n[0] > 0 else ("x0",)
    return ("z1",) if n[1] > 0 else ("z0",)


def _ends(anchor: Part) -> tuple[str, ...]:
    """The sides at the ends of a piece (not its front or back): where a computer tower
    stands beside its desk, out of the way of the legs of whoever sits at it."""
    n = anchor.normal
    if n is None:
        return ("x0", "x1", "z0", "z1")
    return ("z0", "z1") if n[0] else ("x0", "x1")


def _side(normal: tuple[float, float] | None) -> str:
    for side, n in INWARD.items():
        if n == normal:
            return side
    raise ValueError(f"not a wall normal: {normal}")


def _spans(p: Part, side: str, fp: Rect) -> bool:
    if side[0] == "x":
        return p.box[2] <= (fp[1] + fp[3]) / 2 <= p.box[5]
    return p.box[0] <= (fp[0] + fp[2]) / 2 <= p.box[3]


def _rank(cls: str) -> int:
    """Placing order: what a piece faces across the floor first (the TV stand), then that
    piece (the sofa), then the rest, pieces standing beside others last."""
    across = classes_where(tags="across")
    if any(cls in anchors_of(a) for a in across):
        return 0
    if cls in across:
        return 1
    return 3 if anchors_of(cls) else 2


def furnish_room(rng: random.Random, plan: Plan, parts: list[Part], room: int
                 ) -> list[Entry]:
    """Place the room's fixtures; return the entries left for `homesim.world.procedural.
    items` (things on and in furniture)."""
    entries = draw_entries(rng, plan.rooms[room].kind)
    f = RoomFurnisher(rng, plan, parts, room)

    def area(e: Entry) -> float:
        w, _, d = class_info(e.cls)["size"]
        return -w * d

    floor = sorted((e for e in entries if e.mount == "floor"), key=lambda e: (
        _rank(e.cls), e.cls == "rug", area(e), e.cls))
    for e in floor:
        for _ in range(e.count):
            f.place_floor(e.cls)
    for e in entries:
        for _ in range(e.count):
            if e.mount == "wall":
                f.place_wall(e.cls)
            elif e.mount == "ceiling":
                f.place_ceiling(e.cls)
    f.prune()
    return [e for e in entries if e.mount == "item"]
