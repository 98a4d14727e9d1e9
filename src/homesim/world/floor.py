"""The floor model of a home: where the agent may stand and walk.

One model for everything that puts the agent on the floor: grounding chooses standing
spots with it (`homesim.world.standing`), the renderer walks the agent on its raster
(`homesim.world.walkgrid`, used by `homesim.render.navigation`), and generated homes are
checked against that raster (`homesim.world.procedural.checks`).

- The floor of a room is the union of its floor tiles (the room's box when it has none).
- Obstacles of a room are the nodes INSIDE it whose boxes reach into the agent's body
  height (`BODY_LOW` to `BODY_HIGH`), apart from rooms, floors, ceilings, walls, doors,
  windows and characters. Walls are left out: the floor tiles already end where the walls
  stand, and the corner pieces of VirtualHome's apartments are 2.5 m cubes that cover
  floor that is free.
- The agent is a square of side `AGENT_SIZE`. It may stand at (x, z) in a room when the
  square's corners lie on the room's floor and the square overlaps no obstacle of the room.
- Rooms join at doorways (door and doorjamb boxes): there the agent may cross the wall,
  its square inside the opening.

Pure Python (grounding needs no numpy); coordinates are the Unity frame's (x, z), metres.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from homesim.limits import MAX_COORD, MAX_SIZE
from homesim.world.graph import BoundingBox, EnvironmentGraph, Node
from homesim.world.vocab import CHARACTER_CLASS, INSIDE

AGENT_SIZE = 0.4
"""Side (m) of the agent's square footprint."""
BODY_LOW, BODY_HIGH = 0.1, 1.5
"""Boxes lower than this (rugs) or starting above that (shelves on walls) do not block."""
NOT_OBSTACLES = frozenset({"Rooms", "Floor", "Floors", "Ceiling", "Walls", "Doors",
                           "Characters", "Windows"})
"""Categories that never stand in the agent's way."""
DOORWAY_CLASSES = frozenset({"door", "doorjamb"})

Rect = tuple[float, float, float, float]
"""A footprint ``(x0, z0, x1, z1)`` on the floor."""


def is_obstacle(node: Node) -> bool:
    """Whether a node's box stands in the agent's way (it reaches into body height)."""
    box = node.bounding_box
    if box is None or node.category in NOT_OBSTACLES or node.class_name == CHARACTER_CLASS:
        return False
    return (box.center[1] + box.size[1] / 2 > BODY_LOW
            and box.center[1] - box.size[1] / 2 < BODY_HIGH)


def room_floor(graph: EnvironmentGraph, room: int
               ) -> tuple[list[BoundingBox], list[BoundingBox]]:
    """The floor tiles and the obstacles of a room (its box stands in for missing tiles)."""
    floors: list[BoundingBox] = []
    obstacles: list[BoundingBox] = []
    for nid in contents(graph, room):
        node = graph.nodes[nid]
        box = node.bounding_box
        if box is None:
            continue
        if node.class_name == "floor":
            floors.append(box)
        elif is_obstacle(node):
            obstacles.append(box)
    room_box = graph.nodes[room].bounding_box
    if not floors and room_box is not None:
        floors = [room_box]
    return floors, obstacles


def footprint(box: BoundingBox) -> Rect:
    """A box's rectangle on the floor."""
    hx, hz = box.size[0] / 2, box.size[2] / 2
    return (box.center[0] - hx, box.center[2] - hz, box.center[0] + hx, box.center[2] + hz)


def doorways(graph: EnvironmentGraph) -> list[Rect]:
    """Footprints of the openings between rooms: every door frame, and every door with no
    frame at its place (its footprint within 0.3 m of none)."""
    jambs = [footprint(n.bounding_box) for n in graph.nodes_of_class("doorjamb")
             if n.bounding_box is not None]
    out = list(jambs)
    for door in graph.nodes_of_class("door"):
        if door.bounding_box is None:
            continue
        d = footprint(door.bounding_box)
        if not any(min(d[2], j[2]) - max(d[0], j[0]) > -0.3
                   and min(d[3], j[3]) - max(d[1], j[1]) > -0.3 for j in jambs):
            out.append(d)
    return sorted(out)


def contents(graph: EnvironmentGraph, room: int) -> Iterator[int]:
    """Ids of the nodes directly INSIDE a room."""
    return iter(graph.sources(room, INSIDE))


CELL = 0.1
"""Side (m) of a cell of `FloorModel`'s rows."""
PASSAGE_DEPTH = 0.6
"""How far (m) a doorway's passage reaches into each room from the opening's middle."""

Interval = tuple[float, float]
Run = tuple[int, int, int, int]
"""Free cells of one row: (row j, first cell i, last cell i, room id or -1 in a doorway)."""


