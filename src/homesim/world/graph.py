"""`EnvironmentGraph`: a home as nodes (objects, rooms, the character) and typed edges.

The format is VirtualHome's JSON: ``{"nodes": [{id, class_name, category, properties,
states, prefab_name, bounding_box}], "edges": [{from_id, relation_type, to_id}]}``.

A graph is read-only once built: it is validated once at the edge (`from_dict`, `load`)
and then indexed (`homesim.world.index.HomeIndex`: by id, by class, by relation in both
directions), so the simulator can trust it and look things up in O(1), and threads can
share it. Executing a program never changes a graph; it yields a new one.
"""

from __future__ import annotations

import gzip
import io
import json
import math
from collections.abc import Iterable, Iterator, Mapping, Sequence
from operator import itemgetter
from pathlib import Path
from typing import Any, TypeGuard, cast

import orjson

from homesim.errors import GraphError, HomesimError, excerpt
from homesim.files import read_limited, write_bytes, write_text
from homesim.limits import (
    MAX_COORD,
    MAX_GRAPH_BYTES,
    MAX_JSON_DEPTH,
    MAX_NODE_ID,
    MAX_SIZE,
    deeper_than,
)
from homesim.world.index import HomeIndex, index_edges
from homesim.world.node import BoundingBox, Edge, Node
from homesim.world.vocab import CHARACTER_CLASS, INSIDE, RELATIONS

_EMPTY: frozenset[int] = frozenset()
_EMPTY_STR: frozenset[str] = frozenset()
_INT_TYPE = {int}
_NODE_KEY_SET = frozenset(("id", "class_name", "category", "properties", "states",
                           "prefab_name", "bounding_box"))


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

    # _nodes, _out and _in repeat fields of the index: the queries below read them often.
    __slots__ = ("__weakref__", "_in", "_index", "_meta", "_nodes", "_out")

    def __init__(self, nodes: Iterable[Node], edges: Iterable[Edge],
                 meta: Mapping[str, Any] | None = None):
        """Build from trusted parts; use `from_dict` or `load` for outside data."""
        edge_list = list(edges)
        out, inn = index_edges([e[0] for e in edge_list], [e[1] for e in edge_list],
                               [e[2] for e in edge_list])
        self._adopt(HomeIndex.build({n.id: n for n in nodes}, out, inn), dict(meta or {}))

    def _adopt(self, index: HomeIndex, meta: dict[str, Any]) -> None:
        self._index = index
        self._nodes = index.nodes
        self._out = index.out
        self._in = index.incoming
        self._meta = meta

    @classmethod
    def from_index(cls, index: HomeIndex, meta: Mapping[str, Any] | None = None
                   ) -> EnvironmentGraph:
        """Adopt a ready-made index without copying (the simulator's final graphs)."""
        g = cls.__new__(cls)
        g._adopt(index, dict(meta or {}))
        return g

    @property
    def index(self) -> HomeIndex:
        """The fixed index of this home (read-only; shared with the simulator)."""
        return self._index

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
            node = _node_from_dict(raw, where, i)
            if node.id in nodes:
                raise GraphError(f"{where}nodes[{i}]: duplicate node id {node.id}")
            nodes[node.id] = node
        columns = _edge_columns(data["edges"], nodes)
        if columns is None:  # something is off: find it edge by edge, for the message
            edges = [_edge_from_dict(raw, nodes, f"{where}edges[{i}]")
                     for i, raw in enumerate(data["edges"])]
            columns = ([e[0] for e in edges], [e[1] for e in edges], [e[2] for e in edges])
        out, inn = index_edges(*columns)
        index = HomeIndex.build(nodes, out, inn)
        _check_characters(index, where)
        meta = {k: v for k, v in data.items() if k not in ("nodes", "edges")}
        return cls.from_index(index, meta)

    @classmethod
    def load(cls, path: str | Path, max_bytes: int = MAX_GRAPH_BYTES) -> EnvironmentGraph:
        """Load a home from a ``.json`` or ``.json.gz`` file; it must have a character.

        Every `GraphError` names the file and says why in one line."""
        path = Path(path)
        try:
            raw = read_limited(path, max_bytes, "MAX_GRAPH_BYTES", "graph")
        except HomesimError as e:
            raise GraphError(str(e)) from None
        try:
            if path.suffix == ".gz":
                # Read at most the limit: a small .gz file can unpack to gigabytes.
                with gzip.GzipFile(fileobj=io.BytesIO(raw)) as f:
                    raw = f.read(max_bytes + 1)
                if len(raw) > max_bytes:
                    raise GraphError(f"{path}: unpacks to over the {max_bytes / 2**20:.0f} MiB "
                                     "limit for a graph (MAX_GRAPH_BYTES)")
            data = _parse_json(raw)
        except EOFError:
            raise GraphError(f"{path}: the gzip data ends early (is the file truncated?)") from None
        except (OSError, gzip.BadGzipFile) as e:
            raise GraphError(f"{path}: cannot read graph file ({e})") from None
        except UnicodeDecodeError:
            raise GraphError(f"{path}: not UTF-8 text") from None
        except json.JSONDecodeError as e:
            raise GraphError(f"{path}: {_json_problem(e)}") from None
        except ValueError as e:  # an integer of over 4300 digits
            raise GraphError(f"{path}: invalid JSON ({excerpt(str(e))})") from None
        except RecursionError:
            raise GraphError(f"{path}: JSON nested deeper than the limit of {MAX_JSON_DEPTH} "
                             "levels (MAX_JSON_DEPTH)") from None
        graph = cls.from_dict(data, source=str(path))
        if graph.character_id is None:
            raise GraphError(f"{path}: the graph has no character node (class_name "
                             f"'{CHARACTER_CLASS}'); a home needs one to act in it")
        return graph

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
        if path.suffix == ".gz":  # atomically: an interrupted save leaves the old file
            write_bytes(path, gzip.compress(text.encode(), mtime=0))
        else:
            write_text(path, text)

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
        return [self._nodes[i] for i in self._index.by_class.get(class_name, ())]

    def class_names(self) -> set[str]:
        return set(self._index.by_class)

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
        return self._index.character

    @property
    def room_ids(self) -> frozenset[int]:
        return self._index.rooms

    def rooms(self) -> list[Node]:
        return [self._nodes[i] for i in sorted(self._index.rooms)]

    def room_of(self, node_id: int) -> int | None:
        """The room a node is in, following INSIDE edges; None if it is in none."""
        return room_of(node_id, self._index.rooms, lambda n: self.targets(n, INSIDE))


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
# One pass over the nodes checks each field where it is read; edges (most of a home: 14k
# in scene1) are checked column-wise by C-level set operations, and only when a check
# fails are they walked one by one to name the faulty edge.

