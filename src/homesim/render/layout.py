"""Turn a home's 3D boxes into renderable parts: slabs, furniture, hinged doors, objects.

Frames: the graph's boxes are in Unity's frame (y up, metres). Everything in
`homesim.render` uses MuJoCo's frame (z up): ``(x, y, z)_mujoco = (x, z, y)_unity``.
Boxes are axis-aligned and stored as (centre, half size).

This module is pure geometry (no mujoco), so navigation and tests can use it alone. The
walk grid comes from the floor model (`homesim.world.floor`), not from the parts.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from homesim.render.palette import RGBA, class_color
from homesim.world.floor import FloorModel
from homesim.world.graph import EnvironmentGraph, Node
from homesim.world.vocab import CAN_OPEN, GRABBABLE, S_ON, S_OPEN, SITTABLE

WALL_THICKNESS = 0.1
"""Metres; corner walls (2.5 m cubes) become slabs this thick on the room's edge."""
PANEL_THICKNESS = 0.04
HINGED_CLASSES = frozenset({
    "fridge", "cabinet", "kitchencabinet", "kitchencabinets", "closet", "microwave",
    "washingmachine", "dishwasher", "stove", "oven", "bathroomcabinet", "closetdrawer",
    "garbagecan", "nightstand", "dresser",
})
"""Classes drawn as a hollow carcass with a hinged front door when they can open."""
SCREEN_CLASSES = frozenset({"tv", "computer", "laptop", "television"})
LAMP_CLASSES = frozenset({"ceilinglamp", "tablelamp", "walllamp", "floorlamp", "lamp",
                          "desklamp", "lightbulb"})
SKIP_CATEGORIES = frozenset({"Rooms", "Characters"})
ENCLOSURES = frozenset({"stall", "shower", "showerstall"})
"""Furniture that surrounds other objects (a toilet stall): drawn as three walls, open at
the front and the top."""
SEAT_HEIGHT = 0.45
"""Metres: sittable boxes taller than 0.7 m become a seat this high and a backrest."""


@dataclass(frozen=True)
class Box:
    """An axis-aligned box in the MuJoCo frame: centre and half size, metres."""

    center: np.ndarray
    half: np.ndarray

    @property
    def lo(self) -> np.ndarray:
        return self.center - self.half

    @property
    def hi(self) -> np.ndarray:
        return self.center + self.half

    @staticmethod
    def from_bounds(lo, hi) -> Box:
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        return Box((lo + hi) / 2, (hi - lo) / 2)


def to_mujoco(node: Node) -> Box | None:
    """A node's bounding box in the MuJoCo frame, or None if it has none."""
    bb = node.bounding_box
    if bb is None:
        return None
    cx, cy, cz = bb.center
    sx, sy, sz = bb.size
    return Box(np.array([cx, cz, cy], float), np.array([sx, sz, sy], float) / 2)


@dataclass
class Hinge:
    """A door panel turning about a vertical axis through `pivot` (closed at angle 0)."""

    pivot: np.ndarray
    panel: Box  # in the hinge body's frame (origin at the pivot), closed position
    open_angle: float  # radians about +z when OPEN
    is_open: bool


@dataclass
class Part:
    """Everything drawn for one graph node."""

    node_id: int
    class_name: str
    rgba: RGBA
    boxes: list[Box] = field(default_factory=list)  # static geometry
    movable: Box | None = None  # a free object (mocap body): grabbable things
    hinge: Hinge | None = None
    screen: Box | None = None  # a thin emissive panel: tv, computer
    lamp: bool = False
    is_on: bool = False


@dataclass
class Layout:
    """The parts of a home, its rooms and floor tiles (all in the MuJoCo frame)."""

    parts: list[Part]
    rooms: dict[int, Box]
    room_names: dict[int, str]
    floors: list[Box]
    room_floors: dict[int, Box]  # bounds of each room's floor tiles
    start: np.ndarray  # the character's start position on the floor (x, y)
    walk: FloorModel | None = None
    """Where the agent may walk: the floor model grounding uses (MuJoCo x, y = Unity x, z)."""

    def part(self, node_id: int) -> Part | None:
        return next((p for p in self.parts if p.node_id == node_id), None)


def _flat(box: Box, min_half: float = 0.01) -> Box:
    return Box(box.center, np.maximum(box.half, min_half))


