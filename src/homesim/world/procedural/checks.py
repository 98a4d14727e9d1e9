"""Validity checks every generated home passes before it is returned or written.

- every node has a bounding box;
- no two pieces of furniture overlap (things standing on the floor or mounted on a wall
  or ceiling; rugs lie under furniture and are left out);
- every room can be reached on foot from every other, on the floor model that grounding
  and the renderer use (`homesim.world.floor`): rooms are joined by doors, every room has
  floor on the home's walkable floor, the character stands on it, and every piece of
  furniture has a standing spot on it (the spot grounding would choose);
- no room is reachable only through a bathroom (a bathroom is never the way between two
  other rooms);
- every object is supported: ON or INSIDE something other than a room;
- edges agree with the boxes (ON: resting on the top or hung on the face; INSIDE: the
  centre is in the box; CLOSE: the boxes are less than 1.5 m apart; BETWEEN: a door
  touches both rooms).
"""

from __future__ import annotations

import functools

import numpy as np

from homesim.world.graph import BoundingBox, EnvironmentGraph, Node
from homesim.world.procedural.geometry import Rect
from homesim.world.procedural.parts import Box3, gap3, overlap3

STRUCTURAL = frozenset({"Walls", "Floor", "Floors", "Ceiling", "Doors", "Windows"})
MOUNTS = frozenset({"floor", "wall", "ceiling"})
TOL = 0.02


def _box(n: Node) -> Box3:
    assert n.bounding_box is not None
    return _corners(n.bounding_box)


@functools.lru_cache(maxsize=8192)
def _corners(b: BoundingBox) -> Box3:
    c, s = b.center, b.size
    return (c[0] - s[0] / 2, c[1] - s[1] / 2, c[2] - s[2] / 2,
            c[0] + s[0] / 2, c[1] + s[1] / 2, c[2] + s[2] / 2)


def _fp(b: Box3) -> Rect:
    return (b[0], b[2], b[3], b[5])


def check_home(graph: EnvironmentGraph) -> list[str]:
    """Every problem found, one line each; an empty list for a valid home."""
    missing = [n.label() for n in graph if n.bounding_box is None]
    if missing:
        return [f"{missing[0]} has no bounding box"]
    problems: list[str] = []
    fixtures = _fixtures(graph)
    problems += _overlaps(graph, fixtures)
    problems += _support(graph)
    problems += _reachable(graph, fixtures)
    problems += _edges(graph)
    return problems


def _fixtures(graph: EnvironmentGraph) -> list[Node]:
    out = []
    for n in graph:
        if n.is_room or n.category in STRUCTURAL or n.category == "Characters":
            continue
        held = [graph.node(t) for r in ("ON", "INSIDE") for t in graph.targets(n.id, r)]
        if held and all(h.class_name in MOUNTS or h.is_room for h in held):
            out.append(n)
    return out


def _is_flat(n: Node) -> bool:
    return n.class_name == "rug" or _box(n)[4] - _box(n)[1] < 0.03


def _overlaps(graph: EnvironmentGraph, fixtures: list[Node]) -> list[str]:
    solid = [n for n in fixtures if not _is_flat(n)]
    if len(solid) < 2:
        return []
    boxes = np.array([_box(n) for n in solid])  # (n, 6)
    lo, hi = boxes[:, :3], boxes[:, 3:]
    depth = np.minimum(hi[:, None, :], hi[None, :, :]) - np.maximum(lo[:, None, :],
                                                                    lo[None, :, :])
    hit = np.triu((depth > TOL).all(axis=2), k=1)
    return [f"{solid[i].label()} overlaps {solid[j].label()}"
            for i, j in zip(*np.nonzero(hit), strict=True)]


def _support(graph: EnvironmentGraph) -> list[str]:
    out = []
    for n in graph:
        if n.is_room or n.category in STRUCTURAL or n.category == "Characters":
            continue
        held = [t for r in ("ON", "INSIDE") for t in graph.targets(n.id, r)
                if not graph.node(t).is_room]
        if not held:
            out.append(f"{n.label()} is not ON or INSIDE anything")
    return out


def _reachable(graph: EnvironmentGraph, fixtures: list[Node]) -> list[str]:
    """Rooms cut off from the rest, and fixtures the agent cannot walk to, on the floor
    model that grounding and the renderer use (`homesim.world.floor`)."""
    from homesim.world.standing import FloorPlan

    doors = [n for n in graph if n.class_name == "door"]
    out = _connected(graph, doors)
    out += through_bathroom(graph)
    plan = FloorPlan(graph)
    model = plan.model()
    on_main = model.rooms_on_main()
    out += [f"{graph.node(r).label()} cannot be reached on foot from the other rooms"
            for r in sorted(graph.room_ids - on_main)]
    char = graph.character_id
    if char is not None:
        c = graph.node(char).bounding_box
        assert c is not None
        if not model.reachable(c.center[0], c.center[2]):
            out.append(f"{graph.node(char).label()} stands off the walkable floor")
    out += [f"{n.label()} cannot be reached on foot (no free floor to stand at next to it)"
            for n in fixtures if plan.spot_near(n.id) is None]
    return out