class FloorModel:
    """The floor model on a grid: the free cells of a home, in runs along x per row.

    A cell is free when the agent may stand at its centre (its square on the floor of a
    room, clear of that room's obstacles), or when the centre lies in a doorway's passage
    (the opening narrowed so that the square fits, `PASSAGE_DEPTH` into both rooms) and
    the square there overlaps no obstacle. Free cells that share a side are joined; the
    largest group of joined cells is the home's walkable floor (`main`): cells apart from
    it are pockets (between a bed and a wall, say) that the agent cannot walk into.
    Cell (i, j) is centred at ``origin + (i, j) * cell``.
    """

    def __init__(self, graph: EnvironmentGraph, cell: float = CELL):
        self.cell = cell
        rooms = sorted(r.id for r in graph.rooms() if r.bounding_box is not None)
        parts = {r: room_floor(graph, r) for r in rooms}
        tiles = {r: [f for f in map(footprint, parts[r][0]) if _sane(f)] for r in rooms}
        x0, z0, x1, z1 = _bounds([t for ts in tiles.values() for t in ts])
        self.origin = (x0 + cell / 2, z0 + cell / 2)
        self.shape = (int((x1 - x0) / cell) + 1, int((z1 - z0) / cell) + 1)
        runs: list[Run] = []
        for r in rooms:
            if tiles[r]:
                runs += self._room_runs(r, tiles[r], [footprint(b) for b in parts[r][1]])
        every = [footprint(b) for _, obstacles in parts.values() for b in obstacles]
        room_rects = [footprint(box) for r in rooms if (box := graph.nodes[r].bounding_box)]
        for way in doorways(graph):
            runs += self._passage_runs(way, every, room_rects)
        self.runs = sorted(runs)
        self.labels = _label(self.runs)
        self.main = _largest(self.runs, self.labels)
        self._main_rows: dict[int, list[tuple[int, int]]] = {}
        for j, a, b, _ in self.main_runs():
            self._main_rows.setdefault(j, []).append((a, b))

    # -- queries --------------------------------------------------------------------
    def index(self, x: float, z: float) -> tuple[int, int]:
        """The cell whose centre is nearest to (x, z); a point off the grid gets a cell
        just off it."""
        (ox, oz), c, (nx, nz) = self.origin, self.cell, self.shape
        i = (x - ox) / c if math.isfinite(x) else math.copysign(nx + 2, x)
        j = (z - oz) / c if math.isfinite(z) else math.copysign(nz + 2, z)
        return (round(min(max(i, -2.0), nx + 1.0)), round(min(max(j, -2.0), nz + 1.0)))

    def point(self, i: int, j: int) -> tuple[float, float]:
        return (self.origin[0] + i * self.cell, self.origin[1] + j * self.cell)

    def walkable(self, i: int, j: int) -> bool:
        """Whether cell (i, j) is on the home's walkable floor (`main`)."""
        return any(a <= i <= b for a, b in self._main_rows.get(j, ()))

    def reachable(self, x: float, z: float) -> bool:
        """Whether (x, z) is on the walkable floor, or a cell away from it (a spot between
        cell centres)."""
        i, j = self.index(x, z)
        return any(a <= i + 1 and i - 1 <= b for jj in (j - 1, j, j + 1)
                   for a, b in self._main_rows.get(jj, ()))

    def main_runs(self) -> list[Run]:
        """The runs of the walkable floor."""
        return [r for r, label in zip(self.runs, self.labels, strict=True)
                if label == self.main]

    def rooms_on_main(self) -> set[int]:
        """Rooms with some of their floor on the walkable floor."""
        return {r[3] for r in self.main_runs() if r[3] >= 0}

    # -- building -------------------------------------------------------------------
    def _rows(self, z_lo: float, z_hi: float) -> range:
        """Rows whose centre lies in [z_lo, z_hi]."""
        oz, c, n = self.origin[1], self.cell, self.shape[1]
        return range(_ceil(_clip((z_lo - oz) / c, n)), _floor(_clip((z_hi - oz) / c, n)) + 1)

    def _cells(self, j: int, room: int, free: list[Interval]) -> list[Run]:
        ox, c = self.origin[0], self.cell
        out = []
        for lo, hi in free:
            n = self.shape[0]
            a, b = _ceil(_clip((lo - ox) / c, n)), _floor(_clip((hi - ox) / c, n))
            if a <= b:
                out.append((j, a, b, room))
        return out

    def _room_runs(self, room: int, floors: list[Rect], obstacles: list[Rect]) -> list[Run]:
        h = AGENT_SIZE / 2
        out: list[Run] = []
        for j in self._rows(min(f[1] for f in floors) + h, max(f[3] for f in floors) - h):
            z = self.origin[1] + j * self.cell
            rim = _intersect(_spans(floors, z - h), _spans(floors, z + h))
            free = [(max(a1 + h, a2 - h), min(b1 + h, b2 - h))
                    for a1, b1 in rim for a2, b2 in rim]
            free = _merge([f for f in free if f[0] <= f[1]])
            out += self._cells(j, room, _subtract(free, _blocking(obstacles, z)))
        return out

    def _passage_runs(self, way: Rect, obstacles: list[Rect], rooms: list[Rect]) -> list[Run]:
        h = AGENT_SIZE / 2
        x0, z0, x1, z1 = way
        if x1 - x0 >= z1 - z0:  # the opening runs along x
            mid = (z0 + z1) / 2
            rect = (x0 + h, mid - PASSAGE_DEPTH, x1 - h, mid + PASSAGE_DEPTH)
        else:
            mid = (x0 + x1) / 2
            rect = (mid - PASSAGE_DEPTH, z0 + h, mid + PASSAGE_DEPTH, z1 - h)
        out: list[Run] = []
        for j in self._rows(rect[1], rect[3]):
            z = self.origin[1] + j * self.cell
            inside = _intersect([(rect[0], rect[2])], _spans(rooms, z))
            out += self._cells(j, -1, _subtract(inside, _blocking(obstacles, z)))
        return out