_NUMBER = (int, float)
_FROM, _RELATION, _TO = itemgetter("from_id"), itemgetter("relation_type"), itemgetter("to_id")


def _is_int(x: Any) -> TypeGuard[int]:
    return isinstance(x, int) and not isinstance(x, bool)


def _node_where(where: str, i: int, node_id: Any = None) -> str:
    return f"{where}nodes[{i}]" + ("" if node_id is None else f" (id {node_id})")


def _str_set(raw: Mapping[str, Any], key: str, where: str, i: int, node_id: int
             ) -> frozenset[str]:
    value = raw.get(key)
    if not value:
        return _EMPTY_STR
    if isinstance(value, list):
        try:
            return frozenset(map(str.upper, value))  # TypeError on a non-string
        except TypeError:
            pass
    raise GraphError(f"{_node_where(where, i, node_id)}: '{key}' must be a list of strings, "
                     f"got {value!r:.60}")


def _opt_str(raw: Mapping[str, Any], key: str, where: str, i: int, node_id: int) -> str | None:
    value = raw.get(key)
    if value is not None and not isinstance(value, str):
        raise GraphError(f"{_node_where(where, i, node_id)}: '{key}' must be a string or null, "
                         f"got {value!r:.60}")
    return value


def _vec3(value: Any, what: str, limit: float, low: float, where: str, i: int,
          node_id: int) -> tuple[float, float, float]:
    if isinstance(value, list) and len(value) == 3:
        x, y, z = value
        # Chained comparisons are False for NaN and infinities too.
        if (type(x) in _NUMBER and type(y) in _NUMBER and type(z) in _NUMBER
                and low <= x <= limit and low <= y <= limit and low <= z <= limit):
            return (float(x), float(y), float(z))
        if all(isinstance(v, _NUMBER) and not isinstance(v, bool) and math.isfinite(v)
               for v in value):
            bound = f"within ±{limit:g} m" if low < 0 else f"between 0 and {limit:g} m"
            raise GraphError(f"{_node_where(where, i, node_id)}: bounding_box '{what}' must be "
                             f"{bound} (homesim.limits), got {value!r:.60}")
    raise GraphError(f"{_node_where(where, i, node_id)}: bounding_box '{what}' must be 3 finite "
                     f"numbers, got {value!r:.60}")


