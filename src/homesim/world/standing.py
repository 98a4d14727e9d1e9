"""Where the agent stands to interact with an object: free floor next to it.

The floor model is `homesim.world.floor`'s, the one the renderer walks on: the floor of a
room is the union of its floor tiles, obstacles are the boxes that reach into the agent's
body height, the agent is a square of side `AGENT_SIZE`, and the home's walkable floor is
the largest region of free floor joined through doorways.

A standing spot for an object is the first spot, on rings of growing distance around
the object's footprint, where the agent's square lies on the floor of the object's room,
overlaps no obstacle and is on the walkable floor (not in a pocket the agent cannot walk
into). Spots are (x, z) in metres (Unity frame, y up).
"""

from __future__ import annotations

import functools
import math
import random
import threading
import weakref
from collections.abc import Iterator
from typing import Any, cast

from homesim.world.floor import AGENT_SIZE, FloorModel, room_floor
from homesim.world.graph import BoundingBox, EnvironmentGraph

Spot = tuple[float, float]

__all__ = ["AGENT_SIZE", "FloorPlan", "Spot", "has_geometry", "note_prepared",
           "square_distance"]
_RINGS = (0.25, 0.45, 0.7, 1.0)
"""Distances (m) from the object's footprint edge to the agent's centre, tried in turn."""
_FLOOR_RINGS = (0.05, 0.2, 0.4, 0.6, 0.8, 1.0)
"""Distances (m) from an anchor's footprint at which a new object may stand on the floor."""
_DIRECTIONS = 16
_DOOR_CLEAR = 0.5
"""Metres: a new object's footprint stays this far from every doorway (a television
prepared on the floor before a door cut a room's floor in two)."""
_COMPOSITE = 2.5
"""A box wider than this (m) is taken for a composite piece (L-shaped counter or sofa)."""


def has_geometry(graph: EnvironmentGraph) -> bool:
    """Whether the home has boxes to stand and place on (its rooms have boxes)."""
    rooms = graph.rooms()
    return bool(rooms) and all(r.bounding_box is not None for r in rooms)


