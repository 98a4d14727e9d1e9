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

from homesim.render.counters import COUNTERS, carve, strips
from homesim.render.models import Shape, fit_model, local_model, variant_of
from homesim.render.palette import RGBA, class_color
from homesim.sim.effects import can_grab
from homesim.world.class_table import class_row
from homesim.world.floor import FloorModel
from homesim.world.graph import EnvironmentGraph, Node
from homesim.world.vocab import CAN_OPEN, S_ON, S_OPEN, SITTABLE

WALL_THICKNESS = 0.1
"""Metres; corner walls (2.5 m cubes) become slabs this thick on the room's edge."""
PANEL_THICKNESS = 0.04
"""Metres of a hinged front inside its box: the door leaf and, in front of it, the handle."""
LEAF_THICKNESS = 0.025
SKIP_CATEGORIES = frozenset({"Rooms", "Characters"})
SEAT_HEIGHT = 0.45
"""Metres: sittable boxes taller than 0.7 m become a seat this high and a backrest."""
DESK_TOP = 0.05
"""Metres: a desk's top board; what stands under it is cut out of the desk below that."""
DESK_FACE = 0.05
"""Metres: what stands under a desk this near a side face of its box is cut out through
that face."""
TABLES = ("desk", "kitchentable", "table", "coffeetable", "diningtable", "kitchencounter")
AT_TABLE = 0.5
"""Metres: a seat this near a table, desk or counter faces it."""


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
    shapes: list[Shape] = field(default_factory=list)  # drawn, in the hinge body's frame


@dataclass
class Part:
    """Everything drawn for one graph node."""

    node_id: int
    class_name: str
    rgba: RGBA
    boxes: list[Box] = field(default_factory=list)  # what it occupies (navigation, cameras)
    shapes: list[Shape] = field(default_factory=list)  # what is drawn (static), MuJoCo frame
    movable: Box | None = None  # a free object (mocap body): grabbable things
    movable_shapes: list[Shape] = field(default_factory=list)  # drawn, body frame
    hinge: Hinge | None = None
    screen: Box | None = None  # a thin emissive panel: tv, computer
    lamp: bool = False
    is_on: bool = False
    front: tuple[int, float] | None = None  # the side facing the room (axis, sign)
    levels: list[float] = field(default_factory=list)  # inside: tops of floor and shelves


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
    room_of_part: dict[int, int] = field(default_factory=dict)  # node id -> room id

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
    """Five carcass slabs and a front door hinged on its left edge, all inside the box:
    the front `PANEL_THICKNESS` holds the door leaf and its handle."""
    lo, hi = box.lo.copy(), box.hi.copy()
    if sign > 0:
        hi[axis] -= PANEL_THICKNESS
    else:
        lo[axis] += PANEL_THICKNESS
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
    face = box.center[axis] + sign * (box.half[axis] - PANEL_THICKNESS + LEAF_THICKNESS / 2)
    pivot = box.center.copy()
    pivot[axis] = face
    pivot[side] = box.lo[side]
    half = np.empty(3)
    half[axis] = LEAF_THICKNESS / 2
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


def _handle(panel: Box, axis: int, sign: float, depth: float) -> Shape:
    """A vertical bar handle in front of a door leaf, near its free edge (hinge frame)."""
    side = 1 - axis
    c = panel.center.copy()
    c[side] = panel.center[side] + panel.half[side] - min(0.06, panel.half[side] * 0.3)
    c[axis] += sign * (panel.half[axis] + depth / 2)
    tall = min(0.3, panel.half[2] * 0.6)
    c[2] = min(c[2] + panel.half[2] * 0.2, panel.center[2] + panel.half[2] - tall)
    half = np.full(3, 0.01)
    half[axis] = depth / 2
    half[2] = tall
    return Shape("box", c, half, "chrome")


def _window(panel: Box, axis: int, sign: float) -> Shape:
    """A dark glass pane on the front of a door leaf (microwave, oven, washer)."""
    c = panel.center.copy()
    c[axis] += sign * (panel.half[axis] - 0.002)
    half = panel.half * 0.7
    half[axis] = 0.003
    c[1 - axis] -= panel.half[1 - axis] * 0.1
    return Shape("box", c, half, "glass_dark")


_CARCASS_ROLE = {"white": "white", "metal": "metal", "dark": "black"}
"""A hinged object's family (class table) -> the material of its body; others are wood."""


