"""The pieces models are built of: `Shape` (one primitive), `Kit` (collects shapes in a
box's local frame) and the registry of builders by name (`builder`, `BUILDERS`).

A builder draws in a local frame fitted to the node's box: x across the front, y towards
the front (the side facing the room), z up, origin at the box centre, half sizes
``(w, d, h)``. The class table (`homesim.world.class_table`, column ``model``) names the
builder of each class; a builder registered with ``variants=n`` draws n variants
(`Kit.v`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

KINDS = ("box", "cylinder", "capsule", "ellipsoid")


@dataclass(frozen=True)
class Shape:
    """One primitive, axis-aligned: its centre, the half sizes of its bounding box, the
    axis a cylinder or capsule runs along (0 x, 1 y, 2 z) and its material role."""

    kind: str
    center: np.ndarray
    half: np.ndarray
    role: str
    axis: int = 2

    def mjcf_size(self) -> np.ndarray:
        """MuJoCo's `size` of the geom (boxes and ellipsoids: half sizes; cylinders and
        capsules: radius and half length)."""
        if self.kind in ("box", "ellipsoid"):
            return np.maximum(self.half, 1e-3)
        across = [a for a in range(3) if a != self.axis]
        r = max(float(min(self.half[across[0]], self.half[across[1]])), 1e-3)
        length = float(self.half[self.axis])
        if self.kind == "capsule":
            length -= r
        return np.array([r, max(length, 1e-3)])


class Kit:
    """Collects shapes in the local frame of a box with half sizes (w, d, h)."""

    def __init__(self, w: float, d: float, h: float, variant: int):
        self.w, self.d, self.h, self.v = w, d, h, variant
        self.shapes: list[Shape] = []

    @property
    def bottom(self) -> float:
        return -self.h

    def box(self, lo, hi, role: str = "body") -> Kit:
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        self.shapes.append(Shape("box", (lo + hi) / 2, np.abs(hi - lo) / 2, role))
        return self

    def ell(self, center, half, role: str = "body") -> Kit:
        self.shapes.append(Shape("ellipsoid", np.asarray(center, float),
                                 np.asarray(half, float), role))
        return self

    def cyl(self, x: float, y: float, r: float, z0: float, z1: float, role: str = "body",
            kind: str = "cylinder") -> Kit:
        """A vertical cylinder (or capsule) from z0 to z1."""
        self.shapes.append(Shape(kind, np.array([x, y, (z0 + z1) / 2]),
                                 np.array([r, r, abs(z1 - z0) / 2]), role))
        return self

    def rod(self, center, axis: int, r: float, half_len: float, role: str = "body",
            kind: str = "cylinder") -> Kit:
        """A cylinder (or capsule) along a horizontal or vertical axis."""
        half = np.full(3, r)
        half[axis] = half_len
        self.shapes.append(Shape(kind, np.asarray(center, float), half, role, axis))
        return self

    def add(self, other: Kit, offset: np.ndarray) -> Kit:
        """Another kit's shapes, moved by `offset`."""
        self.shapes += [Shape(s.kind, s.center + offset, s.half, s.role, s.axis)
                        for s in other.shapes]
        return self

    def legs(self, top: float, r: float, inset: float, role: str = "wood",
             square: bool = False) -> Kit:
        """Four legs from the floor up to `top`, `inset` from the corners."""
        for sx in (-1, 1):
            for sy in (-1, 1):
                x, y = sx * (self.w - inset - r), sy * (self.d - inset - r)
                if square:
                    self.box([x - r, y - r, self.bottom], [x + r, y + r, top], role)
                else:  # round legs: a capsule-ended rod reads as turned wood or tube
                    self.cyl(x, y, r, self.bottom, top, role)
        return self


Builder = Callable[[Kit], None]


BUILDERS: dict[str, Builder] = {}
"""Builder name (the class table's ``model`` column) -> builder."""
VARIANTS: dict[str, int] = {}
"""Builder name -> how many variants it draws (1: one model)."""


def builder(name: str | None = None, variants: int = 1) -> Callable[[Builder], Builder]:
    """Register a function as the builder `name` (by default its own name) drawing
    `variants` variants."""

    def register(fn: Builder) -> Builder:
        key = name or fn.__name__
        if key in BUILDERS:
            raise ValueError(f"model builder {key!r} is registered twice")
        BUILDERS[key] = fn
        VARIANTS[key] = variants
        return fn

    return register