def through_bathroom(graph: EnvironmentGraph) -> list[str]:
    """The rooms other than bathrooms that can be reached from the others only through a
    bathroom (doors joining rooms, bathrooms left out)."""
    rooms = {r for r in graph.room_ids if graph.node(r).class_name != "bathroom"}
    if not rooms:
        return []
    links: dict[int, set[int]] = {r: set() for r in rooms}
    for d in graph.nodes_of_class("door"):
        ends = [r for r in graph.targets(d.id, "BETWEEN") if r in rooms]
        if len(ends) == 2:
            links[ends[0]].add(ends[1])
            links[ends[1]].add(ends[0])
    seen, todo = set(), [min(rooms)]
    while todo:
        r = todo.pop()
        if r not in seen:
            seen.add(r)
            todo.extend(links[r] - seen)
    return [f"{graph.node(r).label()} can be reached only through a bathroom"
            for r in sorted(rooms - seen)]


def _door_groups(graph: EnvironmentGraph, doors: list[Node]) -> dict[int, set[int]]:
    """Each room mapped to the set of rooms joined to it through doors."""
    rooms = graph.room_ids
    joined = {r: {r} for r in rooms}
    for d in doors:
        ends = [r for r in graph.targets(d.id, "BETWEEN") if r in rooms]
        if len(ends) == 2:
            merged = joined[ends[0]] | joined[ends[1]]
            for r in merged:
                joined[r] = merged
    return joined


def _connected(graph: EnvironmentGraph, doors: list[Node]) -> list[str]:
    """A problem when some room has no door path from the first room."""
    rooms = graph.room_ids
    if not rooms:
        return []
    first = min(rooms)
    group = _door_groups(graph, doors)[first]
    if len(group) == len(rooms):
        return []
    lone = min(rooms - group)
    return [f"{graph.node(lone).label()} has no door path from {graph.node(first).label()}"]


def _edges(graph: EnvironmentGraph) -> list[str]:
    out = _close_edges(graph)
    others = (e for rel in ("ON", "INSIDE", "BETWEEN") for e in graph.edges(rel))
    for a, rel, b in others:
        na, nb = graph.node(a), graph.node(b)
        ba, bb = _box(na), _box(nb)
        bad = False
        if rel == "ON":
            if nb.class_name == "wall":
                bad = gap3(ba, bb) > TOL
            elif nb.class_name == "ceiling":
                bad = abs(ba[4] - bb[1]) > TOL
            else:
                bad = abs(ba[1] - bb[4]) > TOL or not overlap3(
                    (ba[0], 0, ba[2], ba[3], 1, ba[5]), (bb[0], 0, bb[2], bb[3], 1, bb[5]))
        elif rel == "INSIDE":
            c = [(ba[k] + ba[k + 3]) / 2 for k in range(3)]
            axes = (0, 2) if nb.is_room else (0, 1, 2)
            bad = any(not bb[k] - TOL <= c[k] <= bb[k + 3] + TOL for k in axes)
        elif rel == "BETWEEN":
            bad = gap3(ba, bb) > TOL
        if bad:
            out.append(f"edge {na.label()} {rel} {nb.label()} disagrees with their boxes")
            if len(out) >= 5:
                break
    return out


def _close_edges(graph: EnvironmentGraph) -> list[str]:
    """CLOSE edges whose boxes are 1.5 m apart or more (vectorised: most edges are CLOSE)."""
    pairs = list(graph.edges("CLOSE"))
    if not pairs:
        return []
    ids = sorted(graph.nodes)
    row = {nid: k for k, nid in enumerate(ids)}
    boxes = np.array([_box(graph.node(i)) for i in ids])  # (n, 6)
    a = boxes[[row[p[0]] for p in pairs]]
    b = boxes[[row[p[2]] for p in pairs]]
    gap = np.maximum(a[:, :3] - b[:, 3:], b[:, :3] - a[:, 3:]).max(axis=1)
    return [f"edge {graph.node(pairs[k][0]).label()} CLOSE {graph.node(pairs[k][2]).label()} "
            "disagrees with their boxes" for k in np.nonzero(gap >= 1.5 + 1e-6)[0][:5]]
