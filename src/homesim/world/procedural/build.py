"""Turn placed parts into an `EnvironmentGraph`: nodes with boxes, and edges from
geometry (INSIDE, ON, CLOSE, FACING, BETWEEN) as in the built-in homes."""

from __future__ import annotations

from typing import Any

import numpy as np

from homesim.world.graph import EnvironmentGraph
from homesim.world.procedural.parts import Part
from homesim.world.procedural.stats import class_info, room_class

CLOSE_GAP = 1.5
"""Boxes nearer than this (m) are CLOSE (fitted: the built-in homes' CLOSE pairs)."""
FACING_RANGE = 5.0
LOOKED_AT = frozenset({"tv", "computer", "wallpictureframe", "clock"})
"""What things FACE in the built-in homes."""
STRUCTURE = {"wall": ("Walls", "PRE_WAL_WAL_Wall_01"), "floor": ("Floor", "Floor"),
             "ceiling": ("Ceiling", "PRE_CEI_Tile_01"), "door": ("Doors", "PRE_DOO_Door_01"),
             "doorjamb": ("Doors", "PRE_DOO_Doorjamb_01"),
             "window": ("Windows", "PRE_Window_01")}


def to_graph(parts: list[Part], meta: dict[str, Any]) -> EnvironmentGraph:
    """Nodes numbered 1.. in part order; edges computed from the boxes."""
    nodes, edges = [], set()
    for k, p in enumerate(parts):
        nodes.append(_node(k + 1, p))
        if p.kind == "room":
            continue
        edges.add((k + 1, "INSIDE", p.room + 1))
        if p.support:
            edges.add((k + 1, p.support[1], p.support[0] + 1))
        for r in p.between:
            edges.add((k + 1, "BETWEEN", r + 1))
    edges |= _close_and_facing(parts)
    graph = {"nodes": nodes, "edges": [{"from_id": a, "relation_type": r, "to_id": b}
                                       for a, r, b in sorted(edges)], **meta}
    return EnvironmentGraph.from_dict(graph)


def _node(nid: int, p: Part) -> dict[str, Any]:
    b = p.box
    box = {"center": [round((b[0] + b[3]) / 2, 4), round((b[1] + b[4]) / 2, 4),
                      round((b[2] + b[5]) / 2, 4)],
           "size": [round(b[3] - b[0], 4), round(b[4] - b[1], 4), round(b[5] - b[2], 4)]}
    if p.kind == "room":
        cls = room_class(p.cls)
        return {"id": nid, "class_name": cls, "category": "Rooms", "properties": [],
                "states": [], "prefab_name": f"PROC_ROOM_{p.cls}", "bounding_box": box}
    if p.kind == "character":
        return {"id": nid, "class_name": "character", "category": "Characters",
                "properties": [], "states": [], "prefab_name": "Male1", "bounding_box": box}
    if p.cls in STRUCTURE:
        category, prefab = STRUCTURE[p.cls]
        props = ["CAN_OPEN"] if p.cls == "door" else []
        return {"id": nid, "class_name": p.cls, "category": category, "properties": props,
                "states": list(p.states), "prefab_name": prefab, "bounding_box": box}
    info = class_info(p.cls)
    return {"id": nid, "class_name": p.cls, "category": info["category"],
            "properties": info["properties"], "states": list(p.states),
            "prefab_name": info["prefab"], "bounding_box": box}


def _close_and_facing(parts: list[Part]) -> set[tuple[int, str, int]]:
    edges: set[tuple[int, str, int]] = set()
    by_room: dict[int, list[int]] = {}
    for k, p in enumerate(parts):
        if p.kind != "room":
            by_room.setdefault(p.room, []).append(k)
    for ks in by_room.values():
        boxes = np.array([parts[k].box for k in ks])  # (n, 6)
        lo, hi = boxes[:, :3], boxes[:, 3:]
        gap = np.maximum(lo[:, None, :] - hi[None, :, :], lo[None, :, :] - hi[:, None, :])
        near = gap.max(axis=2) < CLOSE_GAP  # (n, n)
        np.fill_diagonal(near, False)
        ids = (np.array(ks) + 1).tolist()
        edges.update((ids[i], "CLOSE", ids[j]) for i, j in zip(*np.nonzero(near), strict=True))
        centre = (lo + hi) / 2
        for j, k in enumerate(ks):
            p = parts[k]
            if p.cls not in LOOKED_AT or p.normal is None:
                continue
            d = centre[:, [0, 2]] - centre[j, [0, 2]]
            dist = np.hypot(d[:, 0], d[:, 1])
            ahead = d @ np.array(p.normal)
            for i in np.nonzero((dist < FACING_RANGE) & (ahead > 0.3 * dist))[0]:
                if ks[i] != k:
                    edges.add((ks[i] + 1, "FACING", k + 1))
    return edges
