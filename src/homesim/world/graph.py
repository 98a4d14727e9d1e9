"""`EnvironmentGraph`: a home as nodes (objects, rooms, the character) and typed edges.

The format is VirtualHome's JSON: ``{"nodes": [{id, class_name, category, properties,
states, prefab_name, bounding_box}], "edges": [{from_id, relation_type, to_id}]}``.

A graph is read-only once built: it is validated once at the edge (`from_dict`, `load`)
and then indexed by id, by class and by relation in both directions, so the simulator can
trust it and look things up in O(1). Executing a program never changes a graph; it yields
a new one.
"""

from __future__ import annotations

import gzip
import json
import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from homesim.errors import GraphError
from homesim.limits import MAX_GRAPH_BYTES
from homesim.world.vocab import CHARACTER_CLASS, INSIDE, RELATIONS, ROOM_CATEGORY

_EMPTY: frozenset[int] = frozenset()
_NODE_KEYS = ("id", "class_name", "category", "properties", "states", "prefab_name",
              "bounding_box")


@dataclass(frozen=True, slots=True)
class BoundingBox:
    """An axis-aligned box in metres, in the Unity frame (y up)."""

    center: tuple[float, float, float]
    size: tuple[float, float, float]

    def to_dict(self) -> dict[str, list[float]]:
        return {"center": list(self.center), "size": list(self.size)}


@dataclass(frozen=True, slots=True)
class Node:
    """One object, room or character of a home."""

    id: int
    class_name: str
    category: str | None = None
    properties: frozenset[str] = frozenset()
    states: frozenset[str] = frozenset()
    prefab_name: str | None = None
    bounding_box: BoundingBox | None = None
    extra: Mapping[str, Any] | None = field(default=None, compare=False, hash=False)
    """Keys of the JSON node that homesim does not interpret, kept for saving."""

    @property
    def is_room(self) -> bool:
        return self.category == ROOM_CATEGORY

    def label(self) -> str:
        """Human name used in messages: ``fridge 9``."""
        return f"{self.class_name} {self.id}"

    def with_states(self, states: frozenset[str]) -> Node:
        return Node(self.id, self.class_name, self.category, self.properties, states,
                    self.prefab_name, self.bounding_box, self.extra)

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {
            "id": self.id,
            "class_name": self.class_name,
            "category": self.category,
            "properties": sorted(self.properties),
            "states": sorted(self.states),
            "prefab_name": self.prefab_name,
            "bounding_box": self.bounding_box.to_dict() if self.bounding_box else None,
        }
        if self.extra:
            d.update(self.extra)
        return d


Edge = tuple[int, str, int]
"""An edge as (from_id, relation, to_id)."""

Index = dict[str, dict[int, frozenset[int]]]
"""relation -> node id -> the ids at the other end."""


def _index(edges: Iterable[Edge]) -> tuple[Index, Index]:
    out: dict[str, dict[int, set[int]]] = {r: {} for r in RELATIONS}
    inn: dict[str, dict[int, set[int]]] = {r: {} for r in RELATIONS}
    for a, r, b in edges:
        out[r].setdefault(a, set()).add(b)
        inn[r].setdefault(b, set()).add(a)

    def freeze(ix: dict[str, dict[int, set[int]]]) -> Index:
        return {r: {k: frozenset(v) for k, v in m.items()} for r, m in ix.items()}

    return freeze(out), freeze(inn)


