"""Per-episode changes to a home: move some objects, and where the agent starts.

Both take a `random.Random` and return a new graph (graphs are read-only) plus a record of
what changed, which the episode's metadata keeps. Objects move only where the placement
knowledge base allows (``cup`` ON ``kitchen_counter``, INSIDE ``cabinet``...), onto free
room on the destination's box (`homesim.ground.placement.place_box`).
"""

from __future__ import annotations

import random
from dataclasses import dataclass

from homesim.ground.placement import place_box
from homesim.knowledge.kbtypes import ObjectKnowledge, class_names_for
from homesim.world.floor import FloorModel
from homesim.world.graph import BoundingBox, Edge, EnvironmentGraph, Node
from homesim.world.vocab import CLOSE, FACING, GRABBABLE, INSIDE, ON, S_CLOSED

_SUPPORT = (ON, INSIDE)


@dataclass(frozen=True)
class Move:
    """One object put somewhere else."""

    node_id: int
    class_name: str
    relation: str  # ON or INSIDE
    destination: int  # node id
    room: int

    def to_dict(self) -> dict[str, object]:
        return {"node_id": self.node_id, "class": self.class_name, "relation": self.relation,
                "destination": self.destination, "room": self.room}


def movable_objects(graph: EnvironmentGraph) -> list[int]:
    """Grabbable objects with a box, resting on or in furniture, holding nothing."""
    out = []
    rooms = graph.room_ids
    for node in graph:
        if GRABBABLE not in node.properties or node.bounding_box is None:
            continue
        supports = graph.targets(node.id, ON) | (graph.targets(node.id, INSIDE) - rooms)
        holds = graph.sources(node.id, ON) | graph.sources(node.id, INSIDE)
        if supports and not holds:
            out.append(node.id)
    return out


def _destinations(graph: EnvironmentGraph, node: Node, kb: ObjectKnowledge
                  ) -> list[tuple[int, str]]:
    """(destination node, relation) the knowledge base allows for the node's class."""
    out: list[tuple[int, str]] = []
    for name in class_names_for(node.class_name, kb):
        for p in kb.placements(name):
            for cls in class_names_for(p.destination, kb):
                out += [(d.id, p.relation) for d in graph.nodes_of_class(cls)
                        if d.id != node.id and d.bounding_box is not None
                        and S_CLOSED not in d.states and p.relation in _SUPPORT]
        if out:
            break
    return sorted(set(out))


class _Edit:
    """Nodes and edges of a graph being changed."""

    def __init__(self, graph: EnvironmentGraph):
        self.graph = graph
        self.nodes = dict(graph.nodes)
        self.edges: set[Edge] = set(graph.edges())

    def detach(self, node_id: int, relations: tuple[str, ...]) -> None:
        """Drop the node's outgoing edges of `relations` and every CLOSE edge at it."""
        self.edges = {e for e in self.edges if not (
            (e[0] == node_id and e[1] in relations) or (e[1] == CLOSE and node_id in (e[0], e[2])))}

    def set_box(self, node_id: int, box: BoundingBox) -> None:
        n = self.nodes[node_id]
        self.nodes[node_id] = Node(n.id, n.class_name, n.category, n.properties, n.states,
                                   n.prefab_name, box, n.extra)

    def others_at(self, dest: int, relation: str) -> list[BoundingBox]:
        return [b for e in self.edges if e[2] == dest and e[1] == relation
                if (b := self.nodes[e[0]].bounding_box) is not None]

    def build(self) -> EnvironmentGraph:
        return EnvironmentGraph(self.nodes.values(), sorted(self.edges), self.graph.meta)


def move_objects(graph: EnvironmentGraph, count: int, rng: random.Random,
                 kb: ObjectKnowledge) -> tuple[EnvironmentGraph, list[Move]]:
    """Move up to `count` movable objects to places the knowledge base allows."""
    edit = _Edit(graph)
    moves: list[Move] = []
    candidates = movable_objects(graph)
    rng.shuffle(candidates)
    for node_id in candidates:
        if len(moves) >= count:
            break
        move = _move_one(edit, graph.node(node_id), rng, kb)
        if move is not None:
            moves.append(move)
    return (edit.build() if moves else graph), moves


def _move_one(edit: _Edit, node: Node, rng: random.Random, kb: ObjectKnowledge) -> Move | None:
    options = _destinations(edit.graph, node, kb)
    box = node.bounding_box
    if not options or box is None:
        return None
    dest, relation = options[rng.randrange(len(options))]
    room = edit.graph.room_of(dest)
    dest_box = edit.nodes[dest].bounding_box
    if room is None or dest_box is None:
        return None
    new_box = place_box(box.size, dest_box, relation, edit.others_at(dest, relation), rng)
    if new_box is None:
        return None
    edit.detach(node.id, (ON, INSIDE, FACING))
    edit.set_box(node.id, new_box)
    edit.edges |= {(node.id, INSIDE, room), (node.id, relation, dest),
                   (node.id, CLOSE, dest), (dest, CLOSE, node.id)}
    return Move(node.id, node.class_name, relation, dest, room)


@dataclass(frozen=True)
class Start:
    """Where the agent starts: a room and a point of its free floor (Unity x, z)."""

    room: int
    x: float
    z: float

    def to_dict(self) -> dict[str, float | int]:
        return {"room": self.room, "x": self.x, "z": self.z}


def move_character(graph: EnvironmentGraph, rng: random.Random
                   ) -> tuple[EnvironmentGraph, Start | None]:
    """Stand the character on a random cell of a random room's walkable floor (the floor
    model's main part, `homesim.world.floor.FloorModel`: every room and object the
    renderer can walk to is reachable from there); None (home unchanged) when there is
    none."""
    char = graph.character_id
    if char is None or graph.node(char).bounding_box is None:
        return graph, None
    model = FloorModel(graph)
    runs = [r for r in model.main_runs() if r[3] >= 0]  # (row, first, last, room)
    rooms = sorted({r[3] for r in runs})
    if not rooms:
        return graph, None
    room = rng.choice(rooms)
    cells = [(i, j) for j, a, b, r in runs if r == room for i in range(a, b + 1)]
    x, z = model.point(*rng.choice(cells))
    return _place_character(graph, char, room, (x, z)), Start(room, x, z)


def _place_character(graph: EnvironmentGraph, char: int, room: int,
                     spot: tuple[float, float]) -> EnvironmentGraph:
    edit = _Edit(graph)
    box = graph.node(char).bounding_box
    assert box is not None  # checked by the caller
    edit.detach(char, (INSIDE, FACING))
    edit.set_box(char, BoundingBox((spot[0], box.center[1], spot[1]), box.size))
    edit.edges.add((char, INSIDE, room))
    return edit.build()