class FloorPlan:
    """Free floor per room of a home, built lazily, for choosing standing spots."""

    def __init__(self, graph: EnvironmentGraph, rotation: int = 0,
                 parent: FloorPlan | None = None, changed_rooms: frozenset[int] = frozenset()):
        """`rotation` (from the seed) picks which direction around an object is tried first.

        A plan for a prepared home may lean on the plan of the home it was prepared from
        (`parent`): rooms whose floor did not change share its obstacles and spots."""
        self.graph = graph
        self.rotation = rotation % _DIRECTIONS
        self._floors: dict[int, list[BoundingBox]] = {}
        self._obstacles: dict[int, list[BoundingBox]] = {}
        self._spots: dict[int, Spot | None] = {}
        self._parent = parent
        self._changed = changed_rooms
        self._rect_cache: dict[int, tuple[Any, tuple[list[_Rect], list[_Rect]]]] = {}
        self._model: FloorModel | None = None
        self._cached = False  # made by `_PlanCache` (for_graph)
        # A plan from `for_graph` is shared by threads: its lazy tables fill under a lock.
        self._lock = threading.RLock()

    @classmethod
    def for_graph(cls, graph: EnvironmentGraph, rotation: int = 0) -> FloorPlan:
        """The plan of a home, cached per home (see `_PlanCache`) and safe to share.

        Spots are computed once per home and rotation, not once per program: a home that
        `prepare` made says which home it came from and which rooms got new floor
        obstacles (`note_prepared`), and its plan asks the original's for everything else."""
        return _PLANS.plan(graph, rotation % _DIRECTIONS)

    def _room_parts(self, room: int) -> tuple[list[BoundingBox], list[BoundingBox]]:
        parent = self._parent
        if parent is not None and room not in self._changed:
            return parent._room_parts(room)
        with self._lock:
            return self._own_room_parts(room)

    def _own_room_parts(self, room: int) -> tuple[list[BoundingBox], list[BoundingBox]]:
        floors = self._floors.get(room)
        if floors is None:
            floors, obstacles = room_floor(self.graph, room)
            self._floors[room], self._obstacles[room] = floors, obstacles
        return floors, self._obstacles[room]

    def reachable(self, x: float, z: float) -> bool:
        """Whether (x, z) is on the home's walkable floor (`FloorModel`). A prepared home
        asks the home it was prepared from: the objects preparation adds are obstacles for
        `is_free`, and rarely change which floor can be walked to."""
        return self.model().reachable(x, z)

    def model(self) -> FloorModel:
        """The floor model on a grid (of the home this one was prepared from, if any)."""
        if self._parent is not None:
            return self._parent.model()
        if self._model is None:
            with self._lock:
                if self._model is None:
                    # A plan of one's own (preparation's, which adds obstacles) shares the
                    # model of the home's cached plan: the model depends on the graph only.
                    self._model = (FloorModel(self.graph) if self._cached
                                   else FloorPlan.for_graph(self.graph).model())
        return self._model

    def is_free(self, room: int, x: float, z: float, size_x: float = AGENT_SIZE,
                size_z: float = AGENT_SIZE, ignore: list[BoundingBox] | None = None) -> bool:
        """Whether a footprint (default: the agent's) centred at (x, z) lies on the room's
        free floor."""
        floors, obstacles = self._rects(room)
        hx, hz = size_x / 2, size_z / 2
        x0, x1, z0, z1 = x - hx, x + hx, z - hz, z + hz
        if not (math.isfinite(x0) and math.isfinite(x1) and math.isfinite(z0)
                and math.isfinite(z1)):
            return False  # huge boxes (1e308) overflow to inf: no spot there
        for cx, cz in ((x0, z0), (x0, z1), (x1, z0), (x1, z1)):
            for fx0, fx1, fz0, fz1, _ in floors:
                if fx0 <= cx <= fx1 and fz0 <= cz <= fz1:
                    break
            else:
                return False
        for ox0, ox1, oz0, oz1, box in obstacles:
            if x1 > ox0 and x0 < ox1 and z1 > oz0 and z0 < oz1:
                if ignore and any(box is i for i in ignore):
                    continue
                return False
        return True

    def _rects(self, room: int) -> tuple[list[_Rect], list[_Rect]]:
        """Floors and obstacles of a room as (x0, x1, z0, z1, box): is_free runs often."""
        floors, obstacles = self._room_parts(room)
        key = (id(floors), id(obstacles), len(obstacles))
        cached = self._rect_cache.get(room)
        if cached is None or cached[0] != key:
            cached = (key, ([_rect(b) for b in floors], [_rect(b) for b in obstacles]))
            self._rect_cache[room] = cached
        return cached[1]

    def free_floor(self, room: int, size_x: float, size_z: float,
                   rng: random.Random, tries: int = 64) -> Spot | None:
        """A random spot of the room where a footprint of this size fits, on the walkable
        floor (not in a pocket the agent could not walk to), or None."""
        floors, _ = self._room_parts(room)
        if not floors:
            return None
        for _ in range(tries):
            f = floors[rng.randrange(len(floors))]
            x = f.center[0] + rng.uniform(-0.5, 0.5) * f.size[0]
            z = f.center[2] + rng.uniform(-0.5, 0.5) * f.size[2]
            if (self.is_free(room, x, z, size_x, size_z) and self.reachable(x, z)
                    and not self._by_door(x, z, size_x, size_z)):
                return (x, z)
        return None

    def _by_door(self, x: float, z: float, size_x: float, size_z: float) -> bool:
        """Whether a footprint centred at (x, z) comes within `_DOOR_CLEAR` of a doorway."""
        for d in self._door_boxes:
            gx = abs(x - d.center[0]) - (size_x + d.size[0]) / 2
            gz = abs(z - d.center[2]) - (size_z + d.size[2]) / 2
            if max(gx, gz) < _DOOR_CLEAR:
                return True
        return False

    @functools.cached_property
    def _door_boxes(self) -> list[BoundingBox]:
        """The boxes of the home's doors and door jambs."""
        return [b for c in ("door", "doorjamb") for n in self.graph.nodes_of_class(c)
                if (b := n.bounding_box) is not None]

    def free_floor_near(self, room: int, box: BoundingBox, size_x: float,
                        size_z: float) -> Spot | None:
        """The nearest spot around `box` where a footprint of this size fits, on the
        walkable floor, or None."""
        for x, z in self._ring_spots(box, max(size_x, size_z), _FLOOR_RINGS):
            if (self.is_free(room, x, z, size_x, size_z) and self.reachable(x, z)
                    and not self._by_door(x, z, size_x, size_z)):
                return (x, z)
        return None

    def add_obstacle(self, room: int, box: BoundingBox) -> None:
        """Count a new object's box as an obstacle (scene preparation adds objects)."""
        self._room_parts(room)[1].append(box)
        self._spots.clear()

    def spot_near(self, node_id: int) -> Spot | None:
        """Free floor next to the object (cached), or None if there is none in its room."""
        spot = self._spots.get(node_id, _UNKNOWN)
        if spot is not _UNKNOWN:
            return spot
        with self._lock:
            return self._find_spot(node_id)

    def _find_spot(self, node_id: int) -> Spot | None:
        parent = self._parent
        if parent is not None and node_id in parent.graph.nodes:
            room = parent.graph.room_of(node_id)
            if room is not None and room not in self._changed:
                return parent.spot_near(node_id)
        spot = None
        g = self.graph
        node = g.nodes[node_id]
        room = g.room_of(node_id)
        box = node.bounding_box
        if room is not None and box is not None:
            if node_id == room:
                spot = self._room_spot(room, box)
            else:
                # A composite piece (an L-shaped counter) has a box far larger than itself
                # that covers the floor in front of what is built into it (a dishwasher):
                # near such a piece, its box does not block.
                skip = [o for o in self._room_parts(room)[1]
                        if max(o.size[0], o.size[2]) > _COMPOSITE
                        and abs(box.center[0] - o.center[0]) * 2 < o.size[0]
                        and abs(box.center[2] - o.center[2]) * 2 < o.size[2]]
                spot = next((s for s in self._ring_spots(box)
                             if self.is_free(room, *s, ignore=skip) and self.reachable(*s)),
                            None)
        self._spots[node_id] = spot
        return spot

    def _ring_spots(self, box: BoundingBox, width: float = AGENT_SIZE,
                    rings: tuple[float, ...] = _RINGS) -> Iterator[Spot]:
        hx, hz = box.size[0] / 2, box.size[2] / 2
        for ring in rings:
            for k in range(_DIRECTIONS):
                a = 2 * math.pi * ((k + self.rotation) % _DIRECTIONS) / _DIRECTIONS
                dx, dz = math.cos(a), math.sin(a)
                # Distance from the centre to the footprint's edge along (dx, dz).
                edge = min(hx / abs(dx) if abs(dx) > 1e-9 else math.inf,
                           hz / abs(dz) if abs(dz) > 1e-9 else math.inf)
                r = edge + width / 2 + ring
                yield (box.center[0] + r * dx, box.center[2] + r * dz)

    def _room_spot(self, room: int, box: BoundingBox) -> Spot | None:
        """For walking into a room: the free spot nearest the room's centre."""
        floors, _ = self._room_parts(room)
        cx, cz = box.center[0], box.center[2]
        candidates = []
        for f in floors:
            for fx in (-0.25, 0.0, 0.25):
                for fz in (-0.25, 0.0, 0.25):
                    candidates.append((f.center[0] + fx * f.size[0],
                                       f.center[2] + fz * f.size[2]))
        candidates.sort(key=lambda s: (square_distance((s[0], 0.0, s[1]), (cx, 0.0, cz)), s))
        return next((s for s in candidates if self.is_free(room, *s) and self.reachable(*s)),
                    None)