def render_kind(class_name: str) -> str:
    """How render shapes a class beyond its model (the class table's ``render``: hinged,
    screen, lamp, room_lamp, enclosure; empty for the rest)."""
    row = class_row(class_name)
    return "" if row is None else row.render


def _tagged(class_name: str, tag: str) -> bool:
    row = class_row(class_name)
    return row is not None and tag in row.tags


def _family(class_name: str) -> str:
    row = class_row(class_name)
    return "" if row is None else row.family


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


def door_leaf(jamb: Box) -> Box:
    """The closed door leaf of a door frame: between its posts, as tall as the opening.

    The built-in homes' door boxes are these leaves (`tools/convert_homes.py` sets them:
    VirtualHome's are 0.93 x 0.93 x 1.0 placeholders), so the door is drawn from its box."""
    along = 0 if jamb.half[0] >= jamb.half[1] else 1
    half = np.empty(3)
    half[along] = jamb.half[along] - 0.06
    half[1 - along] = LEAF_THICKNESS / 2
    half[2] = jamb.half[2] - 0.02
    center = jamb.center.copy()
    center[2] = jamb.lo[2] + half[2]
    return Box(center, half)


def _is_leaf(box: Box) -> bool:
    return min(box.half[0], box.half[1]) <= 0.05 and box.half[2] > 0.6


def _door(box: Box, jambs: list[Box]) -> Hinge | None:
    """A room door hinged on one edge of its leaf: the node's box when it is a leaf (it
    opens on its +90 degree side), else the leaf of the nearest door frame, hinged on the
    end and opening to the side that keep it, open, inside the node's box (the box of
    its swing, `homesim.world.doors.door_swing`; VirtualHome's placeholders as far as
    they can)."""
    if _is_leaf(box):
        return _leaf_hinge(box, 0, 1.0)
    if not jambs:
        return None
    leaf = door_leaf(min(jambs, key=lambda j: float(np.hypot(*(j.center[:2]
                                                               - box.center[:2])))))
    end, side = max(((e, s) for e in (0, 1) for s in (1.0, -1.0)),
                    key=lambda c: _overlap(_swung(leaf, *c), box))
    return _leaf_hinge(leaf, end, side)


def _leaf_hinge(leaf: Box, end: int, side: float) -> Hinge:
    """A hinge on end `end` (0: the low end along the leaf, 1: the high end) of a closed
    leaf, opening 90 degrees about +z with sign `side`."""
    along = 0 if leaf.half[0] >= leaf.half[1] else 1
    pivot = leaf.center.copy()
    pivot[along] = leaf.lo[along] if end == 0 else leaf.hi[along]
    offset = np.zeros(3)
    offset[along] = leaf.half[along] if end == 0 else -leaf.half[along]
    return Hinge(pivot, Box(offset, leaf.half.copy()), side * np.pi / 2, False)


def _swung(leaf: Box, end: int, side: float) -> Box:
    """The box of a leaf hinged at `end` once swung open by `side` * 90 degrees."""
    h = _leaf_hinge(leaf, end, side)
    c, s = np.cos(h.open_angle), np.sin(h.open_angle)
    off = h.panel.center
    center = h.pivot + np.array([c * off[0] - s * off[1], s * off[0] + c * off[1], off[2]])
    half = h.panel.half[[1, 0, 2]]  # a quarter turn swaps the horizontal extents
    return Box(center, half)


def _overlap(a: Box, b: Box) -> float:
    """Volume of the intersection of two boxes."""
    d = np.minimum(a.hi, b.hi) - np.maximum(a.lo, b.lo)
    return float(np.prod(np.maximum(d, 0.0)))


