"""Convert the VirtualHome apartments of ../shared/data into homesim's built-in homes.

Each scene is validated by `EnvironmentGraph.from_dict` and written, canonically sorted
and gzip-compressed, to src/homesim/world/builtin/<name>.json.gz. Where the character's
INSIDE edge names another room than the one its box is in (scene1: bathroom 1, with its
box and CLOSE edges in bedroom 67), the edge is moved to the room of the box, and the fix
is printed. Door boxes are VirtualHome placeholders (0.93 x 0.93 x 1.0 m at the floor);
each becomes the box of its door's swing in its door frame (`homesim.world.doors`: the
closed leaf between the posts, as tall as the opening, and the leaf open at a right angle
on the side the placeholder lies), so the rendered door, open or closed, stays in its
graph box. Then the column files `load_home` reads are written from the JSON
(`tools/pack_homes.py`). Run from the repo root:

    python tools/convert_homes.py [../shared/data/virtualhome/scenes]
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from homesim.world.doors import door_swing
from homesim.world.graph import BoundingBox, EnvironmentGraph
from homesim.world.homes import character_room_problem, rooms_holding_box
from homesim.world.vocab import INSIDE
from pack_homes import pack_all  # tools/ is on the path when this script runs

OUT = Path(__file__).resolve().parents[1] / "src" / "homesim" / "world" / "builtin"


def main(scenes: Path) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    for path in sorted(scenes.glob("scene*.json")):
        graph = fix_character_room(EnvironmentGraph.load(path), path.name)
        graph = fix_door_boxes(graph, path.name)
        target = OUT / (path.stem + ".json.gz")
        graph.save(target)
        print(f"{path.name}: {len(graph)} nodes, {graph.num_edges()} edges -> {target.name} "
              f"({target.stat().st_size // 1024} KiB)")
    pack_all(OUT)


def fix_character_room(graph: EnvironmentGraph, name: str) -> EnvironmentGraph:
    """The graph with the character INSIDE the room its box is in, if its edge says other."""
    problem = character_room_problem(graph)
    if problem is None:
        return graph
    char = graph.character_id
    assert char is not None
    room = rooms_holding_box(graph, char)[0]
    edges = [e for e in graph.edges() if not (e[0] == char and e[1] == INSIDE
                                              and e[2] in graph.room_ids)]
    print(f"{name}: fixed: {problem}; now INSIDE {graph.node(room).label()}")
    return EnvironmentGraph(graph.nodes.values(), [*edges, (char, INSIDE, room)], graph.meta)


def fix_door_boxes(graph: EnvironmentGraph, name: str) -> EnvironmentGraph:
    """The graph with each door's box set to the box of its swing in its nearest door
    frame (`homesim.world.doors.door_swing`), opening to the side VirtualHome's
    placeholder box lies on."""
    jambs = [n.bounding_box for n in graph.nodes_of_class("doorjamb")
             if n.bounding_box is not None]
    fixed = 0
    nodes = []
    for node in graph.nodes.values():
        box = node.bounding_box if node.class_name == "door" else None
        if box is not None and jambs:
            jamb = min(jambs, key=lambda j: float(np.hypot(j.center[0] - box.center[0],
                                                           j.center[2] - box.center[2])))
            swing = door_swing(jamb, (box.center[0], box.center[2]))
            node = replace(node, bounding_box=BoundingBox(
                tuple(round(float(c), 4) for c in swing.center),
                tuple(round(float(c), 4) for c in swing.size)))
            fixed += 1
        nodes.append(node)
    if not fixed:
        return graph
    print(f"{name}: {fixed} door boxes set to the boxes of their swings")
    return EnvironmentGraph(nodes, list(graph.edges()), graph.meta)


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "../shared/data/virtualhome/scenes"))