def _bounds(rects: list[Rect]) -> Rect:
    """The rectangle around some rectangles (a point at the origin for none)."""
    if not rects:
        return (0.0, 0.0, 0.0, 0.0)
    return (min(r[0] for r in rects), min(r[1] for r in rects), max(r[2] for r in rects),
            max(r[3] for r in rects))


def _sane(r: Rect) -> bool:
    """Whether a floor rectangle can be gridded (huge boxes of hand-made homes cannot)."""
    return all(abs(v) <= MAX_COORD + MAX_SIZE for v in r)


def _clip(v: float, n: int) -> float:
    """A cell coordinate clipped to the grid's cells 0..n-1 (inf and huge values too)."""
    return min(max(v, 0.0), n - 1.0)


def _ceil(v: float) -> int:
    return math.ceil(v - 1e-9)


def _floor(v: float) -> int:
    return math.floor(v + 1e-9)


def _spans(rects: list[Rect], z: float) -> list[Interval]:
    """The x intervals of the rectangles that contain row z (closed), merged."""
    return _merge([(r[0], r[2]) for r in rects if r[1] <= z <= r[3]])


def _blocking(obstacles: list[Rect], z: float) -> list[Interval]:
    """Open x intervals where the agent's square on row z overlaps an obstacle."""
    h = AGENT_SIZE / 2
    return [(o[0] - h, o[2] + h) for o in obstacles if o[1] - h < z < o[3] + h]


def _merge(spans: list[Interval]) -> list[Interval]:
    out: list[Interval] = []
    for a, b in sorted(spans):
        if out and a <= out[-1][1] + 1e-9:
            out[-1] = (out[-1][0], max(out[-1][1], b))
        else:
            out.append((a, b))
    return out


def _intersect(p: list[Interval], q: list[Interval]) -> list[Interval]:
    out = [(max(a, c), min(b, d)) for a, b in p for c, d in q]
    return [s for s in out if s[0] <= s[1]]


def _subtract(free: list[Interval], cuts: list[Interval]) -> list[Interval]:
    """Closed intervals less open ones (their end points stay free)."""
    for ca, cb in cuts:
        out = []
        for a, b in free:
            if cb <= a or ca >= b:
                out.append((a, b))
                continue
            if a <= ca:
                out.append((a, ca))
            if cb <= b:
                out.append((cb, b))
        free = out
    return free


def _label(runs: list[Run]) -> list[int]:
    """Group label of each run (sorted by row, then first cell): runs of a row that share
    or touch a cell, and runs of neighbouring rows that overlap, are joined (union-find)."""
    parent = list(range(len(runs)))

    def find(k: int) -> int:
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    rows: dict[int, list[int]] = {}
    for k, run in enumerate(runs):
        rows.setdefault(run[0], []).append(k)
    for j, ks in rows.items():
        for other, touch in ((ks, 1), (rows.get(j + 1, []), 0)):
            for a in ks:
                for b in other:
                    if (b > a and runs[a][1] <= runs[b][2] + touch
                            and runs[b][1] <= runs[a][2] + touch):
                        parent[find(a)] = find(b)
    return [find(k) for k in range(len(runs))]


def _largest(runs: list[Run], labels: list[int]) -> int:
    """The label with the most cells (the lowest label on ties); -1 without runs."""
    size: dict[int, int] = {}
    for run, label in zip(runs, labels, strict=True):
        size[label] = size.get(label, 0) + run[2] - run[1] + 1
    return min(size, key=lambda k: (-size[k], k)) if size else -1