@dataclass
class _Home:
    """What shaping one part needs to know about the rest of the home."""

    graph: EnvironmentGraph
    rooms: dict[int, Box]
    tiles: dict[int, list[Box]]
    jambs: list[Box]
    seed: int = 0

    def toward(self, room: int | None, fallback: Any) -> Any:
        """A point inside the room (its centre), to tell an object's front from its back."""
        return self.rooms[room].center if room in self.rooms else fallback

    def front(self, node: Node, box: Box) -> tuple[int, float]:
        """The side of a node's box that faces its room; a seat faces the table, desk or
        counter it stands at (within `AT_TABLE`), else a screen it FACES."""
        room = self.graph.room_of(node.id)
        if SITTABLE in node.properties and node.class_name != "bed":
            faced = self._faced(node, box, room)
            if faced is not None:
                return _front_axis(box, faced)
        return _front_axis(box, self.toward(room, box.center + np.array([0.0, 1.0, 0.0])))

    def _faced(self, node: Node, box: Box, room: int | None) -> np.ndarray | None:
        """The centre of what a seat faces: the nearest table, desk or counter it stands
        at, else a screen it FACES."""
        graph = self.graph
        near: tuple[float, np.ndarray] | None = None
        for cls in TABLES:
            for table in graph.nodes_of_class(cls):
                b = to_mujoco(table)
                if b is None or graph.room_of(table.id) != room:
                    continue
                gap = float(np.linalg.norm(np.maximum(np.abs(b.center[:2] - box.center[:2])
                                                      - b.half[:2] - box.half[:2], 0.0)))
                if gap <= AT_TABLE and (near is None or gap < near[0]):
                    near = (gap, b.center)
        if near is not None:
            return near[1]
        for t in sorted(graph.targets(node.id, "FACING")):
            if render_kind(graph.node(t).class_name) == "screen" and graph.room_of(t) == room:
                b = to_mujoco(graph.node(t))
                if b is not None:
                    return b.center
        return None

    def model(self, node: Node, box: Box, front: tuple[int, float] | None = None
              ) -> list[Shape]:
        """The node's model fitted to its box, its variant chosen by the seed (objects of
        a class in the same room look alike)."""
        room = self.graph.room_of(node.id) or 0
        variant = variant_of(node.class_name, self.seed, room)
        return fit_model(node.class_name, node.category, box.center, box.half,
                         front or self.front(node, box), variant)


def build_layout(graph: EnvironmentGraph, seed: int = 0) -> Layout:
    """All parts of a home with geometry; `seed` picks model variants. Raises nothing:
    nodes without boxes are skipped."""
    home = _Home(graph, {r.id: b for r in graph.rooms() if (b := to_mujoco(r)) is not None},
                 _room_floor_tiles(graph),
                 [b for n in graph.nodes_of_class("doorjamb") if (b := to_mujoco(n)) is not None],
                 seed)
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
    _carve_counters(parts, graph)
    _clear_shelves(parts, graph)
    rooms_of = {p.node_id: r for p in parts if (r := graph.room_of(p.node_id)) is not None}
    return Layout(parts, home.rooms, {r.id: r.class_name for r in graph.rooms()}, floors,
                  _room_floors(home.tiles), _start(graph), FloorModel(graph), rooms_of)


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
    kind = render_kind(cls)
    if kind == "hinged" and CAN_OPEN in node.properties:
        return "hinged"
    if kind == "enclosure":
        return "enclosure"
    if SITTABLE in node.properties and box.hi[2] > 0.7 and cls != "bed":
        return "seat"
    if can_grab(node.properties, cls):  # what a hand may take rides in it
        return "movable"
    if cls in COUNTERS:
        return "counter"
    return "solid"


Shaper = Callable[[Part, Node, Box, _Home], bool]
"""Fills a part's boxes and shapes (hinge, screen, lamp); False drops the part."""


def _slab_shapes(boxes: list[Box], role: str, piece: float = 0.0) -> list[Shape]:
    """Box shapes of slabs; with `piece` > 0, each cut into pieces at most that long
    along x and y (and 1.25 m up): MuJoCo lights per vertex, so a room light's pool of
    light falls off across a floor or wall only where it has vertices."""
    out = []
    for b in boxes:
        for c, h in _pieces(b, piece) if piece > 0 else [(b.center, b.half)]:
            out.append(Shape("box", c.copy(), np.maximum(h, 1e-3), role))
    return out


LIT_PIECE = 1.25
"""Metres: floors and walls are drawn in pieces this long for the lights' falloff."""


def _pieces(b: Box, piece: float) -> list[tuple[np.ndarray, np.ndarray]]:
    counts = [max(1, int(np.ceil(2 * b.half[a] / piece - 1e-6))) for a in range(3)]
    size = 2 * b.half / np.array(counts)
    out = []
    for i in range(counts[0]):
        for j in range(counts[1]):
            for k in range(counts[2]):
                lo = b.lo + size * np.array([i, j, k])
                out.append((lo + size / 2, size / 2))
    return out