class EnvironmentGraph:
    """A home: nodes indexed by id and class, edges indexed by relation both ways.

    >>> g = EnvironmentGraph.from_dict({
    ...     "nodes": [{"id": 1, "class_name": "kitchen", "category": "Rooms"},
    ...               {"id": 2, "class_name": "character"},
    ...               {"id": 3, "class_name": "fridge", "states": ["CLOSED"]}],
    ...     "edges": [{"from_id": 2, "relation_type": "INSIDE", "to_id": 1},
    ...               {"from_id": 3, "relation_type": "INSIDE", "to_id": 1}]})
    >>> g.node(3).label(), sorted(g.sources(1, "INSIDE")), g.room_of(3)
    ('fridge 3', [2, 3], 1)
    """

    __slots__ = ("_by_class", "_character", "_derived", "_in", "_meta", "_nodes", "_out", "_rooms")

    def __init__(self, nodes: Iterable[Node], edges: Iterable[Edge],
                 meta: Mapping[str, Any] | None = None):
        """Build from trusted parts; use `from_dict` or `load` for outside data."""
        node_map = {n.id: n for n in nodes}
        out, inn = _index(edges)
        self._init(node_map, out, inn, dict(meta or {}))

    def _init(self, nodes: dict[int, Node], out: Index, inn: Index,
              meta: dict[str, Any]) -> None:
        self._nodes = nodes
        self._out = out
        self._in = inn
        self._meta = meta
        by_class: dict[str, list[int]] = {}
        for n in nodes.values():
            by_class.setdefault(n.class_name, []).append(n.id)
        self._by_class = {k: tuple(v) for k, v in by_class.items()}
        self._rooms = frozenset(n.id for n in nodes.values() if n.is_room)
        chars = self._by_class.get(CHARACTER_CLASS, ())
        self._character = min(chars) if chars else None
        self._derived: dict[str, Any] = {}  # caches of derived data, e.g. body parts

    @classmethod
    def _from_indexes(cls, nodes: dict[int, Node], out: Index, inn: Index,
                      meta: Mapping[str, Any] | None = None) -> EnvironmentGraph:
        """Adopt ready-made indexes without copying (used by the simulator)."""
        g = cls.__new__(cls)
        g._init(nodes, out, inn, dict(meta or {}))
        return g

    # ----------------------------------------------------------------- loading
    @classmethod
    def from_dict(cls, data: Any, source: str | None = None) -> EnvironmentGraph:
        """Validate and load a VirtualHome graph dict; raises `GraphError` naming the fault."""
        where = f"{source}: " if source else ""
        if not isinstance(data, Mapping):
            raise GraphError(f"{where}a graph must be a JSON object with 'nodes' and 'edges'")
        for key in ("nodes", "edges"):
            if not isinstance(data.get(key), list):
                raise GraphError(f"{where}'{key}' must be a list")
        nodes: dict[int, Node] = {}
        for i, raw in enumerate(data["nodes"]):
            node = _node_from_dict(raw, f"{where}nodes[{i}]")
            if node.id in nodes:
                raise GraphError(f"{where}nodes[{i}]: duplicate node id {node.id}")
            nodes[node.id] = node
        edges: list[Edge] = []
        for i, raw in enumerate(data["edges"]):
            edges.append(_edge_from_dict(raw, nodes, f"{where}edges[{i}]"))
        meta = {k: v for k, v in data.items() if k not in ("nodes", "edges")}
        return cls(nodes.values(), edges, meta)

    @classmethod
    def load(cls, path: str | Path, max_bytes: int = MAX_GRAPH_BYTES) -> EnvironmentGraph:
        """Load a graph from a ``.json`` or ``.json.gz`` file."""
        path = Path(path)
        try:
            size = path.stat().st_size
        except OSError as e:
            raise GraphError(f"{path}: cannot read graph file ({e.strerror})") from None
        if size > max_bytes:
            raise GraphError(
                f"{path}: file is {size / 2**20:.0f} MiB, over the {max_bytes / 2**20:.0f} MiB "
                "limit for a graph"
            )
        try:
            raw = gzip.decompress(path.read_bytes()) if path.suffix == ".gz" else path.read_bytes()
            data = json.loads(raw)
        except (OSError, EOFError) as e:
            raise GraphError(f"{path}: cannot read graph file ({e})") from None
        except UnicodeDecodeError:
            raise GraphError(f"{path}: not UTF-8 text") from None
        except json.JSONDecodeError as e:
            raise GraphError(f"{path}: invalid JSON at line {e.lineno} column {e.colno}: "
                             f"{e.msg}") from None
        return cls.from_dict(data, source=str(path))

    def to_dict(self) -> dict[str, Any]:
        """The graph as a VirtualHome JSON dict (nodes by id, edges sorted)."""
        d: dict[str, Any] = {
            "nodes": [self._nodes[i].to_dict() for i in sorted(self._nodes)],
            "edges": [{"from_id": a, "relation_type": r, "to_id": b}
                      for a, r, b in sorted(self.edges())],
        }
        d.update(self._meta)
        return d

    def save(self, path: str | Path) -> None:
        """Write the graph as JSON (gzip-compressed when the name ends in ``.gz``)."""
        path = Path(path)
        text = json.dumps(self.to_dict())
        if path.suffix == ".gz":
            path.write_bytes(gzip.compress(text.encode(), mtime=0))
        else:
            path.write_text(text)

    # ----------------------------------------------------------------- queries
    def __len__(self) -> int:
        return len(self._nodes)

    def __contains__(self, node_id: object) -> bool:
        return node_id in self._nodes

    def __iter__(self) -> Iterator[Node]:
        return iter(self._nodes.values())

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, EnvironmentGraph):
            return NotImplemented
        return self._nodes == other._nodes and set(self.edges()) == set(other.edges())

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"EnvironmentGraph({len(self._nodes)} nodes, {self.num_edges()} edges)"

    @property
    def nodes(self) -> Mapping[int, Node]:
        """All nodes by id (read-only view)."""
        return self._nodes

    @property
    def meta(self) -> Mapping[str, Any]:
        """Top-level JSON keys other than nodes and edges, kept for saving."""
        return self._meta

    def node(self, node_id: int) -> Node:
        """The node with this id; `GraphError` if there is none."""
        try:
            return self._nodes[node_id]
        except KeyError:
            raise GraphError(f"the graph has no node {node_id}") from None

    def get(self, node_id: int) -> Node | None:
        return self._nodes.get(node_id)

    def nodes_of_class(self, class_name: str) -> list[Node]:
        return [self._nodes[i] for i in self._by_class.get(class_name, ())]

    def class_names(self) -> set[str]:
        return set(self._by_class)

    def targets(self, node_id: int, relation: str) -> frozenset[int]:
        """Ids `x` with an edge ``node_id -relation-> x``."""
        return self._out[relation].get(node_id, _EMPTY)

    def sources(self, node_id: int, relation: str) -> frozenset[int]:
        """Ids `x` with an edge ``x -relation-> node_id``."""
        return self._in[relation].get(node_id, _EMPTY)

    def has_edge(self, from_id: int, relation: str, to_id: int) -> bool:
        return to_id in self._out[relation].get(from_id, _EMPTY)

    def edges(self, relation: str | None = None) -> Iterator[Edge]:
        """Every edge, or every edge of one relation, as (from_id, relation, to_id)."""
        rels = RELATIONS if relation is None else (relation,)
        for r in rels:
            for a, bs in self._out[r].items():
                for b in bs:
                    yield (a, r, b)

    def num_edges(self) -> int:
        return sum(len(bs) for m in self._out.values() for bs in m.values())

    @property
    def character_id(self) -> int | None:
        """Id of the acting character (the lowest-id ``character`` node), or None."""
        return self._character

    @property
    def room_ids(self) -> frozenset[int]:
        return self._rooms

    def rooms(self) -> list[Node]:
        return [self._nodes[i] for i in sorted(self._rooms)]

    def room_of(self, node_id: int) -> int | None:
        """The room a node is in, following INSIDE edges; None if it is in none."""
        return room_of(node_id, self._rooms, lambda n: self.targets(n, INSIDE))


