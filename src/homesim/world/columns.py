"""Column files: the built-in homes in a layout that loads in a few milliseconds.

A VirtualHome graph is JSON with one object per node and per edge; scene1 has 14k edges,
and parsing and checking 14k little dicts is most of the 13 ms its JSON takes to load. The
built-in homes therefore also ship as *column files* (``<name>.columns.json.gz``, written
by ``tools/pack_homes.py`` from the VirtualHome JSON): gzip-compressed JSON holding

- ``nodes``: one list per field (``id``, ``class_name``, ``category``, ``properties``,
  ``states``, ``prefab_name``, ``center``, ``size``; boxes as null where a node has none)
  and ``extra``: the uninterpreted keys of node ``i`` under ``"i"``;
- ``out`` and ``in``: the edge index itself, per relation ``[from ids, [to ids of each]]``
  (``in`` the other way round, without CLOSE when ``close_symmetric``: CLOSE goes both
  ways in VirtualHome homes and one map serves both directions, as in `HomeIndex`);
- ``meta``: the graph's other top-level keys; ``format`` and ``version``.

Loading builds the `HomeIndex` straight from these lists (C-level ``dict(zip(...))`` and
``frozenset``), with no per-edge Python work. The files are trusted: only their shape is
checked when read, while a test checks that every column file gives exactly the graph
its JSON gives under full validation. User files keep the VirtualHome JSON loader.
"""

from __future__ import annotations

import gzip
import zlib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import orjson

from homesim.errors import GraphError, excerpt
from homesim.files import write_bytes
from homesim.world.graph import BoundingBox, EnvironmentGraph, Node
from homesim.world.index import HomeIndex, Index
from homesim.world.vocab import CLOSE, RELATIONS

FORMAT = "homesim-home-columns"
VERSION = 1
SUFFIX = ".columns.json.gz"
"""File name ending of a column file (``scene1.columns.json.gz``)."""

_NODE_FIELDS = ("id", "class_name", "category", "properties", "states", "prefab_name",
                "center", "size")


def to_columns(graph: EnvironmentGraph) -> dict[str, Any]:
    """The graph as a column document (sorted where order is free: same graph, same bytes)."""
    index = graph.index
    incoming = {r: m for r, m in index.incoming.items()
                if not (r == CLOSE and index.close_symmetric)}
    return {
        "format": FORMAT,
        "version": VERSION,
        "nodes": _node_columns(list(graph.nodes.values())),
        "out": _adjacency(index.out),
        "in": _adjacency(incoming),
        "close_symmetric": index.close_symmetric,
        "meta": dict(graph.meta),
    }


def _node_columns(nodes: list[Node]) -> dict[str, Any]:
    boxes = [n.bounding_box for n in nodes]
    return {
        "id": [n.id for n in nodes],
        "class_name": [n.class_name for n in nodes],
        "category": [n.category for n in nodes],
        "properties": [sorted(n.properties) for n in nodes],
        "states": [sorted(n.states) for n in nodes],
        "prefab_name": [n.prefab_name for n in nodes],
        "center": [list(b.center) if b else None for b in boxes],
        "size": [list(b.size) if b else None for b in boxes],
        "extra": {str(i): dict(n.extra) for i, n in enumerate(nodes) if n.extra},
    }


def _adjacency(index: Mapping[str, Mapping[int, frozenset[int]]]) -> dict[str, Any]:
    return {r: [sorted(index[r]), [sorted(index[r][k]) for k in sorted(index[r])]]
            for r in sorted(index) if index[r]}


def from_columns(data: Any, source: str) -> EnvironmentGraph:
    """The graph of a column document; `GraphError` naming `source` if it is malformed."""
    try:
        if data["format"] != FORMAT or data["version"] != VERSION:
            raise ValueError(f"format {data['format']!r:.40} version {data['version']!r:.10}, "
                             f"expected {FORMAT!r} version {VERSION}")
        nodes = _nodes(data["nodes"])
        out, incoming = _index(data["out"]), _index(data["in"])
        if data["close_symmetric"]:
            incoming[CLOSE] = out[CLOSE]
        graph = EnvironmentGraph.from_index(HomeIndex.build(nodes, out, incoming),
                                            data["meta"])
    except (KeyError, TypeError, ValueError) as e:
        raise GraphError(f"{source}: not a valid home column file ({excerpt(repr(e))}); "
                         "rewrite it with tools/pack_homes.py") from None
    if graph.character_id is None:
        raise GraphError(f"{source}: the home has no character node")
    return graph


def _nodes(cols: Mapping[str, Any]) -> dict[int, Node]:
    ids = cols["id"]
    if any(len(cols[f]) != len(ids) for f in _NODE_FIELDS):
        raise ValueError("node columns of different lengths")
    boxes = [None if c is None else BoundingBox(tuple(c), tuple(s))
             for c, s in zip(cols["center"], cols["size"], strict=True)]
    extras: list[dict[str, Any] | None] = [None] * len(ids)
    for i, extra in cols["extra"].items():
        extras[int(i)] = extra
    nodes = {n.id: n for n in map(Node, ids, cols["class_name"], cols["category"],
                                   map(frozenset, cols["properties"]),
                                   map(frozenset, cols["states"]), cols["prefab_name"],
                                   boxes, extras)}
    if len(nodes) != len(ids):
        raise ValueError("duplicate node ids")
    return nodes


def _index(adjacency: Mapping[str, list[Any]]) -> Index:
    index: Index = {r: {} for r in RELATIONS}
    for relation, (keys, values) in adjacency.items():
        if relation not in index or len(keys) != len(values):
            raise ValueError(f"bad relation {relation!r:.40} or its lists")
        index[relation] = dict(zip(keys, map(frozenset, values), strict=True))
    return index


def read_columns(path: str | Path) -> EnvironmentGraph:
    """Load a column file (trusted: the built-in homes); errors name the file."""
    path = Path(path)
    try:
        data = orjson.loads(gzip.decompress(path.read_bytes()))
    except (OSError, EOFError, zlib.error, orjson.JSONDecodeError) as e:
        raise GraphError(f"{path}: cannot read home column file ({excerpt(str(e))})") from None
    return from_columns(data, str(path))


def write_columns(graph: EnvironmentGraph, path: str | Path) -> None:
    """Write the graph as a column file (atomically; same graph, same bytes)."""
    write_bytes(Path(path), gzip.compress(orjson.dumps(to_columns(graph)), mtime=0))