def _node_from_dict(raw: Any, where: str, i: int) -> Node:
    """Node `i` of the JSON list; `where` is the source prefix for messages."""
    if not isinstance(raw, Mapping):
        raise GraphError(f"{_node_where(where, i)}: a node must be a JSON object, "
                         f"got {raw!r:.60}")
    raw_id = raw.get("id")
    if type(raw_id) is not int and not _is_int(raw_id):
        raise GraphError(f"{_node_where(where, i)}: 'id' must be an integer, got {raw_id!r:.60}")
    node_id = cast(int, raw_id)
    if not 0 <= node_id <= MAX_NODE_ID:
        raise GraphError(f"{_node_where(where, i)}: 'id' {excerpt(str(node_id))} is outside 0.."
                         f"{MAX_NODE_ID} (MAX_NODE_ID: ids index 32-bit arrays in render)")
    class_name = raw.get("class_name")
    if not isinstance(class_name, str) or not class_name.strip():
        raise GraphError(f"{_node_where(where, i, node_id)}: 'class_name' must be a non-empty "
                         f"string, got {class_name!r:.60}")
    box = raw.get("bounding_box")
    bbox = None
    if box is not None:
        if not isinstance(box, Mapping):
            raise GraphError(f"{_node_where(where, i, node_id)}: 'bounding_box' must be an "
                             "object with center and size")
        bbox = BoundingBox(
            _vec3(box.get("center"), "center", MAX_COORD, -MAX_COORD, where, i, node_id),
            _vec3(box.get("size"), "size", MAX_SIZE, 0.0, where, i, node_id))
    extra = None
    if not raw.keys() <= _NODE_KEY_SET:
        extra = {k: v for k, v in raw.items() if k not in _NODE_KEY_SET}
        if deeper_than(extra, MAX_JSON_DEPTH - 3):  # graph > nodes > node > extra
            raise GraphError(f"{_node_where(where, i, node_id)}: JSON nested deeper than the "
                             f"limit of {MAX_JSON_DEPTH} levels (MAX_JSON_DEPTH)")
    return Node(node_id, class_name, _opt_str(raw, "category", where, i, node_id),
                _str_set(raw, "properties", where, i, node_id),
                _str_set(raw, "states", where, i, node_id),
                _opt_str(raw, "prefab_name", where, i, node_id), bbox, extra)


def _edge_columns(raw_edges: list[Any], nodes: Mapping[int, Node]
                  ) -> tuple[Sequence[int], Sequence[str], Sequence[int]] | None:
    """The edges as (from ids, relations, to ids) if every one is valid and its relation
    is spelled in upper case; None otherwise (then `_edge_from_dict` says which is not)."""
    try:
        froms = list(map(_FROM, raw_edges))
        rels = list(map(_RELATION, raw_edges))
        tos = list(map(_TO, raw_edges))
    except (TypeError, KeyError):  # not an object, or a key is missing
        return None
    ids = nodes.keys()
    try:
        if (set(map(type, froms)) == _INT_TYPE and set(map(type, tos)) == _INT_TYPE
                and RELATIONS.issuperset(rels) and ids >= set(froms) and ids >= set(tos)):
            return froms, rels, tos
    except TypeError:  # an unhashable relation
        pass
    return None


def _edge_from_dict(raw: Any, nodes: Mapping[int, Node], where: str) -> Edge:
    if not isinstance(raw, Mapping):
        raise GraphError(f"{where}: an edge must be a JSON object, got {raw!r:.60}")
    a, r, b = raw.get("from_id"), raw.get("relation_type"), raw.get("to_id")
    if not _is_int(a) or not _is_int(b):
        raise GraphError(f"{where}: 'from_id' and 'to_id' must be integers, got {a!r}, {b!r}")
    if not isinstance(r, str) or r.upper() not in RELATIONS:
        known = ", ".join(sorted(RELATIONS))
        raise GraphError(f"{where}: unknown relation {r!r:.60} (known: {known})")
    for end, value in (("from_id", a), ("to_id", b)):
        if value not in nodes:
            raise GraphError(f"{where} ({a} {r} {b}): {end} {value} is not a node of the graph")
    return (cast(int, a), r.upper(), cast(int, b))


def _check_characters(index: HomeIndex, where: str) -> None:
    """Every character is INSIDE a room, when the home has rooms: grounding and rendering
    place the agent by its room."""
    if not index.rooms:
        return
    inside = index.out[INSIDE]
    for char in index.by_class.get(CHARACTER_CLASS, ()):
        if not inside.get(char, _EMPTY) & index.rooms:
            raise GraphError(f"{where}character {char} is INSIDE no room; add an edge "
                             f"{{'from_id': {char}, 'relation_type': 'INSIDE', 'to_id': ROOM}}")


def _parse_json(raw: bytes) -> Any:
    """Parse JSON with orjson (about 3x faster on a home), else with `json`.

    Anything orjson refuses (bad JSON, integers beyond 64 bits, NaN, deep nesting) is
    parsed again by `json`, whose exceptions the caller turns into messages: the same
    answer as before, only valid homes take the fast path."""
    try:
        return orjson.loads(raw)
    except orjson.JSONDecodeError:
        return json.loads(raw)


def _json_problem(e: json.JSONDecodeError) -> str:
    """One full line for a JSON syntax error: where, what, and whether the text ends early."""
    if not e.doc.strip():
        return "the file is empty, not a JSON graph"
    what = e.msg.removesuffix(" starting at").removesuffix(": line 1 column 1 (char 0)")
    what = what[0].lower() + what[1:] if what else "syntax error"
    if e.msg.startswith("Unterminated string"):
        what = "a string starting there never ends"
    ends_early = e.pos >= len(e.doc.rstrip()) or e.msg.startswith("Unterminated")
    tail = "; the text ends early (is the file truncated?)" if ends_early else ""
    return f"invalid JSON at line {e.lineno} column {e.colno}: {what}{tail}"