def _room_floor_tiles(graph: EnvironmentGraph) -> dict[int, list[Box]]:
    tiles: dict[int, list[Box]] = {}
    for node in graph:
        if node.class_name != "floor":
            continue
        box = to_mujoco(node)
        room = graph.room_of(node.id)
        if box is not None and room is not None:
            tiles.setdefault(room, []).append(box)
    return tiles


def _wall_slabs(box: Box, room_tiles: list[Box]) -> list[Box]:
    """A corner cube keeps only the faces with no floor of its room beyond them."""
    if min(box.half[0], box.half[1]) < 0.5:
        return [box]
    slabs = []
    t = WALL_THICKNESS
    for axis in (0, 1):
        for sign in (-1.0, 1.0):
            beyond = box.center.copy()
            beyond[axis] += sign * 2 * box.half[axis]
            if any(np.hypot(*(tile.center[:2] - beyond[:2])) < 0.6 for tile in room_tiles):
                continue
            lo, hi = box.lo.copy(), box.hi.copy()
            if sign < 0:
                hi[axis] = lo[axis] + t
            else:
                lo[axis] = hi[axis] - t
            slabs.append(Box.from_bounds(lo, hi))
    return slabs


def _cut_doorways(slab: Box, jambs: list[Box]) -> list[Box]:
    """Split a wall slab around every door frame that crosses it (leaving a lintel)."""
    along = 0 if slab.half[0] >= slab.half[1] else 1
    across = 1 - along
    pieces = [slab]
    for jamb in jambs:
        out = []
        for piece in pieces:
            gap = abs(jamb.center[across] - piece.center[across])
            lo_j, hi_j = jamb.lo[along], jamb.hi[along]
            if (gap > piece.half[across] + jamb.half[across] + 0.15
                    or hi_j <= piece.lo[along] or lo_j >= piece.hi[along]):
                out.append(piece)
                continue
            lo, hi = piece.lo, piece.hi
            for a, b in ((lo[along], lo_j), (hi_j, hi[along])):
                if b - a > 0.02:
                    plo, phi = lo.copy(), hi.copy()
                    plo[along], phi[along] = a, b
                    out.append(Box.from_bounds(plo, phi))
            top = jamb.hi[2]
            if hi[2] - top > 0.02:
                plo, phi = lo.copy(), hi.copy()
                plo[along], phi[along] = max(lo_j, lo[along]), min(hi_j, hi[along])
                plo[2] = top
                out.append(Box.from_bounds(plo, phi))
        pieces = out
    return pieces


def _front_axis(box: Box, toward: np.ndarray) -> tuple[int, float]:
    """The side face (axis, sign) whose outward normal points most toward `toward`."""
    d = toward[:2] - box.center[:2]
    scores = [(abs(d[a]) / max(box.half[a], 1e-3), a) for a in (0, 1)]
    axis = max(scores)[1]
    return axis, 1.0 if d[axis] >= 0 else -1.0


def _hollow(box: Box, axis: int, sign: float, t: float = 0.03) -> tuple[list[Box], Hinge]:
    """Five carcass slabs and a front door hinged on its left edge."""
    lo, hi = box.lo, box.hi
    slabs = []
    for ax in range(3):
        for s in (-1.0, 1.0):
            if ax == axis and s == sign:
                continue  # the front is the door
            plo, phi = lo.copy(), hi.copy()
            if s < 0:
                phi[ax] = lo[ax] + t
            else:
                plo[ax] = hi[ax] - t
            slabs.append(Box.from_bounds(plo, phi))
    side = 1 - axis
    face = box.center[axis] + sign * (box.half[axis] + PANEL_THICKNESS / 2)
    pivot = box.center.copy()
    pivot[axis] = face
    pivot[side] = lo[side]
    pivot[2] = box.center[2]
    half = np.empty(3)
    half[axis] = PANEL_THICKNESS / 2
    half[side] = box.half[side]
    half[2] = box.half[2]
    offset = np.zeros(3)
    offset[side] = box.half[side]
    # Opening swings the free edge outwards (toward the front).
    turn = np.pi / 2 * 0.9
    open_angle = turn if (axis == 1) == (sign > 0) else -turn
    if axis == 0:
        open_angle = -open_angle
    hinge = Hinge(pivot, Box(offset, half), open_angle, False)
    return slabs, hinge


