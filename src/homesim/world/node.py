"""The parts of a home: `Node` (an object, room or character), its `BoundingBox`, `Edge`.

They sit apart from `homesim.world.graph` so that the index (`homesim.world.index`) can
name them without importing the graph that builds it.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from homesim.world.vocab import ROOM_CATEGORY


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
