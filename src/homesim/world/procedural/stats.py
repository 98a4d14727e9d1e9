"""The statistics procedural homes are drawn from (stats.json, fitted from the five
built-in apartments by tools/fit_home_stats.py): room sizes and objects per room kind,
box sizes and attributes per class."""

from __future__ import annotations

import json
from functools import lru_cache
from importlib import resources
from typing import Any

KINDS = ("living_room", "kitchen", "dining_room", "bedroom", "kids_bedroom", "bathroom",
         "entrance_hall", "home_office")
"""The paper's eight room kinds."""


@lru_cache(maxsize=1)
def stats() -> dict[str, Any]:
    text = (resources.files("homesim.world.procedural") / "stats.json").read_text()
    return json.loads(text)


def kind_sizes(kind: str) -> list[list[float]]:
    """Observed (x, z) sizes (m) of rooms of this kind: their floors' extents in the
    built-in homes (scaled for derived kinds)."""
    return stats()["kinds"][kind]["sizes"]


def kind_area(kind: str) -> tuple[float, float]:
    """The smallest and largest floor area (m2) of rooms of this kind in the built-in
    homes (scaled for derived kinds)."""
    lo, hi = stats()["kinds"][kind]["area"]
    return float(lo), float(hi)


def room_class(kind: str) -> str:
    """The class name of a room of this kind (``living_room`` -> ``livingroom``)."""
    return stats()["kinds"][kind]["class"]


def kind_objects(kind: str) -> list[dict[str, Any]]:
    """Per class: ``class``, ``p`` (share of rooms with it), ``counts``, ``mount``,
    ``parents`` ({"parent|ON": n})."""
    return stats()["kinds"][kind]["objects"]


def class_info(cls: str) -> dict[str, Any]:
    """``category``, ``properties``, ``states``, ``prefab``, ``size`` [w, h, d] (w >= d),
    ``height`` (bottom above the floor)."""
    return stats()["classes"][cls]