def _seat(box: Box, axis: int, sign: float) -> list[Box]:
    """A seat `SEAT_HEIGHT` high and a 0.2 m backrest on the side away from the front."""
    lo, hi = box.lo.copy(), box.hi.copy()
    seat_hi = hi.copy()
    seat_hi[2] = lo[2] + SEAT_HEIGHT
    back_lo, back_hi = lo.copy(), hi.copy()
    depth = min(0.2, box.half[axis])
    if sign > 0:
        back_hi[axis] = lo[axis] + depth
    else:
        back_lo[axis] = hi[axis] - depth
    return [Box.from_bounds(lo, seat_hi), Box.from_bounds(back_lo, back_hi)]


def _door(box: Box, jambs: list[Box]) -> Hinge | None:
    if not jambs:
        return None
    jamb = min(jambs, key=lambda j: float(np.hypot(*(j.center[:2] - box.center[:2]))))
    along = 0 if jamb.half[0] >= jamb.half[1] else 1
    across = 1 - along
    pivot = jamb.center.copy()
    pivot[along] = jamb.lo[along] + 0.05
    pivot[2] = jamb.lo[2] + jamb.half[2] - 0.02
    half = np.empty(3)
    half[along] = jamb.half[along] - 0.06
    half[across] = PANEL_THICKNESS / 2
    half[2] = jamb.half[2] - 0.02
    offset = np.zeros(3)
    offset[along] = half[along]
    return Hinge(pivot, Box(offset, half), np.pi / 2, False)


@dataclass
class _Home:
    """What shaping one part needs to know about the rest of the home."""

    graph: EnvironmentGraph
    rooms: dict[int, Box]
    tiles: dict[int, list[Box]]
    jambs: list[Box]

    def toward(self, room: int | None, fallback: Any) -> Any:
        """A point inside the room (its centre), to tell an object's front from its back."""
        return self.rooms[room].center if room in self.rooms else fallback


def build_layout(graph: EnvironmentGraph) -> Layout:
    """All parts of a home with geometry. Raises nothing: nodes without boxes are skipped."""
    home = _Home(graph, {r.id: b for r in graph.rooms() if (b := to_mujoco(r)) is not None},
                 _room_floor_tiles(graph),
                 [b for n in graph.nodes_of_class("doorjamb") if (b := to_mujoco(n)) is not None])
    parts: list[Part] = []
    floors: list[Box] = []
    seen: set[tuple] = set()
    for node in sorted(graph, key=lambda n: n.id):
        box = to_mujoco(node)
        if box is None or node.category in SKIP_CATEGORIES:
            continue
        key = (node.class_name, *np.round(box.center, 2), *np.round(box.half, 2))
        if key in seen:  # VirtualHome lists some floor tiles twice
            continue
        seen.add(key)
        part = Part(node.id, node.class_name, class_color(node.class_name))
        if not _SHAPERS[_kind(node, box)](part, node, box, home):
            continue
        if node.class_name == "floor":
            floors.append(box)
        if part.hinge is not None:
            part.hinge.is_open = S_OPEN in node.states
        part.is_on = S_ON in node.states
        parts.append(part)
    return Layout(parts, home.rooms, {r.id: r.class_name for r in graph.rooms()}, floors,
                  _room_floors(home.tiles), _start(graph), FloorModel(graph))


def _start(graph: EnvironmentGraph) -> np.ndarray:
    """The character's position on the floor (the origin without one)."""
    char = graph.character_id
    if char is not None and (cb := to_mujoco(graph.node(char))) is not None:
        return cb.center[:2].copy()
    return np.zeros(2)


def _room_floors(tiles: dict[int, list[Box]]) -> dict[int, Box]:
    """Room id -> the box around its floor tiles."""
    return {rid: Box.from_bounds(np.min([t.lo for t in ts], axis=0),
                                 np.max([t.hi for t in ts], axis=0))
            for rid, ts in tiles.items()}


def _kind(node: Node, box: Box) -> str:
    """Which shaping a node's part gets (see `_SHAPERS`)."""
    cls = node.class_name
    if cls in ("floor", "ceiling"):
        return cls
    if node.category == "Walls" or cls == "wall":
        return "wall"
    if cls in ("doorjamb", "door"):
        return cls
    if cls in HINGED_CLASSES and CAN_OPEN in node.properties:
        return "hinged"
    if cls in ENCLOSURES:
        return "enclosure"
    if SITTABLE in node.properties and box.hi[2] > 0.7 and cls != "bed":
        return "seat"
    if GRABBABLE in node.properties:
        return "movable"
    return "solid"


