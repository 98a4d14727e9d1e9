"""Find the file-level import circles in a package (run by `make lint`).

import-linter's contracts keep the layer order between packages, but a circle between two
modules of one package (a.py imports b.py imports a.py) breaks none of them. This tool builds
the module graph with grimp (import-linter's own graph: every import counts, those under
`if TYPE_CHECKING:` and inside functions included) and reports each strongly connected
component of more than one module, with one circle through it.

    python tools/import_graph.py            # homesim; exit 1 when there is a circle
    python tools/import_graph.py mypackage
    python tools/import_graph.py --known homesim.somepackage   # its inner circles, for now

A circle wholly inside a `--known` package is listed but does not fail the check; for a
`--known` package without a circle it says to take the exception out.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Iterable, Mapping

import grimp


def import_edges(package: str) -> dict[str, set[str]]:
    """Each module of `package` -> the modules of `package` it imports directly."""
    graph = grimp.build_graph(package, cache_dir=None)
    return {m: set(graph.find_modules_directly_imported_by(m)) for m in sorted(graph.modules)}


def components(edges: Mapping[str, Iterable[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    found.append(_pop_component(node, stack, on_stack))
            elif child not in index:
                index[child] = low[child] = len(index)
                stack.append(child)
                on_stack.add(child)
                work.append((child, iter(sorted(edges.get(child, ())))))
            elif child in on_stack:
                low[node] = min(low[node], index[child])
    return sorted(sorted(c) for c in found if len(c) > 1)


def _pop_component(node: str, stack: list[str], on_stack: set[str]) -> list[str]:
    component = []
    while True:
        member = stack.pop()
        on_stack.discard(member)
        component.append(member)
        if member == node:
            return component


def circle(component: list[str], edges: Mapping[str, Iterable[str]]) -> list[str]:
    """One shortest circle through the component's first module (breadth-first)."""
    start, inside = component[0], set(component)
    came_from: dict[str, str] = {}
    frontier = [start]
    while frontier:
        following = []
        for node in frontier:
            for child in sorted(set(edges[node]) & inside):
                if child == start:
                    path = [node]
                    while path[-1] != start:
                        path.append(came_from[path[-1]])
                    return [*reversed(path), start]
                if child not in came_from:
                    came_from[child] = node
                    following.append(child)
        frontier = following
    raise ValueError(f"no circle through {start}")  # a component always has one


def _inside(module: str, package: str) -> bool:
    return module == package or module.startswith(package + ".")


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("package", nargs="?", default="homesim")
    parser.add_argument("--known", action="append", default=[], metavar="PACKAGE",
                        help="a package whose inner circles are known (listed, not failed)")
    args = parser.parse_args(argv)
    edges = import_edges(args.package)
    found = components(edges)
    known = {k: [c for c in found if all(_inside(m, k) for m in c)] for k in args.known}
    failing = [c for c in found if not any(c in cs for cs in known.values())]
    count = sum(len(targets) for targets in edges.values())
    print(f"{args.package}: {len(edges)} modules, {count} imports, {len(failing)} file-level "
          f"circles" + (f" ({len(found) - len(failing)} known)" if known else ""))
    for component in found:
        tag = "circle" if component in failing else "known circle"
        print(f"  {tag} among {len(component)} modules, e.g. "
              + " -> ".join(circle(component, edges)))
    for k in [k for k, cs in known.items() if not cs]:
        print(f"  --known {k}: it has no circle any more; take it out of the Makefile")
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
