"""Loading a home: homesim's loaders against the loaders they replaced.

Three loaders run in this one invocation on the same home (best of --repeat runs):

- homesim's built-in home loader, `load_builtin`: the column file shipped in the package
  (``scene1.columns.json.gz``, `homesim.world.columns`), what `load_home` reads;
- the VirtualHome JSON loader, `EnvironmentGraph.load` / `from_dict` (full validation),
  which read the built-in homes before the column files and still reads user files;
- the old loader, a copy kept below of the JSON loader before issue 11 (per-node and
  per-edge validation, one Python object per edge, set-based index frozen afterwards).

Rows:

- ``load scene1 (built-in)``: the full scene1 (437 nodes, 14k edges) from the package:
  column file vs ``scene1.json.gz`` through the JSON loader and the old loader;
- ``from_dict scene1``: validate and index scene1, JSON already parsed;
- ``from_dict 1036 dataset graphs``: the stored initial and final graphs of the 518 real
  programs (what the conformance test loads), when the data set is fetched.

Goal (issue 11): loading scene1 from the package <= 10 ms. The machine's load average is
printed: wall times taken under load are noisy, the ratios less so; the CPU time of the
scene1 load (`time.process_time`) leaves out waiting for a core, so it stays close to a
quiet machine's wall time.

    python benchmarks/home_load.py [--repeat 20] [--skip-dataset]
"""

from __future__ import annotations

import argparse
import gzip
import json
import math
import os
import time
from collections.abc import Callable, Iterable, Mapping
from importlib import resources
from pathlib import Path
from typing import Any

from _timing import best_of
from homesim.errors import GraphError, HomesimError
from homesim.world.graph import BoundingBox, EnvironmentGraph, Node
from homesim.world.homes import load_builtin
from homesim.world.vocab import CHARACTER_CLASS, RELATIONS

# ------------------------------------------------------- reference: the loader before
_NODE_KEYS = ("id", "class_name", "category", "properties", "states", "prefab_name",
              "bounding_box")


def ref_from_dict(data: Any, source: str | None = None) -> tuple[Any, ...]:
    """The old `EnvironmentGraph.from_dict`: nodes, edges, both indexes, class table."""
    where = f"{source}: " if source else ""
    if not isinstance(data, Mapping):
        raise GraphError(f"{where}a graph must be a JSON object with 'nodes' and 'edges'")
    for key in ("nodes", "edges"):
        if not isinstance(data.get(key), list):
            raise GraphError(f"{where}'{key}' must be a list")
    nodes: dict[int, Node] = {}
    for i, raw in enumerate(data["nodes"]):
        node = _ref_node(raw, f"{where}nodes[{i}]")
        if node.id in nodes:
            raise GraphError(f"{where}nodes[{i}]: duplicate node id {node.id}")
        nodes[node.id] = node
    edges = [_ref_edge(raw, nodes, f"{where}edges[{i}]") for i, raw in enumerate(data["edges"])]
    meta = {k: v for k, v in data.items() if k not in ("nodes", "edges")}
    return _ref_init(nodes, edges, meta)


def ref_load(path: Path) -> tuple[Any, ...]:
    """The old `EnvironmentGraph.load` (size check and error mapping left out)."""
    raw = gzip.decompress(path.read_bytes()) if path.suffix == ".gz" else path.read_bytes()
    return ref_from_dict(json.loads(raw), source=str(path))


def _ref_init(nodes: dict[int, Node], edges: Iterable[tuple[int, str, int]],
              meta: dict[str, Any]) -> tuple[Any, ...]:
    out: dict[str, dict[int, set[int]]] = {r: {} for r in RELATIONS}
    inn: dict[str, dict[int, set[int]]] = {r: {} for r in RELATIONS}
    for a, r, b in edges:
        out[r].setdefault(a, set()).add(b)
        inn[r].setdefault(b, set()).add(a)

    def freeze(ix: dict[str, dict[int, set[int]]]) -> dict[str, dict[int, frozenset[int]]]:
        return {r: {k: frozenset(v) for k, v in m.items()} for r, m in ix.items()}

    by_class: dict[str, list[int]] = {}
    for n in nodes.values():
        by_class.setdefault(n.class_name, []).append(n.id)
    rooms = frozenset(n.id for n in nodes.values() if n.is_room)
    chars = by_class.get(CHARACTER_CLASS, [])
    return (nodes, freeze(out), freeze(inn), {k: tuple(v) for k, v in by_class.items()},
            rooms, min(chars) if chars else None, meta)


def _ref_is_int(x: Any) -> bool:
    return isinstance(x, int) and not isinstance(x, bool)


def _ref_str_list(raw: Mapping[str, Any], key: str, where: str) -> frozenset[str]:
    value = raw.get(key) or []
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise GraphError(f"{where}: '{key}' must be a list of strings, got {value!r:.60}")
    return frozenset(v.upper() for v in value)


def _ref_opt_str(raw: Mapping[str, Any], key: str, where: str) -> str | None:
    value = raw.get(key)
    if value is not None and not isinstance(value, str):
        raise GraphError(f"{where}: '{key}' must be a string or null, got {value!r:.60}")
    return value


def _ref_vec3(value: Any, what: str, where: str) -> tuple[float, float, float]:
    ok = (isinstance(value, list) and len(value) == 3
          and all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
                  for v in value))
    if not ok:
        raise GraphError(f"{where}: bounding_box '{what}' must be 3 finite numbers, "
                         f"got {value!r:.60}")
    return (float(value[0]), float(value[1]), float(value[2]))


