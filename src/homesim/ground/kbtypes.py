"""What scene preparation and grounding need from the object knowledge base.

The knowledge base itself lives in `homesim.knowledge` (`load_kb()`); this module only
names the queries preparation and grounding make, so that tests can pass a small stand-in,
and resolves program class names to the class names a home uses.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from typing import Any, Protocol


class PlacementLike(Protocol):
    destination: str
    relation: str  # "ON" or "INSIDE"
    room: str | None


class ObjectKnowledge(Protocol):
    """The subset of `homesim.knowledge.ObjectKB` used here."""

    def properties(self, cls: str) -> frozenset[str]: ...
    def default_states(self, cls: str) -> frozenset[str]: ...
    def equivalents(self, name: str) -> list[str]: ...
    def script_names(self, cls: str) -> list[str]: ...
    def placements(self, cls: str) -> Sequence[Any]: ...
    def prefab_size(self, cls: str) -> tuple[float, float, float] | None: ...
    def classes(self) -> list[str]: ...
    def __hash__(self) -> int: ...  # lookups are cached per knowledge base (lru_cache)


def default_kb() -> ObjectKnowledge:
    """The package's knowledge base (`homesim.knowledge.load_kb()`, cached there)."""
    from homesim.knowledge import load_kb

    return load_kb()


def class_names_for(name: str, kb: ObjectKnowledge) -> list[str]:
    """Home class names a program name may stand for, most specific first.

    The name itself, then its scene equivalents (``television`` -> ``tv``, ``walltv``),
    then the script names of a scene class (``tv`` -> ``television``), so a program
    grounds in trimmed homes (script names) and full homes (Unity names) alike.

    >>> class _KB:
    ...     def equivalents(self, n): return {"television": ["television", "tv"]}.get(n, [n])
    ...     def script_names(self, c): return {"tv": ["television"]}.get(c, [])
    >>> class_names_for("television", _KB()), class_names_for("tv", _KB())
    (['television', 'tv'], ['tv', 'television'])
    """
    return list(_class_names(kb, name))


@lru_cache(maxsize=8192)
def _class_names(kb: ObjectKnowledge, name: str) -> tuple[str, ...]:
    # Cached: the knowledge base's name lookups scan its classes, and grounding asks for
    # the same few names over and over (the knowledge base is read-only).
    out = [name]
    for other in (*kb.equivalents(name), *kb.script_names(name)):
        if other not in out:
            out.append(other)
    return tuple(out)