def _room_role(kind: str, node: Node, home: _Home) -> str:
    room = home.graph.room_of(node.id)
    return kind if room is None else f"{kind}@{room}"


def _flat_part(part: Part, node: Node, box: Box, home: _Home) -> bool:
    part.boxes.append(_flat(box))
    ceiling = node.class_name == "ceiling"
    role = "ceiling" if ceiling else _room_role("floor", node, home)
    part.shapes = _slab_shapes(part.boxes, role, 0.0 if ceiling else LIT_PIECE)
    return True


def _wall(part: Part, node: Node, box: Box, home: _Home) -> bool:
    room = home.graph.room_of(node.id)
    for slab in _wall_slabs(box, [] if room is None else home.tiles.get(room, [])):
        part.boxes.extend(_cut_doorways(slab, home.jambs))
    part.shapes = _slab_shapes(part.boxes, _room_role("wall", node, home), LIT_PIECE)
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
    part.shapes = _slab_shapes(part.boxes, "white")
    return True


def _door_part(part: Part, node: Node, box: Box, home: _Home) -> bool:
    part.hinge = h = _door(box, home.jambs)
    if h is None:
        return False
    along = 0 if h.panel.half[0] >= h.panel.half[1] else 1
    knob = h.panel.center.copy()
    knob[along] += h.panel.half[along] * 0.8
    knob[2] = 1.0 - h.pivot[2]  # a metre above the floor
    knob_half = np.full(3, 0.025)
    knob_half[1 - along] = h.panel.half[1 - along]  # the leaf is thinner: the knob shows
    leaf_half = h.panel.half.copy()
    leaf_half[1 - along] *= 0.6
    h.shapes = [Shape("box", h.panel.center.copy(), leaf_half, "wood"),
                Shape("box", knob, knob_half, "chrome")]
    return True


def _hinged(part: Part, node: Node, box: Box, home: _Home) -> bool:
    axis, sign = home.front(node, box)
    part.boxes, part.hinge = _hollow(box, axis, sign)
    role = _CARCASS_ROLE.get(_family(node.class_name), "wood")
    part.shapes = _slab_shapes(part.boxes, role)
    shelves, part.levels = _shelves(part.boxes, axis)
    part.boxes += shelves
    part.shapes += _slab_shapes(shelves, "glass" if role == "white" else role)
    h = part.hinge
    h.shapes = [Shape("box", h.panel.center.copy(), h.panel.half.copy(), role),
                _handle(h.panel, axis, sign, PANEL_THICKNESS - LEAF_THICKNESS)]
    if _tagged(node.class_name, "windowed"):
        h.shapes.append(_window(h.panel, axis, sign))
    if node.class_name in ("stove", "oven"):  # the top gives way to the hot plates
        part.shapes = [Shape(s.kind, s.center - [0, 0, 0.004], s.half, s.role)
                       if s.center[2] - s.half[2] > box.center[2] else s for s in part.shapes]
        part.shapes += _burners(box)
    return True


SHELF_GAP = 0.36
"""Metres between the shelves inside a cabinet, fridge or closet (about)."""
SHELF_THICKNESS = 0.015