Shaper = Callable[[Part, Node, Box, _Home], bool]
"""Fills a part's boxes (hinge, screen, lamp); False drops the part."""


def _flat_part(part: Part, node: Node, box: Box, home: _Home) -> bool:
    part.boxes.append(_flat(box))
    return True


def _wall(part: Part, node: Node, box: Box, home: _Home) -> bool:
    room = home.graph.room_of(node.id)
    for slab in _wall_slabs(box, [] if room is None else home.tiles.get(room, [])):
        part.boxes.extend(_cut_doorways(slab, home.jambs))
    return True


def _doorjamb(part: Part, node: Node, box: Box, home: _Home) -> bool:
    along = 0 if box.half[0] >= box.half[1] else 1
    for s in (-1.0, 1.0):  # two posts; the opening between them stays free
        lo, hi = box.lo.copy(), box.hi.copy()
        if s < 0:
            hi[along] = lo[along] + 0.06
        else:
            lo[along] = hi[along] - 0.06
        part.boxes.append(Box.from_bounds(lo, hi))
    return True


def _door_part(part: Part, node: Node, box: Box, home: _Home) -> bool:
    part.hinge = _door(box, home.jambs)
    return part.hinge is not None


def _hinged(part: Part, node: Node, box: Box, home: _Home) -> bool:
    toward = home.toward(home.graph.room_of(node.id), [*box.center, 0, 1, 0])
    part.boxes, part.hinge = _hollow(box, *_front_axis(box, toward))
    return True


def _enclosure(part: Part, node: Node, box: Box, home: _Home) -> bool:
    toward = home.toward(home.graph.room_of(node.id), box.center + np.array([0.0, 1.0, 0.0]))
    slabs, _ = _hollow(box, *_front_axis(box, toward))
    part.boxes = [b for b in slabs if b.hi[2] < box.hi[2] - 1e-6 or b.half[2] > 0.1]
    return True


def _seat_part(part: Part, node: Node, box: Box, home: _Home) -> bool:
    toward = home.toward(home.graph.room_of(node.id), box.center + np.array([0.0, 1.0, 0.0]))
    part.boxes = _seat(box, *_front_axis(box, toward))
    return True


def _movable(part: Part, node: Node, box: Box, home: _Home) -> bool:
    part.movable = _flat(box, 0.01)
    return True


def _solid(part: Part, node: Node, box: Box, home: _Home) -> bool:
    """A plain box; screens get a thin panel on the side facing the room, lamps light."""
    part.boxes.append(_flat(box))
    cls = node.class_name
    if cls in SCREEN_CLASSES:
        part.screen = _screen(box, home.toward(home.graph.room_of(node.id),
                                               [*box.center, 0, 1, 0]))
    if cls in LAMP_CLASSES or node.category == "Lamps":
        part.lamp = True
    return True


def _screen(box: Box, toward: Any) -> Box:
    thin = 0 if box.half[0] < box.half[1] else 1
    sign = 1.0 if toward[thin] >= box.center[thin] else -1.0
    c = box.center.copy()
    c[thin] += sign * (box.half[thin] + 0.006)
    half = box.half * 0.9
    half[thin] = 0.005
    return Box(c, half)


_SHAPERS: dict[str, Shaper] = {
    "floor": _flat_part, "ceiling": _flat_part, "wall": _wall, "doorjamb": _doorjamb,
    "door": _door_part, "hinged": _hinged, "enclosure": _enclosure, "seat": _seat_part,
    "movable": _movable, "solid": _solid,
}


def lights_on_by_switch(graph: EnvironmentGraph) -> dict[int, bool]:
    """Room id -> whether its light switch is on (rooms without one count as lit)."""
    lit: dict[int, bool] = {r: True for r in graph.room_ids}
    for sw in graph.nodes_of_class("lightswitch"):
        room = graph.room_of(sw.id)
        if room is not None:
            lit[room] = S_ON in sw.states
    return lit


def room_of_point(layout: Layout, xy: np.ndarray) -> int | None:
    """The room whose floor tiles contain a point (the smallest room box on ties)."""
    best = None
    for rid, box in layout.room_floors.items():
        if np.all(np.abs(xy - box.center[:2]) <= box.half[:2]):
            area = box.half[0] * box.half[1]
            if best is None or area < best[0]:
                best = (area, rid)
    return None if best is None else best[1]


__all__ = ["Box", "Hinge", "Layout", "Part", "build_layout", "to_mujoco"]
