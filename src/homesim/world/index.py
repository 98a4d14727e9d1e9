"""`HomeIndex`: the fixed, shareable index of a home, built once with its graph.

MuJoCo keeps what the world is (the model) apart from its current state (the data). In
homesim the model is an `EnvironmentGraph` and its `HomeIndex`: nodes by id and class,
edges by relation in both directions, rooms, the acting character, body parts and
whether CLOSE is symmetric. The data is the `homesim.sim.state.SimState` overlay that a
run writes. An index is computed in full when its graph is built and never written after,
so any number of threads may read one home (e.g. a home cached by `load_home`) at once.

Caches kept per home (the floor plans of `homesim.world.standing`) live apart from the
index, keyed by the graph; nothing adds to an index once it is built.

Speed notes: the maps are plain dicts, not read-only proxies, because the simulator reads
them in its inner loop; they are never written once built. The edge index is built in one
pass that appends to lists and freezes them once, and CLOSE, symmetric in VirtualHome
homes, shares one map for both directions.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from homesim.world.node import Node
from homesim.world.vocab import BODY_PART, CHARACTER_CLASS, CLOSE, RELATIONS

Index = dict[str, dict[int, frozenset[int]]]
"""relation -> node id -> the ids at the other end."""


@dataclass(frozen=True, slots=True)
class HomeIndex:
    """What a home is, indexed for O(1) lookups; read-only and safe to share.

    Attributes:
        nodes: every node by id.
        out: relation -> node -> the nodes its edges of that relation point to.
        incoming: relation -> node -> the nodes whose edges point to it.
        by_class: class name -> ids of its nodes, in the order of `nodes`.
        rooms: ids of the room nodes.
        character: id of the acting character (the lowest-id ``character`` node), or None.
        body_parts: ids of the nodes with the ``BODY_PART`` property.
        close_symmetric: whether every CLOSE edge has its reverse (then ``out[CLOSE] is
            incoming[CLOSE]``).
    """

    nodes: dict[int, Node]
    out: Index
    incoming: Index
    by_class: Mapping[str, tuple[int, ...]]
    rooms: frozenset[int]
    character: int | None
    body_parts: frozenset[int]
    close_symmetric: bool

    @classmethod
    def build(cls, nodes: dict[int, Node], out: Index, incoming: Index) -> HomeIndex:
        """Index trusted nodes and edge maps (adopted, not copied)."""
        by_class: dict[str, list[int]] = {}
        rooms, parts = [], []
        for n in nodes.values():
            ids = by_class.get(n.class_name)
            if ids is None:
                by_class[n.class_name] = [n.id]
            else:
                ids.append(n.id)
            if n.is_room:
                rooms.append(n.id)
            if BODY_PART in n.properties:
                parts.append(n.id)
        symmetric = out[CLOSE] is incoming[CLOSE] or out[CLOSE] == incoming[CLOSE]
        if symmetric:
            incoming = {**incoming, CLOSE: out[CLOSE]}
        chars = by_class.get(CHARACTER_CLASS)
        return cls(nodes, out, incoming, {k: tuple(v) for k, v in by_class.items()},
                   frozenset(rooms), min(chars) if chars else None, frozenset(parts), symmetric)

    def derive(self, nodes: dict[int, Node], out: Index, incoming: Index,
               nodes_added: bool, close_symmetric: bool | None = None) -> HomeIndex:
        """The index of a home made from this one by changing states and edges, and adding
        nodes if `nodes_added` (the simulator's final graph): the class, room and body
        part tables are reused when no node was added. `close_symmetric` is what the
        caller knows (None: compare)."""
        if nodes_added:
            return HomeIndex.build(nodes, out, incoming)
        if close_symmetric is None:
            close_symmetric = out[CLOSE] == incoming[CLOSE]
        if close_symmetric and out[CLOSE] is not incoming[CLOSE]:
            incoming = {**incoming, CLOSE: out[CLOSE]}
        return HomeIndex(nodes, out, incoming, self.by_class, self.rooms, self.character,
                         self.body_parts, close_symmetric)


def index_edges(froms: Iterable[int], relations: Iterable[str],
                tos: Iterable[int]) -> tuple[Index, Index]:
    """The out and in maps of edges given as three parallel columns (trusted values)."""
    # defaultdict appends in C: about twice as fast as get-then-append on 14k edges.
    out: dict[str, defaultdict[int, list[int]]] = {r: defaultdict(list) for r in RELATIONS}
    inn: dict[str, defaultdict[int, list[int]]] = {r: defaultdict(list) for r in RELATIONS}
    for a, r, b in zip(froms, relations, tos, strict=True):
        out[r][a].append(b)
        inn[r][b].append(a)
    return _freeze(out), _freeze(inn)


def _freeze(ix: Mapping[str, Mapping[int, list[int]]]) -> Index:
    return {r: {k: frozenset(v) for k, v in m.items()} for r, m in ix.items()}
