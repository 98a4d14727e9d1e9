"""Compare two environment graphs aspect by aspect (node states and each relation)."""

from __future__ import annotations

from homesim.world.graph import EnvironmentGraph
from homesim.world.vocab import CLOSE, FACING, HOLDS_LH, HOLDS_RH, INSIDE, ON

CORE_ASPECTS = ("states", INSIDE, ON, HOLDS_RH, HOLDS_LH)
"""What the simulator must reproduce exactly on the real data."""
ASPECTS = (*CORE_ASPECTS, CLOSE, FACING)


def aspect(graph: EnvironmentGraph, name: str) -> set:
    """One aspect of a graph as a set: node states, or the edges of one relation."""
    if name == "states":
        return {(n.id, s) for n in graph for s in n.states}
    return {(a, b) for a, _, b in graph.edges(name)}


def compare_graphs(got: EnvironmentGraph, expected: EnvironmentGraph,
                   aspects: tuple[str, ...] = ASPECTS) -> dict[str, tuple[set, set]]:
    """Differences per aspect, as (only in `got`, only in `expected`); equal aspects omitted."""
    diffs = {}
    for name in aspects:
        a, b = aspect(got, name), aspect(expected, name)
        if a != b:
            diffs[name] = (a - b, b - a)
    return diffs