_Rect = tuple[float, float, float, float, BoundingBox]
_UNKNOWN: Any = object()


class _PlanCache:
    """Floor plans per home and rotation, and where prepared homes came from.

    The cache belongs to homesim.ground, not to the (read-only, shared) graphs: entries
    are keyed by the graph's id, held through a weak reference whose callback drops the
    entry when the graph goes away (before its id can be reused), and written under a
    lock, so threads that ground programs in one cached home share its plans.
    """

    def __init__(self) -> None:
        self._lock = threading.RLock()
        # id(graph) -> (weak reference to it, rotation -> plan, (base home, changed rooms))
        self._entries: dict[int, tuple[weakref.ref[EnvironmentGraph], dict[int, FloorPlan],
                                       list[tuple[EnvironmentGraph, frozenset[int]]]]] = {}

    def _entry(self, graph: EnvironmentGraph) -> tuple[
            dict[int, FloorPlan], list[tuple[EnvironmentGraph, frozenset[int]]]]:
        key = id(graph)
        entry = self._entries.get(key)
        if entry is None or entry[0]() is not graph:
            ref = weakref.ref(graph, functools.partial(self._forget, key))
            entry = self._entries[key] = (ref, {}, [])
        return entry[1], entry[2]

    def _forget(self, key: int, ref: weakref.ref[EnvironmentGraph]) -> None:
        """Drop the entry of a graph that went away (its weak reference calls this while the
        graph is freed, so its id is not reused yet)."""
        entry = self._entries.get(key)
        if entry is not None and entry[0] is ref:
            del self._entries[key]

    def plan(self, graph: EnvironmentGraph, rotation: int) -> FloorPlan:
        with self._lock:
            plans, origin = self._entry(graph)
            plan = plans.get(rotation)
            if plan is None:
                # The plan holds its graph weakly, or the entry would keep the graph alive.
                weak = cast(EnvironmentGraph, weakref.proxy(graph))
                if origin:
                    base, changed = origin[0]
                    plan = FloorPlan(weak, rotation, self.plan(base, rotation), changed)
                else:
                    plan = FloorPlan(weak, rotation)
                plan._cached = True
                plans[rotation] = plan
            return plan

    def note_prepared(self, prepared: EnvironmentGraph, base: EnvironmentGraph,
                      changed_rooms: frozenset[int]) -> None:
        with self._lock:
            plans, origin = self._entry(prepared)
            origin[:] = [(base, changed_rooms)]
            plans.clear()


_PLANS = _PlanCache()


def note_prepared(prepared: EnvironmentGraph, base: EnvironmentGraph,
                  changed_rooms: frozenset[int]) -> None:
    """Record that `prepare` made `prepared` from `base`, adding floor obstacles only in
    `changed_rooms`: the plans of `prepared` then reuse those of `base` for other rooms."""
    _PLANS.note_prepared(prepared, base, changed_rooms)


def square_distance(a: tuple[float, ...], b: tuple[float, ...]) -> float:
    """Squared distance in the floor plane (x, z) of two points (x, y, z); inf, not an
    OverflowError, for coordinates so large that the square overflows (``** 2`` raises)."""
    dx, dz = a[0] - b[0], a[2] - b[2]
    return dx * dx + dz * dz


def _rect(box: BoundingBox) -> _Rect:
    hx, hz = box.size[0] / 2, box.size[2] / 2
    return (box.center[0] - hx, box.center[0] + hx, box.center[2] - hz, box.center[2] + hz, box)
