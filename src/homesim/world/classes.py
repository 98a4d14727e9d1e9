"""What homes and the simulator ask of the object knowledge base, and which one answers.

The object knowledge base (`homesim.knowledge.ObjectKB`) sits above the world and the
simulator in the layer order of DESIGN.md (world 2, sim 3, knowledge 4), yet both need a
little of it: a generated home puts items where the placement knowledge allows
(`placements`), and the simulator, like grounding, accepts a node of an equivalent class
for a program's object (``<television>`` bound to a ``tv``, `class_names_for`). So this
module names those questions as a protocol, `ClassKnowledge`, which the knowledge base
satisfies (its full interface, `homesim.knowledge.kbtypes.ObjectKnowledge`, extends it),
and nothing here imports the knowledge package.

Who answers when a caller passes no knowledge base: `default_kb`, the one that
`use_default_kb` was given. The package facade (``homesim/__init__.py``, the top layer,
which Python runs before any ``homesim.*`` module) gives it `homesim.knowledge.load_kb`;
the knowledge is read on the first question, not at import. Tests pass their own
stand-ins, as every function that asks takes a knowledge base argument.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import lru_cache
from typing import Protocol

from homesim.errors import HomesimError


class PlacementLike(Protocol):
    """Where an object of a class may go: on or inside a destination class, in a room."""

    @property
    def destination(self) -> str: ...
    @property
    def relation(self) -> str: ...  # "ON" or "INSIDE"
    @property
    def room(self) -> str | None: ...


class ClassKnowledge(Protocol):
    """The part of the object knowledge base that homes and the simulator use."""

    def equivalents(self, name: str) -> list[str]: ...
    def script_names(self, cls: str) -> list[str]: ...
    def placements(self, cls: str) -> Sequence[PlacementLike]: ...
    def __hash__(self) -> int: ...  # lookups are cached per knowledge base (lru_cache)


_default: list[Callable[[], ClassKnowledge]] = []


def use_default_kb(load: Callable[[], ClassKnowledge]) -> None:
    """Make `load()` the knowledge base of callers that pass none (the facade's call)."""
    _default[:] = [load]


def default_kb() -> ClassKnowledge:
    """The knowledge base of callers that pass none (see the module docstring)."""
    if not _default:  # only if this module were loaded without the homesim package
        raise HomesimError("no default object knowledge base: import homesim first")
    return _default[0]()


def class_names_for(name: str, kb: ClassKnowledge) -> list[str]:
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
def _class_names(kb: ClassKnowledge, name: str) -> tuple[str, ...]:
    # Cached: the knowledge base's name lookups scan its classes, and grounding asks for
    # the same few names over and over (the knowledge base is read-only).
    out = [name]
    for other in (*kb.equivalents(name), *kb.script_names(name)):
        if other not in out:
            out.append(other)
    return tuple(out)
