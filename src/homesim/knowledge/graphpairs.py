"""Read many stored (initial, final) graph pairs that share most of their content.

Each real program ships its initial and final graph (``graphs/fileN.json``: 750 KB, about
290 nodes and 5,700 edges per graph). The 342 files of scene 1 are one home with a few
nodes and edges changed, so parsing each in full (JSON, validation, edge index: 0.1 s a
file) repeats the same work. `GraphPairReader` cuts a file in VirtualHome's canonical
layout into its node and edge records as bytes, parses each distinct record once across
files, and derives each home's edge index from the first one's by the records that
differ. A file in any other layout (other key order, other spacing, an edge record
spelled differently) is read the slow way, `EnvironmentGraph.from_dict`, so the answer
never depends on the path taken (`tests/knowledge/test_graphpairs.py` compares them).

`changed_objects` is EAI's list of a task's objects: the nodes whose fields or edges differ
between the two graphs.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from operator import itemgetter
from pathlib import Path
from typing import Any

import orjson

from homesim.errors import DataError, GraphError
from homesim.world.graph import (
    Edge,
    EnvironmentGraph,
    Node,
    _check_characters,
    _node_from_dict,
    _parse_json,
)
from homesim.world.index import HomeIndex, Index, index_edges
from homesim.world.vocab import RELATIONS

Objects = frozenset[tuple[str, int]]
"""(class name, node id) pairs."""

_EMPTY: frozenset[int] = frozenset()
_HEAD = b'{"init_graph": {"nodes": [{"id": '
_EDGES = b'}], "edges": [{'
_FINAL = b'}]}, "final_graph": {"nodes": [{"id": '
_TAIL = b'}]}}'
_NODE_SEP = b'}, {"id": '
_EDGE_SEP = b"}, {"
_EDGE = re.compile(rb'"from_id": (\d{1,18}), "relation_type": "([A-Z_]{1,40})", '
                   rb'"to_id": (\d{1,18})')


class _Slow(Exception):
    """This file takes the slow path."""


@dataclass(frozen=True)
class _Sections:
    """A file's node and edge records as bytes (a node's text after ``{"id": `` up to its
    closing brace; an edge's text inside its braces)."""

    init_nodes: list[bytes]
    init_edges: list[bytes]
    final_nodes: list[bytes]
    final_edges: list[bytes]


@dataclass(frozen=True)
class _Base:
    """The first home read: its edge records and index, from which the others derive."""

    edges: frozenset[bytes]
    out: Index
    incoming: Index
    ids: frozenset[int]


def _sections(raw: bytes) -> _Sections | None:
    """The records of a file in the canonical layout; None for any other layout.

    The separators hold an unescaped quote, so they never occur inside a JSON string;
    every record is parsed or matched later, so a file whose structure differs anyway
    (a nested list cut apart) fails there and takes the slow path."""
    body = raw.rstrip()
    if not (body.startswith(_HEAD) and body.endswith(_TAIL)):
        return None
    i = body.find(_EDGES)
    j = body.find(_FINAL, i + 1)
    k = body.find(_EDGES, j + 1)
    if not len(_HEAD) <= i < j < k:
        return None
    return _Sections(body[len(_HEAD):i].split(_NODE_SEP), body[i + len(_EDGES):j].split(_EDGE_SEP),
                     body[j + len(_FINAL):k].split(_NODE_SEP),
                     body[k + len(_EDGES):len(body) - len(_TAIL)].split(_EDGE_SEP))


class GraphPairReader:
    """Reads stored graph pairs, sharing parsed records and the edge index between them.

    Nodes and edge sets are immutable, so the homes it returns share them safely.
    """

    def __init__(self) -> None:
        self._nodes: dict[bytes, tuple[Node, dict[str, Any]]] = {}
        self._edges: dict[bytes, Edge] = {}
        self._base: _Base | None = None

    def read(self, path: Path) -> tuple[EnvironmentGraph, Objects]:
        """The initial graph of the pair in `path` and its `changed_objects`.

        `DataError` when the file cannot be read or parsed, `GraphError` when the graph is
        malformed (both name the file)."""
        try:
            raw = path.read_bytes()
        except OSError as e:
            raise DataError(f"{path}: cannot read stored graphs ({e.strerror})") from None
        sections = _sections(raw)
        if sections is not None:
            try:
                return self._fast(sections, f"{path}:init_graph: ")
            except _Slow:
                pass
        return _slow(raw, path)

    # ------------------------------------------------------------ the fast path
    def _node(self, record: bytes) -> tuple[Node, dict[str, Any]]:
        hit = self._nodes.get(record)
        if hit is None:
            try:
                data = orjson.loads(b'{"id": ' + record + b"}")
                hit = (_node_from_dict(data, "", 0), data)
            except (orjson.JSONDecodeError, GraphError):
                raise _Slow from None
            self._nodes[record] = hit
        return hit

    def _edge(self, record: bytes) -> Edge:
        hit = self._edges.get(record)
        if hit is None:
            m = _EDGE.fullmatch(record)
            if m is None or m[2].decode() not in RELATIONS:
                raise _Slow
            hit = (int(m[1]), m[2].decode(), int(m[3]))
            self._edges[record] = hit
        return hit

    def _fast(self, s: _Sections, where: str) -> tuple[EnvironmentGraph, Objects]:
        nodes = {}
        for record in s.init_nodes:
            node = self._node(record)[0]
            nodes[node.id] = node
        if len(nodes) != len(s.init_nodes):
            raise _Slow  # a duplicate id: from_dict names it
        edges = set(s.init_edges)
        base = self._base or self._make_base(edges, nodes)
        out, incoming = self._derive(base, edges, nodes)
        index = HomeIndex.build(nodes, out, incoming)
        _check_characters(index, where)
        return EnvironmentGraph.from_index(index), self._changed(s, nodes, edges)

    def _make_base(self, edges: set[bytes], nodes: Mapping[int, Node]) -> _Base:
        columns = list(zip(*map(self._edge, edges), strict=True)) or [(), (), ()]
        if not nodes.keys() >= {*columns[0], *columns[2]}:
            raise _Slow
        out, incoming = index_edges(*columns)
        self._base = _Base(frozenset(edges), out, incoming, frozenset(nodes))
        return self._base

    def _derive(self, base: _Base, edges: set[bytes], nodes: Mapping[int, Node]
                ) -> tuple[Index, Index]:
        """The base's edge index with this home's different edges taken out and put in."""
        out, incoming = dict(base.out), dict(base.incoming)
        copied: set[tuple[int, str]] = set()
        for records, add in ((base.edges - edges, False), (edges - base.edges, True)):
            for record in records:
                a, r, b = self._edge(record)
                if add and (a not in nodes or b not in nodes):
                    raise _Slow
                _edit(out, base.out, (0, r), copied, a, b, add)
                _edit(incoming, base.incoming, (1, r), copied, b, a, add)
        for gone in base.ids - nodes.keys():  # a base node this home lacks: no edges left
            if any(out[r].get(gone) or incoming[r].get(gone) for r in RELATIONS):
                raise _Slow
        return out, incoming

    def _changed(self, s: _Sections, nodes: Mapping[int, Node], edges: set[bytes]) -> Objects:
        """`changed_objects` from the records that differ between the two graphs."""
        init_records, final_records = set(s.init_nodes), set(s.final_nodes)
        before = {n.id: d for n, d in map(self._node, init_records - final_records)}
        after = {n.id: d for n, d in map(self._node, final_records - init_records)}
        names = {n.id: n.class_name for n, _ in map(self._node, s.final_nodes)}
        if len(names) != len(s.final_nodes):
            raise _Slow  # a duplicate id in the final graph
        ids = nodes.keys() ^ names.keys()
        ids.update(i for i in before.keys() & after.keys() if _differ(before[i], after[i]))
        for record in edges.symmetric_difference(s.final_edges):
            a, _, b = self._edge(record)
            ids |= {a, b}
        names.update({i: n.class_name for i, n in nodes.items()})
        return frozenset((names[i], i) for i in ids if i in names)


def _edit(index: Index, base: Index, key: tuple[int, str], copied: set[tuple[int, str]],
          a: int, b: int, add: bool) -> None:
    """Add or take out ``a -r-> b`` in `index`, copying the relation's map from `base` on
    its first change."""
    r = key[1]
    if key not in copied:
        index[r] = dict(base[r])
        copied.add(key)
    targets = index[r].get(a, _EMPTY)
    targets = targets | {b} if add else targets - {b}
    if targets:
        index[r][a] = targets
    else:
        index[r].pop(a, None)


# ------------------------------------------------------------ the slow path
def _slow(raw: bytes, path: Path) -> tuple[EnvironmentGraph, Objects]:
    try:
        data = _parse_json(raw)
        init, final = data["init_graph"], data["final_graph"]
        objects = changed_objects(init, final)
    except (ValueError, KeyError, TypeError, RecursionError) as e:
        raise DataError(f"{path}: cannot read stored graphs ({e})") from None
    return EnvironmentGraph.from_dict(init, f"{path}:init_graph"), objects


def changed_objects(init: dict, final: dict) -> Objects:
    """(class name, id) of the nodes whose dict or edges differ between two graph dicts
    (state and property lists compared as sets, as EAI sorts them first)."""
    edge = itemgetter("from_id", "relation_type", "to_id")
    before = {n["id"]: n for n in init["nodes"]}
    after = {n["id"]: n for n in final["nodes"]}
    ids = before.keys() ^ after.keys()
    for node_id, a in before.items():
        b = after.get(node_id)
        if b is not None and a != b and _differ(a, b):
            ids.add(node_id)
    for x, _, y in set(map(edge, init["edges"])) ^ set(map(edge, final["edges"])):
        ids |= {x, y}
    names = {i: n["class_name"] for i, n in after.items()}
    names.update({i: n["class_name"] for i, n in before.items()})
    return frozenset((names[i], i) for i in ids if i in names)


def _differ(a: dict, b: dict) -> bool:
    lists = ("states", "properties")
    if any(set(a.get(k, ())) != set(b.get(k, ())) for k in lists):
        return True
    return {k: v for k, v in a.items() if k not in lists} != {
        k: v for k, v in b.items() if k not in lists}
