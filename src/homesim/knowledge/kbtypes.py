"""The object knowledge base as preparation, grounding, agents and data sets use it.

`ObjectKnowledge` names the queries they make, so that tests can pass a small stand-in;
`homesim.knowledge.ObjectKB` (`load_kb()`) is the real one. It extends the part that homes
and the simulator use from below (`homesim.world.classes.ClassKnowledge`: equivalent class
names and placements), and `class_names_for`, which resolves a program's class name to
the class names a home uses, is that module's, named here too.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from homesim.knowledge.objects import load_kb
from homesim.world.classes import ClassKnowledge, PlacementLike, class_names_for

__all__ = ["ObjectKnowledge", "PlacementLike", "class_names_for", "default_kb"]


class ObjectKnowledge(ClassKnowledge, Protocol):
    """The subset of `homesim.knowledge.ObjectKB` used above the simulator."""

    def properties(self, cls: str) -> frozenset[str]: ...
    def default_states(self, cls: str) -> frozenset[str]: ...
    def placements(self, cls: str) -> Sequence[PlacementLike]: ...
    def prefab_size(self, cls: str) -> tuple[float, float, float] | None: ...
    def classes(self) -> list[str]: ...


def default_kb() -> ObjectKnowledge:
    """The package's knowledge base (`homesim.knowledge.load_kb()`, cached there)."""
    return load_kb()