def _shelves(slabs: list[Box], front_axis: int) -> tuple[list[Box], list[float]]:
    """Shelves inside a hollow carcass (its five slabs): boards spanning the inside every
    `SHELF_GAP` or so, and the heights things rest at inside (the carcass floor's top,
    each shelf's top)."""
    lo = np.min([b.lo for b in slabs], axis=0)
    hi = np.max([b.hi for b in slabs], axis=0)
    floor = min(slabs, key=lambda b: b.center[2])  # the bottom slab
    ceil = max(slabs, key=lambda b: b.center[2])
    inner_lo, inner_hi = floor.hi[2], ceil.lo[2]
    n = int((inner_hi - inner_lo) // SHELF_GAP)
    if n < 2:
        return [], [float(inner_lo)]
    t = float(min(b.half[a] for b in slabs for a in range(3)) * 2)
    boards, levels = [], [float(inner_lo)]
    for k in range(1, n):
        z = inner_lo + k * (inner_hi - inner_lo) / n
        blo, bhi = lo + t, hi - t
        blo[2], bhi[2] = z - SHELF_THICKNESS, z
        boards.append(Box.from_bounds(blo, bhi))
        levels.append(float(z))
    return boards, levels


def _burners(box: Box) -> list[Shape]:
    """Four hot plates on a stove's top, inside its box."""
    out = []
    r = float(min(box.half[0], box.half[1])) * 0.25
    for sx in (-1, 1):
        for sy in (-1, 1):
            c = box.center + np.array([sx * box.half[0] * 0.45, sy * box.half[1] * 0.45,
                                       box.half[2] - 0.006])
            out.append(Shape("cylinder", c, np.array([r, r, 0.006]), "black"))
    return out


def _enclosure(part: Part, node: Node, box: Box, home: _Home) -> bool:
    slabs, _ = _hollow(box, *home.front(node, box))
    part.boxes = [b for b in slabs if b.hi[2] < box.hi[2] - 1e-6 or b.half[2] > 0.1]
    part.shapes = _slab_shapes(part.boxes, "white")
    return True


def _seat_part(part: Part, node: Node, box: Box, home: _Home) -> bool:
    part.front = front = home.front(node, box)
    part.boxes = _seat(box, *front)
    part.shapes = home.model(node, box, front)
    return True


def _movable(part: Part, node: Node, box: Box, home: _Home) -> bool:
    part.movable = _flat(box, 0.01)
    room = home.graph.room_of(node.id) or 0
    variant = variant_of(node.class_name, home.seed, room)
    part.movable_shapes = local_model(node.class_name, node.category, part.movable.half,
                                      variant)
    return True


def _counter(part: Part, node: Node, box: Box, home: _Home) -> bool:
    """A counter: strips along the walls of its room when its box is an L or a U (see
    `homesim.render.counters`), each drawn as the counter model facing the room."""
    room = home.graph.room_of(node.id)
    tiles = home.tiles.get(room, []) if room is not None else []
    if not tiles:
        return _solid(part, node, box, home)
    room_lo = np.min([t.lo for t in tiles], axis=0)
    room_hi = np.max([t.hi for t in tiles], axis=0)
    for lo, hi, front in strips(box.lo, box.hi, room_lo, room_hi):
        strip = Box.from_bounds(lo, hi)
        part.boxes.append(strip)
        part.shapes += home.model(node, strip, front)
    part.front = home.front(node, box)
    return True


def _carve_counters(parts: list[Part], graph: EnvironmentGraph) -> None:
    """Cut each counter's shapes around the furniture and appliances standing in its box
    (a dishwasher under it, scene 5's table in the corner of its U), and each desk's
    below its top around what stands under it (a computer tower where the drawer block
    would be), so what stands there is drawn and can be reached."""
    boxes = {n.id: b for n in graph if (b := to_mujoco(n)) is not None}
    for part in parts:
        row = class_row(part.class_name)
        desk = row is not None and row.model == "desk"
        if (part.class_name not in COUNTERS and not desk) or part.node_id not in boxes:
            continue
        holes = _holes(part, parts, graph, boxes, desk)
        if holes:
            part.shapes = carve(part.shapes, holes)
            part.boxes = [Box((a + c) / 2, (c - a) / 2) for bx in part.boxes
                          for a, c in _box_pieces(bx, holes)]


BOOK_ROOM = (0.03, 0.03, 0.25)
"""Metres kept free of drawn books around a thing standing on a shelf (each side; above
it more, for the hand that takes it from above)."""


def _clear_shelves(parts: list[Part], graph: EnvironmentGraph) -> None:
    """Cut a shelf's drawn rows of books (`role` "books") around what stands on its
    shelves (a radio in a bookshelf stood inside a row of books, and the hand that
    turned it on with it)."""
    boxes = {n.id: b for n in graph if (b := to_mujoco(n)) is not None}
    for part in parts:
        if not any(s.role == "books" for s in part.shapes) or part.node_id not in boxes:
            continue
        sb = boxes[part.node_id]
        room = np.array(BOOK_ROOM)
        holes = [(b.lo - room * (1, 1, 0), b.hi + room) for n, b in boxes.items()
                 if n != part.node_id and np.all(np.abs(b.center - sb.center) < sb.half)
                 and np.all(b.half < sb.half) and not graph.node(n).is_room]
        if holes:
            books = carve([s for s in part.shapes if s.role == "books"], holes)
            part.shapes = [s for s in part.shapes if s.role != "books"] + books


def _holes(part: Part, parts: list[Part], graph: EnvironmentGraph, boxes: dict[int, Box],
           desk: bool) -> list[tuple[np.ndarray, np.ndarray]]:
    """(lo, hi) of what a counter (a desk: below its top, seats left out) is cut
    around: the furniture of its room standing at least half inside its box."""
    cb = boxes[part.node_id]
    room = graph.room_of(part.node_id)
    holes = []
    for other in parts:
        b = boxes.get(other.node_id)
        if (b is None or other is part or other.class_name in ("floor", "ceiling", "wall")
                or other.movable is not None or graph.room_of(other.node_id) != room):
            continue
        inside = np.prod(np.maximum(np.minimum(b.hi, cb.hi) - np.maximum(b.lo, cb.lo), 0))
        if not (inside >= 0.5 * np.prod(2 * b.half) and np.prod(2 * b.half) > 1e-3):
            continue
        if not desk:
            holes.append((b.lo - 0.01, b.hi + 0.01))
        elif (b.hi[2] < cb.hi[2] - DESK_TOP
              and SITTABLE not in graph.node(other.node_id).properties):
            holes.append(_through(cb, b.lo - 0.01, np.r_[b.hi[:2] + 0.01, cb.hi[2] - DESK_TOP]))
    return holes


def _through(outer: Box, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A desk's hole (lo, hi) opened right through each side face of `outer` it comes
    within `DESK_FACE` of: a drawer front drawn a little proud of the box would close it
    (scene 5's computer tower stood hidden behind one)."""
    lo, hi = lo.copy(), hi.copy()
    for axis in (0, 1):
        if lo[axis] - outer.lo[axis] < DESK_FACE:
            lo[axis] = outer.lo[axis] - 1.0
        if outer.hi[axis] - hi[axis] < DESK_FACE:
            hi[axis] = outer.hi[axis] + 1.0
    return lo, hi


def _box_pieces(box: Box, holes: list[tuple[np.ndarray, np.ndarray]]
                ) -> list[tuple[np.ndarray, np.ndarray]]:
    shapes = carve([Shape("box", box.center, box.half, "body")], holes)
    return [(s.center - s.half, s.center + s.half) for s in shapes]


def _solid(part: Part, node: Node, box: Box, home: _Home) -> bool:
    """The class's model; screens get their panel, lamps light."""
    part.boxes.append(_flat(box))
    kind = render_kind(node.class_name)
    front = _facing_seat(node, box, home) if kind == "screen" else home.front(node, box)
    part.front = front
    part.shapes = home.model(node, _flat(box), front)
    if kind == "screen":
        screen = next((s for s in part.shapes if s.role == "screen"), None)
        if screen is None:
            screen = _screen(box, front)
            part.shapes.append(screen)
        part.screen = Box(screen.center, screen.half)
    else:
        part.shapes = [s if s.role != "screen" else Shape(s.kind, s.center, s.half,
                                                         "screen_dark", s.axis)
                       for s in part.shapes]
    if kind in ("lamp", "room_lamp") or node.category == "Lamps":
        part.lamp = True
    return True


def _facing_seat(node: Node, box: Box, home: _Home) -> tuple[int, float]:
    """A screen faces the nearest sofa of its room (else the room's middle)."""
    room = home.graph.room_of(node.id)
    seats = [b for n in home.graph.nodes_of_class("sofa") if home.graph.room_of(n.id) == room
             and (b := to_mujoco(n)) is not None]
    if not seats:
        return home.front(node, box)
    seat = min(seats, key=lambda b: float(np.hypot(*(b.center[:2] - box.center[:2]))))
    return _front_axis(box, seat.center)


def _screen(box: Box, front: tuple[int, float]) -> Shape:
    """A thin panel on the front face, inside the box."""
    axis, sign = front
    c = box.center.copy()
    c[axis] += sign * (box.half[axis] - 0.004)
    half = box.half * 0.9
    half[axis] = 0.004
    return Shape("box", c, half, "screen")


_SHAPERS: dict[str, Shaper] = {
    "floor": _flat_part, "ceiling": _flat_part, "wall": _wall, "doorjamb": _doorjamb,
    "door": _door_part, "hinged": _hinged, "enclosure": _enclosure, "seat": _seat_part,
    "movable": _movable, "solid": _solid, "counter": _counter,
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