def room_of(node_id: int, rooms: frozenset[int], inside: Any) -> int | None:
    """Follow INSIDE edges from `node_id` to a room (rooms are their own room).

    A direct INSIDE edge to a room wins; otherwise the chain goes through the container
    with the lowest id, so the answer does not depend on set order.
    """
    if node_id in rooms:
        return node_id
    seen = {node_id}
    current = node_id
    while True:
        outer = inside(current)
        if not outer:
            return None
        direct = [x for x in outer if x in rooms]
        if direct:
            return min(direct)
        current = min(outer)
        if current in seen:
            return None
        seen.add(current)


# --------------------------------------------------------------------- validation
def _is_int(x: Any) -> bool:
    return isinstance(x, int) and not isinstance(x, bool)


def _str_list(raw: Mapping[str, Any], key: str, where: str) -> frozenset[str]:
    value = raw.get(key) or []
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise GraphError(f"{where}: '{key}' must be a list of strings, got {value!r:.60}")
    return frozenset(v.upper() for v in value)


def _opt_str(raw: Mapping[str, Any], key: str, where: str) -> str | None:
    value = raw.get(key)
    if value is not None and not isinstance(value, str):
        raise GraphError(f"{where}: '{key}' must be a string or null, got {value!r:.60}")
    return value