def _ref_node(raw: Any, where: str) -> Node:
    if not isinstance(raw, Mapping):
        raise GraphError(f"{where}: a node must be a JSON object, got {raw!r:.60}")
    node_id = raw.get("id")
    if not _ref_is_int(node_id):
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
        bbox = BoundingBox(_ref_vec3(box.get("center"), "center", where),
                           _ref_vec3(box.get("size"), "size", where))
    extra = {k: v for k, v in raw.items() if k not in _NODE_KEYS} or None
    return Node(id=node_id, class_name=class_name, category=_ref_opt_str(raw, "category", where),
                properties=_ref_str_list(raw, "properties", where),
                states=_ref_str_list(raw, "states", where),
                prefab_name=_ref_opt_str(raw, "prefab_name", where), bounding_box=bbox,
                extra=extra)


def _ref_edge(raw: Any, nodes: Mapping[int, Node], where: str) -> tuple[int, str, int]:
    if not isinstance(raw, Mapping):
        raise GraphError(f"{where}: an edge must be a JSON object, got {raw!r:.60}")
    a, r, b = raw.get("from_id"), raw.get("relation_type"), raw.get("to_id")
    if not _ref_is_int(a) or not _ref_is_int(b):
        raise GraphError(f"{where}: 'from_id' and 'to_id' must be integers, got {a!r}, {b!r}")
    if not isinstance(r, str) or r.upper() not in RELATIONS:
        known = ", ".join(sorted(RELATIONS))
        raise GraphError(f"{where}: unknown relation {r!r} (known: {known})")
    for end, value in (("from_id", a), ("to_id", b)):
        if value not in nodes:
            raise GraphError(f"{where} ({a} {r} {b}): {end} {value} is not a node of the graph")
    return (a, r.upper(), b)


def dataset_graphs() -> list[dict[str, Any]]:
    """The stored initial and final graphs of the real programs, or [] without the data."""
    try:
        from homesim.knowledge.datasets import real_programs
        from homesim.knowledge.fetch import dataset_dir

        return [d for rp in real_programs(dataset_dir()) for d in rp.graph_dicts()]
    except HomesimError:
        return []


Row = tuple[str, Callable[[], Any], Callable[[], Any] | None, Callable[[], Any], int]
"""label, homesim's loader, today's JSON loader (None: it is homesim's), old loader, repeat"""


def rows(path: Path, repeat: int, with_dataset: bool = True) -> list[Row]:
    """What to time: the built-in home, from_dict on scene1 and on the dataset graphs."""
    data = json.loads(gzip.decompress(path.read_bytes()))
    # Same answer from every loader before timing anything.
    new, old = EnvironmentGraph.from_dict(data), ref_from_dict(data)
    assert dict(new.nodes) == old[0] and new.index.out == old[1], "loaders disagree"
    assert load_builtin("scene1").to_dict() == new.to_dict(), "column file disagrees"
    out: list[Row] = [
        ("load scene1 (built-in)", lambda: load_builtin("scene1"),
         lambda: EnvironmentGraph.load(path), lambda: ref_load(path), repeat),
        ("from_dict scene1", lambda: EnvironmentGraph.from_dict(data), None,
         lambda: ref_from_dict(data), repeat),
    ]
    graphs = dataset_graphs() if with_dataset else []
    if graphs:
        out.append((f"from_dict {len(graphs)} dataset graphs",
                    lambda: [EnvironmentGraph.from_dict(g) for g in graphs], None,
                    lambda: [ref_from_dict(g) for g in graphs], max(1, repeat // 10)))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    parser.add_argument("--skip-dataset", action="store_true",
                        help="leave out the dataset graphs row (minutes on a busy machine)")
    args = parser.parse_args()
    load = os.getloadavg()
    with resources.as_file(resources.files("homesim.world.builtin") / "scene1.json.gz") as path:
        print(f"{'':<30} {'homesim ms':>10} {'JSON loader ms':>15} {'ratio':>6} "
              f"{'old loader ms':>14} {'ratio':>6}")
        times = {}
        todo = rows(path, args.repeat, with_dataset=not args.skip_dataset)
        for label, ours, json_loader, old_loader, repeat in todo:
            t_ours, t_old = best_of(ours, repeat), best_of(old_loader, repeat)
            times[label] = t_ours
            if json_loader is None:
                json_cols = f"{'-':>15} {'':>6}"
            else:
                t_json = best_of(json_loader, repeat)
                json_cols = f"{t_json * 1e3:>15.2f} {t_json / t_ours:>5.1f}x"
            print(f"{label:<30} {t_ours * 1e3:>10.2f} {json_cols} {t_old * 1e3:>14.2f} "
                  f"{t_old / t_ours:>5.1f}x")
        scene1 = todo[0]
        cpu = [best_of(fn, args.repeat, time.process_time) * 1e3
               for fn in (scene1[1], scene1[2], scene1[3]) if fn is not None]
    load_ms = times["load scene1 (built-in)"] * 1e3
    print(f"\nload scene1, CPU time (process_time): homesim {cpu[0]:.2f} ms, JSON loader "
          f"{cpu[1]:.2f} ms ({cpu[1] / cpu[0]:.1f}x), old loader {cpu[2]:.2f} ms "
          f"({cpu[2] / cpu[0]:.1f}x)")
    print(f"goal: load scene1 from the package <= 10 ms: wall "
          f"{'met' if load_ms <= 10 else 'NOT MET'} ({load_ms:.1f} ms), CPU "
          f"{'met' if cpu[0] <= 10 else 'NOT MET'} ({cpu[0]:.1f} ms)")
    after = os.getloadavg()
    print(f"load average (1 min) before/after: {load[0]:.2f} / {after[0]:.2f} "
          f"on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
