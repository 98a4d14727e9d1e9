"""`Part`: one object of a home being generated, before it becomes a graph node."""

from __future__ import annotations

from dataclasses import dataclass, field

Box3 = tuple[float, float, float, float, float, float]
"""(x0, y0, z0, x1, y1, z1) in metres, y up."""


@dataclass
class Part:
    """An object being placed: class, room, box and what holds it up.

    `support` is (index of the part it stands on or is in, "ON" or "INSIDE"), or None for
    rooms and the character; `normal` is the (x, z) direction its front faces."""

    cls: str
    room: int
    box: Box3
    support: tuple[int, str] | None = None
    normal: tuple[float, float] | None = None
    states: tuple[str, ...] = ()
    kind: str = "item"
    """``structure`` (walls, floors, ceilings, doors, windows), ``fixture`` (furniture on
    the floor, wall or ceiling), ``item`` (on or in a fixture), ``room``, ``character``."""
    between: tuple[int, ...] = field(default=())
    """For a door: the part indices of the two rooms."""

    @property
    def footprint(self) -> tuple[float, float, float, float]:
        return (self.box[0], self.box[2], self.box[3], self.box[5])


def box3(x0: float, y0: float, z0: float, x1: float, y1: float, z1: float) -> Box3:
    return (round(x0, 4), round(y0, 4), round(z0, 4), round(x1, 4), round(y1, 4), round(z1, 4))


def overlap3(a: Box3, b: Box3, margin: float = 0.0) -> bool:
    """Whether two boxes overlap by more than `margin` on every axis."""
    return all(min(a[k + 3], b[k + 3]) - max(a[k], b[k]) > margin for k in range(3))


def gap3(a: Box3, b: Box3) -> float:
    """The largest per-axis gap between two boxes (0 when they touch or overlap)."""
    return max(0.0, *(max(a[k], b[k]) - min(a[k + 3], b[k + 3]) for k in range(3)))