def _vec3(value: Any, what: str, where: str) -> tuple[float, float, float]:
    ok = (isinstance(value, list) and len(value) == 3
          and all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
                  for v in value))
    if not ok:
        raise GraphError(f"{where}: bounding_box '{what}' must be 3 finite numbers, "
                         f"got {value!r:.60}")
    return (float(value[0]), float(value[1]), float(value[2]))


def _node_from_dict(raw: Any, where: str) -> Node:
    if not isinstance(raw, Mapping):
        raise GraphError(f"{where}: a node must be a JSON object, got {raw!r:.60}")
    node_id = raw.get("id")
    if not _is_int(node_id):
        raise GraphError(f"{where}: 'id' must be an integer, got {node_id!r:.60}")
    where = f"{where} (id {node_id})"
    class_name = raw.get("class_name")
    if not isinstance(class_name, str) or not class_name.strip():
        raise GraphError(f"{where}: 'class_name' must be a non-empty string, "
                         f"got {class_name!r:.60}")
    box = raw.get("bounding_box")
    bbox = None
    if box is not None:
        if not isinstance(box, Mapping):
            raise GraphError(f"{where}: 'bounding_box' must be an object with center and size")
        bbox = BoundingBox(_vec3(box.get("center"), "center", where),
                           _vec3(box.get("size"), "size", where))
    extra = {k: v for k, v in raw.items() if k not in _NODE_KEYS} or None
    return Node(
        id=node_id,
        class_name=class_name,
        category=_opt_str(raw, "category", where),
        properties=_str_list(raw, "properties", where),
        states=_str_list(raw, "states", where),
        prefab_name=_opt_str(raw, "prefab_name", where),
        bounding_box=bbox,
        extra=extra,
    )


def _edge_from_dict(raw: Any, nodes: Mapping[int, Node], where: str) -> Edge:
    if not isinstance(raw, Mapping):
        raise GraphError(f"{where}: an edge must be a JSON object, got {raw!r:.60}")
    a, r, b = raw.get("from_id"), raw.get("relation_type"), raw.get("to_id")
    if not _is_int(a) or not _is_int(b):
        raise GraphError(f"{where}: 'from_id' and 'to_id' must be integers, got {a!r}, {b!r}")
    if not isinstance(r, str) or r.upper() not in RELATIONS:
        known = ", ".join(sorted(RELATIONS))
        raise GraphError(f"{where}: unknown relation {r!r} (known: {known})")
    for end, value in (("from_id", a), ("to_id", b)):
        if value not in nodes:
            raise GraphError(f"{where} ({a} {r} {b}): {end} {value} is not a node of the graph")
    return (a, r.upper(), b)
