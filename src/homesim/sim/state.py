"""`SimState`: what a program changes, as a small overlay on a read-only graph.

The base `EnvironmentGraph` is never written. The state keeps, per relation, the edge
sets of the nodes it has touched (copied on first write), the states of the nodes it has
changed, the nodes it has added and the simulator's memory (where each held object was
taken from). Every write is appended to a journal, which serves three uses: the per-step
changes of a trace, `undo` for backtracking search, and building the final graph.

Speed notes: lookups are two dict gets (relation, node); nothing is copied per step; a
node's edge set is copied once, on its first change.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from homesim.errors import ExecutionError
from homesim.world.graph import EnvironmentGraph, Node, room_of
from homesim.world.vocab import BODY_PART, CLOSE, INSIDE, RELATIONS

_EMPTY: frozenset[int] = frozenset()

# Journal entry kinds.
ADD_EDGE = 0
DEL_EDGE = 1
SET_STATES = 2
ADD_NODE = 3
SET_MEMORY = 4
DEL_OUT = 5  # (DEL_OUT, node, relation, ids): edges node -> each id removed at once
DEL_IN = 6  # (DEL_IN, node, relation, ids): edges each id -> node removed at once


@dataclass(frozen=True, slots=True)
class Changes:
    """What one step (or a whole run) changed.

    Attributes:
        added: edges added, as (from_id, relation, to_id).
        removed: edges removed.
        states: (node id, states before, states after) for each node whose states changed.
        nodes: ids of nodes added to the home.
    """

    added: tuple[tuple[int, str, int], ...] = ()
    removed: tuple[tuple[int, str, int], ...] = ()
    states: tuple[tuple[int, frozenset[str], frozenset[str]], ...] = ()
    nodes: tuple[int, ...] = ()

    def __bool__(self) -> bool:
        return bool(self.added or self.removed or self.states or self.nodes)

    def describe(self, label: Callable[[int], str], all_close: bool = False) -> str:
        """One line for people: ``tv 410: OFF → ON; +character 1 ON sofa 352; -2 CLOSE``.

        CLOSE edges are counted unless `all_close`; ``no change`` when there is none.
        """
        parts = []
        for node, before, after in self.states:
            gone = ",".join(sorted(before - after)) or "-"
            new = ",".join(sorted(after - before)) or "-"
            parts.append(f"{label(node)}: {gone} → {new}")
        for sign, edges in (("+", self.added), ("-", self.removed)):
            shown = [e for e in edges if all_close or e[1] != CLOSE]
            parts += [f"{sign}{label(a)} {r} {label(b)}" for a, r, b in shown]
            if len(edges) > len(shown):
                parts.append(f"{sign}{len(edges) - len(shown)} CLOSE")
        parts += [f"added {label(n)}" for n in self.nodes]
        return "; ".join(parts) or "no change"

    def to_dict(self) -> dict[str, Any]:
        """JSON view: edges as [from, relation, to]; states as {node, before, after}."""
        return {
            "added": [list(e) for e in self.added],
            "removed": [list(e) for e in self.removed],
            "states": [{"node": n, "before": sorted(a), "after": sorted(b)}
                       for n, a, b in self.states],
            "nodes": list(self.nodes),
        }


class SimState:
    """The evolving state of one execution on top of a base graph."""

    __slots__ = ("_base_in", "_base_nodes", "_base_out", "_in", "_new_nodes", "_out",
                 "_states", "body_parts", "char", "graph", "journal", "memory", "rooms")

    # Writes keep both indexes right. When a relation shares one overlay for both
    # directions (CLOSE, see __init__), writing a -> b also writes b -> a, and the
    # journal records both edges.

    def __init__(self, graph: EnvironmentGraph):
        char = graph.character_id
        if char is None:
            raise ExecutionError("the graph has no character node (class 'character')")
        self.graph = graph
        self.char = char
        index = graph.index  # the fixed home, never written (homesim.world.index)
        self._base_nodes = index.nodes
        self._base_out = index.out
        self._base_in = index.incoming
        self._out: dict[str, dict[int, set[int]]] = {r: {} for r in RELATIONS}
        self._in: dict[str, dict[int, set[int]]] = {r: {} for r in RELATIONS}
        if index.close_symmetric:
            # CLOSE is symmetric in VirtualHome graphs and every effect keeps it so: one
            # shared overlay serves both directions and halves the work of a walk.
            self._in[CLOSE] = self._out[CLOSE]
        self._states: dict[int, frozenset[str]] = {}
        self._new_nodes: dict[int, Node] = {}
        self.memory: dict[int, tuple[int, str]] = {}
        self.journal: list[tuple[Any, ...]] = []
        self.rooms = index.rooms
        self.body_parts = index.body_parts

    # ----------------------------------------------------------------- reading
    def __contains__(self, node_id: int) -> bool:
        return node_id in self._base_nodes or node_id in self._new_nodes

    def node(self, node_id: int) -> Node:
        """The node as it is now (with its current states)."""
        node = self._new_nodes.get(node_id) or self._base_nodes[node_id]
        states = self._states.get(node_id)
        return node if states is None else node.with_states(states)

    def class_name(self, node_id: int) -> str:
        node = self._base_nodes.get(node_id) or self._new_nodes[node_id]
        return node.class_name

    def properties(self, node_id: int) -> frozenset[str]:
        node = self._base_nodes.get(node_id) or self._new_nodes[node_id]
        return node.properties

    def states(self, node_id: int) -> frozenset[str]:
        states = self._states.get(node_id)
        if states is None:
            node = self._base_nodes.get(node_id) or self._new_nodes[node_id]
            return node.states
        return states

    def label(self, node_id: int) -> str:
        """Name for messages: ``fridge 9``, or ``the character``."""
        if node_id == self.char:
            return "the character"
        return f"{self.class_name(node_id)} {node_id}"

    def targets(self, node_id: int, relation: str) -> frozenset[int] | set[int]:
        """Ids `x` with ``node_id -relation-> x`` now. Do not modify the result."""
        s = self._out[relation].get(node_id)
        return self._base_out[relation].get(node_id, _EMPTY) if s is None else s

    def sources(self, node_id: int, relation: str) -> frozenset[int] | set[int]:
        """Ids `x` with ``x -relation-> node_id`` now. Do not modify the result."""
        s = self._in[relation].get(node_id)
        return self._base_in[relation].get(node_id, _EMPTY) if s is None else s

    def has_edge(self, a: int, relation: str, b: int) -> bool:
        return b in self.targets(a, relation)

    def room_of(self, node_id: int) -> int | None:
        """The room a node is in now (see `homesim.world.graph.room_of`)."""
        rooms = self.rooms
        if node_id in rooms:
            return node_id
        inside: set[int] | frozenset[int] | None = self._out[INSIDE].get(node_id)
        if inside is None:
            inside = self._base_out[INSIDE].get(node_id, _EMPTY)
        if len(inside) == 1:  # fast path: directly inside one room
            for x in inside:
                if x in rooms:
                    return x
        return room_of(node_id, rooms, lambda n: self.targets(n, INSIDE))

    # ----------------------------------------------------------------- writing
    def add_edge(self, a: int, relation: str, b: int) -> None:
        out = self._out[relation]
        s = out.get(a)
        if s is None:
            s = out[a] = set(self._base_out[relation].get(a, _EMPTY))
        if b in s:
            return
        s.add(b)
        inn = self._in[relation]
        t = inn.get(b)
        if t is None:
            t = inn[b] = set(self._base_in[relation].get(b, _EMPTY))
        t.add(a)
        self.journal.append((ADD_EDGE, a, relation, b))
        if inn is out and a != b:
            self.journal.append((ADD_EDGE, b, relation, a))

    def remove_edge(self, a: int, relation: str, b: int) -> None:
        out = self._out[relation]
        s = out.get(a)
        if s is None:
            base = self._base_out[relation].get(a, _EMPTY)
            if b not in base:
                return
            s = out[a] = set(base)
        elif b not in s:
            return
        s.discard(b)
        inn = self._in[relation]
        t = inn.get(b)
        if t is None:
            t = inn[b] = set(self._base_in[relation].get(b, _EMPTY))
        t.discard(a)
        self.journal.append((DEL_EDGE, a, relation, b))
        if inn is out and a != b:
            self.journal.append((DEL_EDGE, b, relation, a))

    def add_pair(self, a: int, relation: str, b: int) -> None:
        """Add the edge both ways (CLOSE is symmetric); no self-loops."""
        if a == b:
            return
        self.add_edge(a, relation, b)
        if self._in[relation] is not self._out[relation]:
            self.add_edge(b, relation, a)

    def detach(self, node_id: int, relations: Iterable[str]) -> None:
        """Remove every edge of these relations that starts or ends at `node_id`."""
        # Bulk version of remove_edge, journaled as one entry per direction: it runs on
        # every walk, the hottest step.
        journal = self.journal
        for r in relations:
            out, inn = self._out[r], self._in[r]
            mine: set[int] | frozenset[int] | None = out.get(node_id)
            if mine is None:
                mine = self._base_out[r].get(node_id)
            if mine:
                base_in = self._base_in[r]
                ids = tuple(mine)
                out[node_id] = set()
                for x in ids:
                    t = inn.get(x)
                    if t is None:
                        t = inn[x] = set(base_in[x])
                    t.discard(node_id)
                journal.append((DEL_OUT, node_id, r, ids))
                if inn is out:  # the shared overlay removed the reverse edges too
                    if node_id in mine:
                        ids = tuple(x for x in ids if x != node_id)
                    journal.append((DEL_IN, node_id, r, ids))
                    continue
            theirs: set[int] | frozenset[int] | None = inn.get(node_id)
            if theirs is None:
                theirs = self._base_in[r].get(node_id)
            if theirs:
                base_out = self._base_out[r]
                ids = tuple(theirs)
                inn[node_id] = set()
                for x in ids:
                    t = out.get(x)
                    if t is None:
                        t = out[x] = set(base_out[x])
                    t.discard(node_id)
                journal.append((DEL_IN, node_id, r, ids))

    def set_states(self, node_id: int, states: frozenset[str]) -> None:
        old = self.states(node_id)
        if old != states:
            self._states[node_id] = states
            self.journal.append((SET_STATES, node_id, old, states))

    def swap_state(self, node_id: int, remove: str, add: str) -> None:
        """Replace one state by another (``CLOSED`` -> ``OPEN``)."""
        self.set_states(node_id, (self.states(node_id) - {remove}) | {add})

    def remember(self, node_id: int, value: tuple[int, str] | None) -> None:
        """Set (or clear, with None) where a held object was taken from."""
        old = self.memory.get(node_id)
        if old == value:
            return
        if value is None:
            del self.memory[node_id]
        else:
            self.memory[node_id] = value
        self.journal.append((SET_MEMORY, node_id, old, value))

    def add_node(self, node: Node) -> None:
        """Add a new node (scene preparation); its id must be unused."""
        if node.id in self:
            raise ExecutionError(f"cannot add node {node.id}: the id is taken")
        self._new_nodes[node.id] = node
        if BODY_PART in node.properties:
            self.body_parts = self.body_parts | {node.id}
        self.journal.append((ADD_NODE, node.id))

    def next_node_id(self) -> int:
        """An id above every node of the home."""
        return max(max(self._base_nodes, default=0), max(self._new_nodes, default=0)) + 1

    # ----------------------------------------------------------------- journal
    def mark(self) -> int:
        """A position in the journal to `undo` back to or to read `changes_since`."""
        return len(self.journal)

    def undo(self, mark: int) -> None:
        """Revert every change made after `mark`."""
        journal = self.journal
        while len(journal) > mark:
            entry = journal.pop()
            kind = entry[0]
            if kind == ADD_EDGE:
                _, a, r, b = entry
                self._out[r][a].discard(b)
                self._in[r][b].discard(a)
            elif kind == DEL_EDGE:
                _, a, r, b = entry
                self._out[r][a].add(b)
                self._in[r][b].add(a)
            elif kind == DEL_OUT:
                _, a, r, ids = entry
                self._out[r][a].update(ids)
                for b in ids:
                    self._in[r][b].add(a)
            elif kind == DEL_IN:
                _, b, r, ids = entry
                self._in[r][b].update(ids)
                for a in ids:
                    self._out[r][a].add(b)
            elif kind == SET_STATES:
                self._states[entry[1]] = entry[2]
            elif kind == SET_MEMORY:
                if entry[2] is None:
                    self.memory.pop(entry[1], None)
                else:
                    self.memory[entry[1]] = entry[2]
            elif kind == ADD_NODE:
                node = self._new_nodes.pop(entry[1])
                if BODY_PART in node.properties:
                    self.body_parts = self.body_parts - {node.id}

    def changes_since(self, mark: int) -> Changes:
        """The net changes made after `mark` (an edge added then removed is no change)."""
        edges: dict[tuple[int, str, int], int] = {}
        states: dict[int, list[frozenset[str]]] = {}
        nodes: list[int] = []
        for entry in self.journal[mark:]:
            kind = entry[0]
            if kind in (ADD_EDGE, DEL_EDGE):
                key = entry[1:]
                edges[key] = edges.get(key, 0) + (1 if kind == ADD_EDGE else -1)
            elif kind in (DEL_OUT, DEL_IN):
                _, n, r, ids = entry
                for x in ids:
                    key = (n, r, x) if kind == DEL_OUT else (x, r, n)
                    edges[key] = edges.get(key, 0) - 1
            elif kind == SET_STATES:
                states.setdefault(entry[1], [entry[2], entry[3]])[1] = entry[3]
            elif kind == ADD_NODE:
                nodes.append(entry[1])
        return Changes(
            added=tuple(k for k, v in edges.items() if v > 0),
            removed=tuple(k for k, v in edges.items() if v < 0),
            states=tuple((n, a, b) for n, (a, b) in states.items() if a != b),
            nodes=tuple(nodes),
        )

    # ----------------------------------------------------------------- output
    def to_graph(self) -> EnvironmentGraph:
        """The graph as it is now, as a new read-only `EnvironmentGraph`."""
        base = self.graph
        nodes = dict(self._base_nodes)
        nodes.update(self._new_nodes)
        for node_id, states in self._states.items():
            nodes[node_id] = nodes[node_id].with_states(states)

        def merge(base_ix: dict[str, dict[int, frozenset[int]]],
                  overlay: dict[str, dict[int, set[int]]],
                  skip: str | None = None) -> dict[str, dict[int, frozenset[int]]]:
            merged = {}
            for r, base_map in base_ix.items():
                touched = overlay[r]
                if not touched or r == skip:
                    merged[r] = base_map  # shared: graphs are read-only
                    continue
                m = dict(base_map)
                for k, v in touched.items():
                    if v:
                        m[k] = frozenset(v)
                    else:
                        m.pop(k, None)
                merged[r] = m
            return merged

        index = base.index
        out = merge(index.out, self._out)
        # A shared CLOSE overlay kept CLOSE symmetric (see __init__): share the result too.
        symmetric = self._in[CLOSE] is self._out[CLOSE]
        inn = merge(index.incoming, self._in, skip=CLOSE if symmetric else None)
        if symmetric:
            inn[CLOSE] = out[CLOSE]
        return EnvironmentGraph.from_index(
            index.derive(nodes, out, inn, bool(self._new_nodes), symmetric or None), base.meta)
