"""The model library: a 3D model per object class, built from MuJoCo primitives.

A model is a list of `Shape` (box, cylinder, capsule, ellipsoid), each with a material
`role` (``body`` takes the class colour; ``wood``, ``fabric``, ``metal``, ``glass``,
``screen``, ``glow``... take the home's materials, see `homesim.render.materials`).
Builders draw in a local frame fitted to the node's box: x across the front, y towards
the front (the side facing the room), z up, origin at the box centre, half sizes
``(w, d, h)``. `fit_model` turns the result into the MuJoCo frame. Every shape is kept
inside the box (clamped), so depth and segmentation stay exact against the graph's boxes.

Classes are looked up spelling-forgiving (``coffee_table`` = ``coffeetable``), then by
word (``kitchen_cabinet`` -> cabinet), then by the node's category. `VARIANTS` classes have
three or more variants; `variant_of` picks one from the seed.
"""

from __future__ import annotations

import zlib
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


# -- furniture ------------------------------------------------------------------------------

def sofa(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    seat = b + min(0.45, 1.2 * k.h)
    leg = 0.06 if k.v != 2 else 0.12
    arm = (0.0, 0.1, 0.16)[k.v] * min(1.0, w)
    back = min(0.22, d * 0.5)
    k.legs(b + leg, 0.025, 0.04, "darkwood", square=True)
    k.box([-w, -d, b + leg], [w, d, seat - 0.12], "fabric")  # base
    n = 3 if w > 0.8 else 2
    inner = w - arm
    for i in range(n):  # seat cushions
        x0 = -inner + 2 * inner * i / n
        k.box([x0 + 0.01, -d + back, seat - 0.12], [x0 + 2 * inner / n - 0.01, d, seat],
              "cushion")
    k.box([-w, -d, seat - 0.12], [w, -d + back, k.h], "fabric")  # backrest
    if arm > 0:
        for s in (-1, 1):
            k.box([s * w - arm if s > 0 else -w, -d, seat - 0.12],
                  [w if s > 0 else -w + arm, d, min(k.h, seat + 0.2)], "fabric")
    if k.v != 1:  # back pillows
        for i in range(n):
            x0 = -inner + 2 * inner * i / n
            k.ell([x0 + inner / n, -d + back + 0.06, (seat + k.h) / 2 + 0.02],
                  [inner / n * 0.9, 0.07, (k.h - seat) / 2 * 0.8], "cushion")


def chair(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    seat = b + min(0.46, 0.55 * 2 * k.h)
    back = min(0.05, d * 0.2)
    if k.v == 2:  # pedestal office chair
        k.cyl(0, 0, 0.03, b + 0.06, seat - 0.06, "metal")
        k.box([-w * 0.8, -0.03, b], [w * 0.8, 0.03, b + 0.06], "black")
        k.box([-0.03, -d * 0.8, b], [0.03, d * 0.8, b + 0.06], "black")
        k.box([-w, -d, seat - 0.07], [w, d, seat], "fabric")
        k.box([-w * 0.9, -d, seat + 0.05], [w * 0.9, -d + 0.08, k.h], "fabric")
        return
    k.legs(seat - 0.04, 0.022, 0.02, "wood", square=True)
    k.box([-w, -d, seat - 0.04], [w, d, seat], "wood" if k.v == 1 else "cushion")
    if k.v == 0:  # slats
        for x in np.linspace(-w + 0.03, w - 0.03, 4):
            k.box([x - 0.015, -d, seat], [x + 0.015, -d + back, k.h - 0.08], "wood")
        k.box([-w, -d, k.h - 0.1], [w, -d + back, k.h], "wood")
    else:
        k.box([-w, -d, seat], [w, -d + back, k.h], "wood" if k.v == 1 else "fabric")


def bench(k: Kit) -> None:
    top = k.h - min(0.05, k.h * 0.2)
    k.legs(top, 0.03, 0.05, "darkwood", square=True)
    k.box([-k.w, -k.d, top], [k.w, k.d, k.h], "wood")


def table(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    top = k.h - min(0.04, k.h * 0.3)
    k.box([-w, -d, top], [w, d, k.h], "wood")
    if k.v == 0:
        k.legs(top, 0.03, 0.05, "darkwood", square=True)
    elif k.v == 1:
        k.legs(top, 0.025, 0.08, "metal")
        k.box([-w + 0.1, -d + 0.1, top - 0.06], [w - 0.1, d - 0.1, top], "darkwood")
    else:  # two trestles
        for s in (-1, 1):
            x = s * (w - 0.15)
            k.box([x - 0.03, -d + 0.1, b + 0.04], [x + 0.03, d - 0.1, top], "darkwood")
            k.box([x - 0.05, -d + 0.05, b], [x + 0.05, d - 0.05, b + 0.04], "darkwood")


def desk(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    top = k.h - 0.04
    k.box([-w, -d, top], [w, d, k.h], "wood")
    side = -1 if k.v == 1 else 1
    x0, x1 = sorted([side * (w - 0.02), side * (w - min(0.45, w * 0.8))])
    k.box([x0, -d, b], [x1, d, top], "body")  # drawer block
    for z in np.linspace(b + 0.1, top - 0.12, 3):
        k.box([x0 + 0.03, d - 0.01, z], [x1 - 0.03, d, z + 0.02], "metal")
    other = -side * (w - 0.03)
    k.box([other - 0.03, -d + 0.02, b], [other + 0.03, d - 0.02, top], "body")


def bed(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    # The bed's front is the foot end; the headboard is at -y.
    frame = b + min(0.25, k.h * 0.45)
    k.box([-w, -d, b + 0.06], [w, d, frame], "darkwood" if k.v else "wood")
    k.legs(b + 0.06, 0.03, 0.05, "darkwood", square=True)
    mattress = min(k.h, frame + 0.2)
    k.box([-w + 0.03, -d + 0.06, frame], [w - 0.03, d - 0.03, mattress], "white")
    blanket_y = -d + (0.8 if d > 0.9 else d * 0.8)
    k.box([-w + 0.02, blanket_y, mattress - 0.05], [w - 0.02, d - 0.01, min(k.h, mattress + 0.03)],
          "fabric")
    k.box([-w, -d, b], [w, -d + 0.06, k.h], "darkwood" if k.v != 2 else "fabric")
    n = 2 if w > 0.6 else 1
    for i in range(n):
        x = -w + (2 * i + 1) * w / n
        k.ell([x, -d + 0.25, mattress + 0.01], [w / n * 0.75, 0.14, 0.06], "cushion")


def carcass(k: Kit, drawers: int = 0, doors: int = 0) -> None:
    """A cabinet body with drawer or door fronts and knobs on its front face."""
    w, d, b = k.w, k.d, k.bottom
    f = min(0.02, d * 0.2)
    k.box([-w, -d, b], [w, d - f, k.h], "body")
    plinth = min(0.06, k.h * 0.1)
    if drawers:
        step = (2 * k.h - plinth) / drawers
        for i in range(drawers):
            z0 = b + plinth + i * step
            k.box([-w + 0.01, d - f, z0 + 0.005], [w - 0.01, d, z0 + step - 0.005], "front")
            k.box([-0.04, d - f, z0 + step / 2 - 0.006], [0.04, d, z0 + step / 2 + 0.006],
                  "metal")
    elif doors:
        for i in range(doors):
            x0 = -w + 2 * w * i / doors
            x1 = x0 + 2 * w / doors
            k.box([x0 + 0.005, d - f, b + plinth], [x1 - 0.005, d, k.h - 0.01], "front")
            hx = x1 - 0.05 if i % 2 == 0 else x0 + 0.05
            k.box([hx - 0.006, d - f * 0.5, k.h - 0.25], [hx + 0.006, d, k.h - 0.1], "metal")


def cabinet(k: Kit) -> None:
    carcass(k, doors=max(1, min(4, round(k.w / 0.3))))


def drawers(k: Kit) -> None:
    """Drawer chests: fronts with knobs (0), with bars (1), or two columns (2)."""
    rows = max(1, min(5, round(k.h / 0.18)))
    if k.v == 2:
        for s_ in (-1, 1):
            sub = Kit(k.w / 2, k.d, k.h, 0)
            carcass(sub, drawers=rows)
            k.add(sub, np.array([s_ * k.w / 2, 0.0, 0.0]))
        return
    carcass(k, drawers=rows)
    if k.v == 1:
        k.shapes = [Shape(x.kind, x.center, x.half * [6 if x.role == "metal" else 1, 1, 1],
                          x.role, x.axis) for x in k.shapes]


def counter(k: Kit) -> None:
    top = k.h - min(0.04, k.h * 0.2)
    sub = Kit(k.w, k.d, (top - k.bottom) / 2, k.v)
    carcass(sub, doors=max(1, min(6, round(k.w / 0.3))))
    k.add(sub, np.array([0.0, 0.0, (top + k.bottom) / 2]))
    k.box([-k.w, -k.d, top], [k.w, k.d, k.h], "stone")


def shelf(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    t = min(0.02, d * 0.3)
    n = max(1, min(6, round(2 * k.h / 0.35)))
    for s in (-1, 1):
        k.box([s * w - t if s > 0 else -w, -d, b], [w if s > 0 else -w + t, d, k.h], "wood")
    if k.v != 1:  # variant 1 is open at the back
        k.box([-w, -d, b], [w, -d + t, k.h], "darkwood")
    if k.v == 2:  # a kick board under the lowest shelf
        k.box([-w, d - t, b], [w, d, b + min(0.08, k.h * 0.3)], "darkwood")
    for i in range(n + 1):
        z = b + i * (2 * k.h - t) / n
        k.box([-w, -d, z], [w, d, z + t], "wood")
        if i < n and n > 1 and k.h > 0.3:  # a row of books (one box, a striped texture)
            top = z + t + (0.55 + 0.1 * ((i + k.v) % 3)) * (2 * k.h / n - t)
            x0 = -w + t if (i + k.v) % 2 else -w * 0.3
            k.box([x0, -d + t, z + t], [w - t, d * 0.6, top], "books")


def wallshelf(k: Kit) -> None:
    """A board on brackets (0), a box shelf (1), or two boards (2)."""
    k.box([-k.w, -k.d, k.h - 0.03], [k.w, k.d, k.h], "wood")
    if k.v == 1:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.bottom + 0.03], "wood")
        for s_ in (-1, 1):
            k.box([s_ * k.w - 0.02 if s_ > 0 else -k.w, -k.d, k.bottom],
                  [k.w if s_ > 0 else -k.w + 0.02, k.d, k.h], "wood")
        return
    if k.v == 2:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.bottom + 0.03], "wood")
    for s_ in (-1, 1):
        x = s_ * (k.w - 0.05)
        k.box([x - 0.01, -k.d, k.bottom], [x + 0.01, -k.d + 0.02, k.h], "metal")


def sink(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    t = min(0.02, w * 0.1)
    k.box([-w, -d, b], [w, d, b + 0.01], "metal")
    for s in (-1, 1):
        k.box([s * w - t if s > 0 else -w, -d, b], [w if s > 0 else -w + t, d, k.h], "metal")
        k.box([-w, s * d - t if s > 0 else -d, b], [w, d if s > 0 else -d + t, k.h], "metal")


def faucet(k: Kit) -> None:
    r = min(k.w, k.d) * 0.25
    k.cyl(0, -k.d + r, r, k.bottom, k.h - r, "chrome")
    k.rod([0, r / 2, k.h - r], 1, r * 0.8, k.d - r * 1.5, "chrome")


def toilet(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    seat = b + min(0.42, 2 * k.h * 0.9)
    k.box([-w * 0.45, -d * 0.3, b], [w * 0.45, d * 0.5, seat - 0.06], "white")
    k.ell([0, d * 0.15, seat - 0.05], [w * 0.7, d * 0.8, 0.05], "white")
    k.box([-w, -d, seat - 0.05], [w, -d + min(0.2, d * 0.4), k.h], "white")


def bathtub(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    k.box([-w, -d, b], [w, d, b + 0.1], "white")
    for s in (-1, 1):
        k.box([s * w - 0.08 if s > 0 else -w, -d, b], [w if s > 0 else -w + 0.08, d, k.h],
              "white")
        k.box([-w, s * d - 0.08 if s > 0 else -d, b], [w, d if s > 0 else -d + 0.08, k.h],
              "white")


def rug(k: Kit) -> None:
    """A plain rug (0), one with a border (1), or a round one (2)."""
    if k.v == 2:
        k.cyl(0, 0, min(k.w, k.d), k.bottom, k.h, "fabric")
        return
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * (0.5 if k.v else 1)], "fabric")
    if k.v == 1:
        b = min(0.12, k.w * 0.2, k.d * 0.2)
        k.box([-k.w + b, -k.d + b, k.bottom], [k.w - b, k.d - b, k.h], "cushion")


def curtains(k: Kit) -> None:
    """Folds hanging from a rod: round folds (0), flat panels (1), tied back (2)."""
    n = max(2, min(4, round(k.w / 0.06)))
    xs = np.linspace(-k.w, k.w, n + 1)
    for i in range(n):
        r = (xs[i + 1] - xs[i]) / 2
        x = (xs[i] + xs[i + 1]) / 2
        if k.v == 1:
            k.box([xs[i], -k.d * (0.3 + 0.5 * (i % 2)), k.bottom], [xs[i + 1], k.d * 0.3,
                                                                    k.h - 0.02], "fabric")
        elif k.v == 2:
            k.ell([x, 0, 0], [r * 1.2, min(r * 1.3, k.d), k.h - 0.02], "fabric")
        else:
            k.cyl(x, 0, min(r * 1.3, k.d), k.bottom, k.h - 0.02, "fabric")
    k.rod([0, 0, k.h - 0.01], 0, 0.01, k.w, "metal")


def towelrack(k: Kit) -> None:
    k.rod([0, 0, 0], 0, min(k.h, k.d, 0.012), k.w, "chrome")


def hanger(k: Kit) -> None:
    """A bar hanger: wood (0), metal (1), or with a garment on it (2)."""
    k.rod([0, 0, k.h - 0.02], 1, 0.008, k.d, "metal" if k.v == 1 else "wood")
    if k.v == 2:
        k.box([-k.w * 0.5, -k.d * 0.9, k.bottom], [k.w * 0.5, k.d * 0.9, k.h - 0.03], "fabric")


def clothes_flat(k: Kit) -> None:
    """A garment: flat (0), folded in two layers (1), or hung with a collar (2)."""
    if k.v == 1:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, 0], "fabric")
        k.box([-k.w * 0.9, -k.d * 0.9, 0], [k.w * 0.9, k.d * 0.9, k.h], "cushion")
    elif k.v == 2:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * 0.8], "fabric")
        k.ell([0, 0, k.h * 0.8], [k.w, k.d * 0.4, k.h * 0.2], "cushion")
    else:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "fabric")


def clothespile(k: Kit) -> None:
    """A heap of clothes: one mound (0), two (1), or a folded stack (2)."""
    if k.v == 1:
        k.ell([-k.w * 0.3, 0, 0], [k.w * 0.7, k.d, k.h], "fabric")
        k.ell([k.w * 0.4, k.d * 0.2, -k.h * 0.2], [k.w * 0.6, k.d * 0.7, k.h * 0.8], "accent")
    elif k.v == 2:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, 0], "fabric")
        k.box([-k.w * 0.9, -k.d * 0.9, 0], [k.w * 0.9, k.d * 0.85, k.h], "accent")
    else:
        k.ell([0, 0, 0], [k.w, k.d, k.h], "fabric")


def stall(k: Kit) -> None:  # drawn by the enclosure shaper; kept for completeness
    k.box([-k.w, -k.d, k.bottom], [k.w, -k.d + 0.03, k.h], "body")


def window(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    t = 0.04
    k.box([-w, -d, b], [w, d, b + t], "white")
    k.box([-w, -d, k.h - t], [w, d, k.h], "white")
    k.box([-w, -d, b], [-w + t, d, k.h], "white")
    k.box([w - t, -d, b], [w, d, k.h], "white")
    k.box([-0.015, -d, b], [0.015, d, k.h], "white")
    k.box([-w + t, -0.005, b + t], [w - t, 0.005, k.h - t], "glass")


def picture(k: Kit) -> None:
    t = min(0.03, k.w * 0.15, k.h * 0.15)
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d * 0.5, k.h], "darkwood" if k.v else "metal")
    k.box([-k.w + t, k.d * 0.5, k.bottom + t], [k.w - t, k.d, k.h - t], f"art{k.v}")


# -- lamps and electronics ------------------------------------------------------------------

def ceilinglamp(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, 0.01, k.h - 0.1, k.h, "metal")
    if k.v == 0:
        k.cyl(0, 0, r, k.h - 0.14, k.h - 0.1, "glow")
    elif k.v == 1:
        k.ell([0, 0, k.h - 0.2], [r * 0.7, r * 0.7, min(0.12, k.h)], "glow")
    else:
        k.cyl(0, 0, r * 0.8, k.h - 0.3, k.h - 0.1, "glow")


def walllamp(k: Kit) -> None:
    """A sconce: a glowing cylinder (0), a globe (1), or an up-light bowl (2)."""
    r = min(k.w, k.d)
    k.box([-r * 0.3, -k.d, -0.05], [r * 0.3, -k.d + 0.02, 0.05], "metal")
    k.rod([0, -k.d / 2, 0], 1, 0.01, k.d / 2, "metal")
    if k.v == 1:
        k.ell([0, k.d * 0.3, k.h * 0.2], [r * 0.6, r * 0.6, min(r * 0.6, k.h)], "glow")
    elif k.v == 2:
        k.ell([0, k.d * 0.3, k.h * 0.5], [r * 0.7, r * 0.7, k.h * 0.3], "glow")
    else:
        k.cyl(0, k.d * 0.3, r * 0.6, -k.h * 0.2, k.h * 0.5, "glow")


def tablelamp(k: Kit) -> None:
    r = min(k.w, k.d)
    b = k.bottom
    k.cyl(0, 0, r * 0.45, b, b + 0.03, "metal")
    k.cyl(0, 0, 0.012, b + 0.03, k.h * 0.2, "metal")
    if k.v == 2:
        k.ell([0, 0, b + 0.25 * 2 * k.h], [r * 0.5, r * 0.5, 0.25 * k.h], "body")
    shade = k.h * 0.5
    k.cyl(0, 0, r, k.h - shade, k.h, "glow", kind="cylinder" if k.v != 1 else "ellipsoid")


def floorlamp(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r * 0.5, k.bottom, k.bottom + 0.03, "metal")
    k.cyl(0, 0, 0.015, k.bottom, k.h - 0.3, "metal")
    k.cyl(0, 0, r, k.h - 0.35, k.h, "glow")


def tv(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    stand = min(0.1, k.h * 0.15)
    if k.v == 1:  # two feet
        for s in (-1, 1):
            k.box([s * w * 0.7 - 0.02, -d * 0.6, b], [s * w * 0.7 + 0.02, d * 0.6, b + stand],
                  "black")
    else:
        k.box([-w * 0.3, -d * 0.6, b], [w * 0.3, d * 0.6, b + 0.015], "black")
        k.box([-0.03, -0.02, b], [0.03, 0.02, b + stand + 0.05], "black")
    k.box([-w, -0.03, b + stand], [w, 0.01, k.h], "black")
    k.box([-w + 0.02, 0.01, b + stand + 0.02], [w - 0.02, min(0.02, d), k.h - 0.02], "screen")


def monitor(k: Kit) -> None:
    tv(k)


def computer(k: Kit) -> None:
    if k.h > 0.3:  # a tower
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "black")
        k.box([-k.w * 0.6, k.d - 0.005, k.h - 0.12], [k.w * 0.6, k.d, k.h - 0.08], "metal")
        k.cyl(0, k.d - 0.01, 0.01, k.h - 0.2, k.h - 0.18, "glow")
    else:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "black")


def keyboard(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.bottom + 0.6 * 2 * k.h], "black")
    k.box([-k.w + 0.01, -k.d + 0.01, k.bottom], [k.w - 0.01, k.d - 0.01, k.h], "white")


def mouse(k: Kit) -> None:
    k.ell([0, 0, k.bottom], [min(k.w, 0.035), min(k.d, 0.06), 2 * k.h], "black")


def plate_on_wall(k: Kit) -> None:
    """Light switches and sockets: a plate with a toggle (0), two (1), or a round one (2)."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d * 0.3, k.h], "white")
    if k.v == 1:
        for s_ in (-1, 1):
            k.box([-k.w * 0.3, k.d * 0.3, s_ * k.h * 0.45 - k.h * 0.2],
                  [k.w * 0.3, k.d, s_ * k.h * 0.45 + k.h * 0.2], "black")
    elif k.v == 2:
        k.rod([0, k.d * 0.65, 0], 1, min(k.w, k.h) * 0.45, k.d * 0.35, "metal")
    else:
        k.box([-k.w * 0.3, k.d * 0.3, -k.h * 0.3], [k.w * 0.3, k.d, k.h * 0.3], "black")


def radio(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "body")
    r = min(k.w, k.h) * 0.45
    k.rod([-k.w * 0.45, k.d - 0.005, 0], 1, r, 0.005, "black")
    k.box([k.w * 0.1, k.d - 0.01, 0], [k.w * 0.9, k.d, k.h * 0.6], "black")


def phone(k: Kit) -> None:
    """A phone or remote: black (0), light (1) or with a coloured case (2); the face is
    the top for flat ones, the front for upright ones."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], ("black", "white", "body")[k.v])
    thin = int(np.argmin([k.w, k.d, k.h]))
    lo = np.array([-k.w, -k.d, k.bottom]) * 0.85
    hi = np.array([k.w, k.d, k.h]) * 0.85
    full = np.array([k.w, k.d, k.h])
    lo[thin], hi[thin] = full[thin] * 0.8, full[thin]
    k.box(lo, hi, "screen_dark")


def clock(k: Kit) -> None:
    thin = 0 if k.w < k.d else 1
    r = min(max(k.w, k.d), k.h)
    half = min(k.w, k.d)
    k.rod([0, 0, 0], thin, r, half, "white")
    k.rod([0, 0, 0], thin, r * 1.0, half * 0.3, "black")


# -- appliances -----------------------------------------------------------------------------

def appliance(k: Kit) -> None:
    """A box appliance with a control strip on its front."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "body")
    k.box([-k.w * 0.9, k.d - 0.01, k.h * 0.6], [k.w * 0.9, k.d, k.h * 0.9], "black")


def fridge(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.03, k.h], "body")
    split = k.bottom + 2 * k.h * 0.62
    k.box([-k.w, k.d - 0.03, k.bottom], [k.w, k.d - 0.01, split - 0.005], "body")
    k.box([-k.w, k.d - 0.03, split + 0.005], [k.w, k.d - 0.01, k.h], "body")
    for z0, z1 in ((split - 0.45, split - 0.05), (split + 0.05, split + 0.3)):
        k.box([k.w - 0.08, k.d - 0.01, z0], [k.w - 0.06, k.d, min(z1, k.h)], "chrome")


def stove(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    k.box([-w, -d, b], [w, d - 0.02, k.h - 0.02], "body")
    k.box([-w, -d, k.h - 0.02], [w, d, k.h], "black")
    for sx in (-1, 1):
        for sy in (-1, 1):
            k.cyl(sx * w * 0.45, sy * d * 0.4, min(w, d) * 0.22, k.h - 0.025, k.h, "metal")
    k.box([-w * 0.85, d - 0.02, b + 0.1], [w * 0.85, d, k.h - 0.2], "glass_dark")
    k.box([-w * 0.7, d - 0.01, k.h - 0.17], [w * 0.7, d, k.h - 0.15], "chrome")


def stovefan(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.bottom + 0.08], "metal")
    k.box([-k.w * 0.3, -k.d, k.bottom + 0.08], [k.w * 0.3, -k.d + 0.3 * k.d, k.h], "metal")


def microwave(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "body")
    k.box([-k.w + 0.02, k.d - 0.01, k.bottom + 0.03], [k.w * 0.4, k.d, k.h - 0.03],
          "glass_dark")
    k.box([k.w * 0.5, k.d - 0.01, k.bottom + 0.03], [k.w - 0.02, k.d, k.h - 0.03], "black")


def washer(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "white")
    r = min(k.w, k.h) * 0.55
    k.rod([0, k.d - 0.005, -k.h * 0.1], 1, r, 0.005, "glass_dark")
    k.box([-k.w, k.d - 0.01, k.h - 0.12], [k.w, k.d, k.h - 0.02], "metal")


def toaster(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h - 0.01], "chrome")
    for s in (-1, 1):
        k.box([s * k.w * 0.3 - 0.015, -k.d * 0.7, k.h - 0.01],
              [s * k.w * 0.3 + 0.015, k.d * 0.7, k.h], "black")


def coffeemaker(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    k.box([-w, -d, b], [w, -d + d * 0.8, k.h], "black")
    k.box([-w, -d, k.h - 2 * k.h * 0.25], [w, d, k.h], "black")
    k.box([-w, -d, b], [w, d, b + 0.03], "black")
    k.cyl(0, d * 0.4, min(w, d) * 0.5, b + 0.03, b + 2 * k.h * 0.5, "glass")


def oventray(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "metal")


# -- small objects --------------------------------------------------------------------------

def mug(k: Kit) -> None:
    r = min(k.w, k.d) * 0.78
    k.cyl(-k.w + r, 0, r, k.bottom, k.h, "body" if k.v else "white")
    hx = -k.w + 2 * r
    k.box([hx, -0.006, -k.h * 0.5], [min(k.w, hx + r * 0.6), 0.006, k.h * 0.6], "body"
          if k.v else "white")


def glass(k: Kit) -> None:
    """A tumbler (0), a tapered glass (1), or one with juice in it (2)."""
    r = min(k.w, k.d)
    if k.v == 1:
        k.cyl(0, 0, r * 0.75, k.bottom, 0, "glass")
        k.cyl(0, 0, r, 0, k.h, "glass")
        return
    k.cyl(0, 0, r, k.bottom, k.h, "glass")
    if k.v == 2:
        k.cyl(0, 0, r * 0.85, k.bottom + 0.005, k.h * 0.3, "accent")


def wineglass(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r * 0.7, k.bottom, k.bottom + 0.005, "glass")
    k.ell([0, 0, k.h * 0.2], [r, r, k.h * 0.8], "glass")


def plate(k: Kit) -> None:
    """A round plate (0), one with a coloured rim (1), or a square one (2)."""
    r = min(k.w, k.d)
    if k.v == 2:
        k.box([-r, -r, k.bottom], [r, r, k.h], "white")
        return
    k.cyl(0, 0, r * 0.7 if k.v == 1 else r, k.bottom, k.h, "white")
    if k.v == 1:
        k.cyl(0, 0, r, k.h * 0.2, k.h, "body")


def bowl(k: Kit) -> None:
    """A round bowl (0), a straight-sided one (1), or one on a foot (2)."""
    r = min(k.w, k.d)
    if k.v == 1:
        k.cyl(0, 0, r, k.bottom, k.h, "body")
    elif k.v == 2:
        k.cyl(0, 0, r * 0.5, k.bottom, k.bottom + k.h * 0.4, "body")
        k.ell([0, 0, k.h], [r, r, k.h * 1.6], "white")
    else:
        k.ell([0, 0, k.h], [r, r, 2 * k.h], "body")


def pot(k: Kit) -> None:
    r = min(k.w, k.d) * 0.7
    k.cyl(0, 0, r, k.bottom, k.h, "metal")
    k.rod([r + (k.w - r) / 2, 0, k.h * 0.5], 0, min(0.012, k.h), (k.w - r) / 2, "black")


def fryingpan(k: Kit) -> None:
    r = min(k.w, k.d) * 0.6
    k.cyl(-k.w + r, 0, r, k.bottom, k.h, "black")
    k.rod([r / 2 + k.w / 2 - r / 2, 0, 0], 0, min(0.015, k.h), (k.w - r) / 2 + r / 4,
          "black")


def book(k: Kit) -> None:
    """A cover and, showing on three edges, the pages."""
    covers = ("book0", "book1", "book2", "book3")
    thin = int(np.argmin([k.w, k.d, k.h]))
    lo, hi = np.array([-k.w, -k.d, k.bottom]), np.array([k.w, k.d, k.h])
    cover_hi = np.where(np.arange(3) == thin, hi, hi * 0.94)
    k.box(lo, cover_hi, covers[k.v % len(covers)])
    pages_lo = np.where(np.arange(3) == thin, lo * 0.75, lo * 0.9)
    pages_hi = np.where(np.arange(3) == thin, hi * 0.75, hi)
    k.box(pages_lo, pages_hi, "paper")


def bottle(k: Kit) -> None:
    """A bottle with a neck (0), a pump bottle (1), or a squat flask (2)."""
    r = min(k.w, k.d)
    if k.v == 2:
        k.box([-k.w, -k.d * 0.6, k.bottom], [k.w, k.d * 0.6, k.h * 0.6], "body")
        k.cyl(0, 0, r * 0.3, k.h * 0.6, k.h, "accent")
        return
    neck = k.h - 2 * k.h * 0.3
    k.cyl(0, 0, r, k.bottom, neck, "body")
    if k.v == 1:
        k.cyl(0, 0, r * 0.25, neck, k.h, "white")
        k.box([0, -0.004, k.h - 0.015], [r, 0.004, k.h], "white")
    else:
        k.cyl(0, 0, r * 0.4, neck, k.h, "accent")


def jar(k: Kit) -> None:
    """A jar with a lid (0), a shaker with a cap (1), or a rounded pot (2)."""
    r = min(k.w, k.d)
    if k.v == 2:
        k.ell([0, 0, -k.h * 0.1], [r, r, k.h * 0.9], "body")
        k.cyl(0, 0, r * 0.5, k.h * 0.7, k.h, "accent")
        return
    lid = k.h - min(0.03, k.h * 0.3)
    k.cyl(0, 0, r if k.v == 0 else r * 0.8, k.bottom, lid, "body" if k.v == 0 else "glass")
    k.cyl(0, 0, r, lid, k.h, "accent" if k.v == 0 else "metal")


def carton(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * 0.7], "body")
    k.box([-k.w, -k.d * 0.2, k.h * 0.7], [k.w, k.d * 0.2, k.h], "white")
    k.box([-k.w, k.d - 0.002, -k.h * 0.3], [k.w * 0.6, k.d, k.h * 0.3], "label")


def package(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "body")
    k.box([-k.w * 0.7, k.d - 0.002, -k.h * 0.4], [k.w * 0.7, k.d, k.h * 0.5], "label")


def tube(k: Kit) -> None:
    big = int(np.argmax([k.w, k.d, k.h]))
    half = np.array([k.w, k.d, k.h])
    r = float(min(np.delete(half, big)))
    center = np.zeros(3)
    k.rod(center, big, r, half[big], "body", kind="capsule")
    cap = center.copy()
    cap[big] = half[big] - r
    k.rod(cap, big, r * 0.6, r, "accent")


def utensil(k: Kit) -> None:
    """Cutlery and tools: a handle and a blade or head along the long axis; steel (0),
    dark handle (1) or wooden handle (2)."""
    big = int(np.argmax([k.w, k.d, k.h]))
    half = np.array([k.w, k.d, k.h])
    split = -half[big] + 2 * half[big] * 0.55
    hi_handle = half.copy()
    hi_handle[big] = split
    k.box(-half, hi_handle, ("metal", "black", "wood")[k.v])
    lo_head = -half * 0.6
    lo_head[big] = split
    hi_head = half * 0.6
    hi_head[big] = half[big]
    k.box(lo_head, hi_head, "chrome")


def toothbrush(k: Kit) -> None:
    big = int(np.argmax([k.w, k.d, k.h]))
    half = np.array([k.w, k.d, k.h])
    r = max(0.004, float(min(np.delete(half, big))) * 0.5)
    k.rod(np.zeros(3), big, r, half[big], "body", kind="capsule")
    head = np.zeros(3)
    head[big] = half[big] * 0.8
    hh = np.full(3, r * 1.2)
    hh[big] = half[big] * 0.15
    k.box(head - hh, head + hh, "white")


def fruit(k: Kit) -> None:
    """A round fruit (0), a flatter one (1), or one with a stalk and leaf (2)."""
    if k.v == 1:
        k.ell([0, 0, -k.h * 0.15], [k.w, k.d, k.h * 0.85], "body")
        return
    k.ell([0, 0, 0], [k.w, k.d, k.h], "body")
    if k.v == 2:
        k.box([0, -0.002, k.h * 0.7], [min(k.w, 0.03), 0.002, k.h], "leaf")


def bananas(k: Kit) -> None:
    long = 0 if k.w > k.d else 1
    half = np.array([k.w, k.d, k.h])
    r = min(half[1 - long] / 3, k.h)
    for i in (-1, 0, 1):
        c = np.zeros(3)
        c[1 - long] = i * r * 1.8
        k.rod(c, long, r, half[long], "body", kind="capsule")


def cake(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "body")


def cupcake(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r * 0.75, k.bottom, 0, "accent")
    k.ell([0, 0, 0], [r, r, k.h], "body")


def slab(k: Kit) -> None:
    """Flat things (paper, towels, folders, slices): a slab (0), one with a band (1), or
    two stacked (2)."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h if k.v != 2 else 0], "body")
    if k.v == 1:
        k.box([-k.w, -k.d * 0.2, k.bottom], [k.w, k.d * 0.2, k.h], "accent")
    elif k.v == 2:
        k.box([-k.w * 0.9, -k.d * 0.9, 0], [k.w * 0.85, k.d * 0.9, k.h], "body")


def rounded(k: Kit) -> None:
    """Soft things (pillows, sponges, buns): an ellipsoid (0), a cushion with a seam (1),
    or a roll (2)."""
    if k.v == 1:
        k.ell([0, 0, 0], [k.w, k.d, k.h], "fabric")
        k.box([-k.w * 0.7, -k.d * 0.7, -k.h * 0.1], [k.w * 0.7, k.d * 0.7, k.h * 0.1], "accent")
    elif k.v == 2:
        long = 0 if k.w > k.d else 1
        half = np.array([k.w, k.d, k.h])
        k.rod([0, 0, 0], long, float(min(half[1 - long], k.h)), half[long], "body",
              kind="capsule")
    else:
        k.ell([0, 0, 0], [k.w, k.d, k.h], "body")


def candle(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "white")


def plant(k: Kit) -> None:
    r = min(k.w, k.d)
    pot_top = k.bottom + 2 * k.h * 0.35
    k.cyl(0, 0, r * 0.55, k.bottom, pot_top, "white" if k.v else "body")
    k.ell([0, 0, (pot_top + k.h) / 2], [r, r, (k.h - pot_top) / 2], "leaf")


def garbagecan(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "metal")


def bucket(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "body")


def knifeblock(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * 0.5], "wood")
    k.box([-k.w * 0.6, -k.d * 0.6, k.h * 0.5], [k.w * 0.6, k.d * 0.6, k.h], "black")


def slippers(k: Kit) -> None:
    for s in (-1, 1):
        k.ell([s * k.w * 0.5, 0, 0], [k.w * 0.45, k.d, k.h], "body")


def toy(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w * 0.2, k.d * 0.2, k.h * 0.2], "body")
    k.ell([k.w * 0.5, k.d * 0.5, k.h * 0.5], [k.w * 0.5, k.d * 0.5, k.h * 0.5], "accent")


def box_generic(k: Kit) -> None:
    """A box: taped (0), with a lid (1), or open with flaps (2)."""
    if k.v == 1:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * 0.6], "body")
        k.box([-k.w, -k.d, k.h * 0.6], [k.w, k.d, k.h], "accent")
    elif k.v == 2:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * 0.7], "body")
        k.box([-k.w, -k.d, k.h * 0.7], [k.w, -k.d * 0.9, k.h], "body")
        k.box([-k.w, k.d * 0.9, k.h * 0.7], [k.w, k.d, k.h], "body")
    else:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "body")
        k.box([-k.w, -k.d * 0.05, k.h - 0.003], [k.w, k.d * 0.05, k.h], "accent")


def generic_furniture(k: Kit) -> None:
    """A body on a plinth with a top: shelves, stands, unknown furniture."""
    k.box([-k.w, -k.d, k.bottom + 0.05], [k.w, k.d, k.h - 0.03], "body")
    k.box([-k.w * 0.95, -k.d * 0.95, k.bottom], [k.w * 0.95, k.d * 0.95, k.bottom + 0.05],
          "darkwood")
    k.box([-k.w, -k.d, k.h - 0.03], [k.w, k.d, k.h], "wood")


def tvstand(k: Kit) -> None:
    if k.v == 1:
        carcass(k, drawers=2)
    else:
        generic_furniture(k)


def generic_prop(k: Kit) -> None:
    """A small object: tall ones as bottles, flat ones as slabs, others packages."""
    if k.h > 1.8 * max(k.w, k.d):
        bottle(k)
    elif k.h < 0.25 * max(k.w, k.d):
        slab(k)
    else:
        package(k)


def generic_food(k: Kit) -> None:
    if k.h < 0.3 * max(k.w, k.d):
        cake(k) if abs(k.w - k.d) < 0.2 * max(k.w, k.d) else slab(k)
    else:
        rounded(k)


MODELS: dict[str, Builder] = {
    # furniture
    "sofa": sofa, "couch": sofa, "loveseat": sofa, "chair": chair, "armchair": chair,
    "bench": bench, "kitchentable": table, "coffeetable": table, "table": table,
    "sidetable": table, "diningtable": table, "desk": desk, "bed": bed,
    "nightstand": drawers, "dresser": drawers, "closetdrawer": drawers, "cabinet": cabinet,
    "kitchencabinets": cabinet, "kitchencabinet": cabinet, "bathroomcabinet": cabinet,
    "closet": cabinet, "kitchencounter": counter, "bathroomcounter": counter,
    "bookshelf": shelf, "shelf": shelf, "wallshelf": wallshelf, "sink": sink,
    "faucet": faucet, "toilet": toilet, "bathtub": bathtub, "rug": rug, "mat": rug,
    "curtains": curtains, "towelrack": towelrack, "hanger": hanger,
    "clothespants": clothes_flat, "clothesshirt": clothes_flat, "clothespile": clothespile,
    "stall": stall, "window": window, "wallpictureframe": picture, "photoframe": picture,
    "picture": picture, "tvstand": tvstand, "pianobench": bench, "shoerack": shelf,
    # lamps, electronics
    "ceilinglamp": ceilinglamp, "walllamp": walllamp, "tablelamp": tablelamp,
    "floorlamp": floorlamp, "lamp": tablelamp, "desklamp": tablelamp, "tv": tv,
    "television": tv, "cpuscreen": monitor, "computer": computer, "laptop": keyboard,
    "keyboard": keyboard, "mouse": mouse, "mousemat": slab, "lightswitch": plate_on_wall,
    "powersocket": plate_on_wall, "radio": radio, "stereo": radio, "cdplayer": radio,
    "dvdplayer": radio, "wallphone": phone, "cellphone": phone, "phone": phone,
    "telephone": phone, "remotecontrol": phone, "clock": clock, "alarmclock": clock,
    "console": radio, "headset": rounded,
    # appliances
    "fridge": fridge, "stove": stove, "oven": stove, "stovefan": stovefan,
    "microwave": microwave, "washingmachine": washer, "dishwasher": washer,
    "toaster": toaster, "coffeemaker": coffeemaker, "oventray": oventray,
    "blender": coffeemaker, "kettle": jar,
    # tableware and kitchen things
    "mug": mug, "cup": mug, "coffeecup": mug, "waterglass": glass, "glass": glass,
    "drinkingglass": glass, "measuringcup": mug, "wineglass": wineglass, "plate": plate,
    "dishbowl": bowl, "bowl": bowl, "cookingpot": pot, "pot": pot, "saucepan": pot,
    "coffeepot": jar, "fryingpan": fryingpan, "cutleryknife": utensil,
    "cutleryfork": utensil, "fork": utensil, "knife": utensil, "spoon": utensil,
    "woodenspoon": utensil, "chefknife": utensil, "knifeblock": knifeblock,
    "cuttingboard": slab, "tray": oventray, "colander": bowl, "dishrack": oventray,
    # bathroom, personal
    "toothbrush": toothbrush, "toothpaste": tube, "barsoap": rounded, "soap": rounded,
    "towel": slab, "toiletpaper": jar, "hairproduct": bottle, "facecream": jar,
    "deodorant": bottle, "perfume": bottle, "painkillers": jar, "shampoo": bottle,
    "conditioner": bottle, "mouthwash": bottle, "comb": utensil, "hairbrush": utensil,
    "razor": utensil, "washingsponge": slab, "sponge": slab, "dishwashingliquid": bottle,
    "dishsoap": bottle,
    # paper, decor, misc
    "book": book, "novel": book, "textbook": book, "notebook": book, "magazine": slab,
    "folder": slab, "paper": slab, "notes": slab, "papertray": oventray, "box": box_generic,
    "candle": candle, "orchid": plant, "plant": plant, "pillow": rounded, "cushion": rounded,
    "blanket": slab, "garbagecan": garbagecan, "bucket": bucket, "mopbucket": bucket,
    "slippers": slippers, "shoes": slippers, "toy": toy,
    # food
    "apple": fruit, "peach": fruit, "plum": fruit, "pear": fruit, "lime": fruit,
    "lemon": fruit, "orange": fruit, "bellpepper": fruit, "bananas": bananas,
    "banana": bananas, "cupcake": cupcake, "pie": cake, "poundcake": cake, "cake": cake,
    "pancake": cake, "pudding": jar, "milkshake": glass, "juice": carton, "milk": carton,
    "cereal": package, "crackers": package, "chips": package, "candybar": slab,
    "chocolatesyrup": bottle, "whippedcream": bottle, "condimentbottle": bottle,
    "condimentshaker": jar, "breadslice": slab, "cutlets": slab, "salmon": slab,
    "mincedmeat": slab, "chicken": rounded, "creamybuns": rounded,
    # classes the knowledge base can add
    "addressbook": book, "diary": book, "notepad": book, "homework": slab, "bills": slab,
    "check": slab, "document": slab, "drawing": slab, "envelope": slab, "form": slab,
    "mail": slab, "receipt": slab, "newspaper": slab, "printingpaper": slab,
    "papertowel": jar, "napkin": slab, "clothnapkin": slab, "placemat": slab,
    "tablecloth": slab, "sheets": slab, "comforter": slab, "rag": slab, "cd": plate,
    "coin": plate, "creditcard": slab, "cards": slab, "deckofcards": package,
    "boardgame": package, "scrabble": package, "chessboard": slab, "stamp": slab,
    "aftershave": bottle, "alcohol": bottle, "beer": bottle, "wine": bottle, "oil": bottle,
    "sauce": bottle, "cleaningsolution": bottle, "detergent": bottle,
    "laundrydetergent": bottle, "facialcleanser": bottle, "foundation": jar,
    "nailpolish": bottle, "shavingcream": bottle, "glue": tube, "jelly": jar,
    "coffee": jar, "groundcoffee": jar, "tea": package, "teabag": slab,
    "coffeefilter": bowl, "drypasta": package, "pasta": package, "groceries": package,
    "bag": package, "purse": package, "shoeshinekit": box_generic, "band-aids": package,
    "bandaids": package, "pen": utensil, "pencil": utensil, "mechanicalpencil": utensil,
    "highlighter": utensil, "crayon": utensil, "laserpointer": utensil, "needle": utensil,
    "broom": utensil, "mop": utensil, "dustpan": slab, "brush": utensil, "scissors": utensil,
    "keys": utensil, "lighter": package, "electricshaver": phone, "controller": phone,
    "videogamecontroller": phone, "microphone": bottle, "hairdryer": toaster,
    "blowdryer": toaster, "iron": toaster, "vacuumcleaner": appliance, "lightbulb": fruit,
    "spectacles": utensil, "thread": jar, "tape": jar, "button": plate, "dough": rounded,
    "ice": package, "dirt": rounded, "hair": rounded, "teeth": rounded, "cat": rounded,
    "dog": rounded, "instrumentguitar": bananas, "instrumentviolin": bananas,
    "centerpiece": plant, "toothbrushholder": glass, "ovenmitts": rounded,
    "pajamas": clothes_flat, "basketforclothes": bucket, "bookmark": slab,
}
"""Class (spelled without underscores) -> builder."""

_WORDS: tuple[tuple[str, Builder], ...] = (
    ("food", generic_food), ("cloth", clothes_flat), ("lamp", tablelamp), ("glass", glass),
    ("cup", mug), ("bottle", bottle),
    ("table", table), ("chair", chair), ("sofa", sofa), ("cabinet", cabinet),
    ("shelf", shelf), ("book", book),
    ("knife", utensil), ("spoon", utensil), ("soap", rounded), ("paper", slab),
)
"""Words inside a class name (checked in order) for classes without a model of their own."""

_CATEGORIES: dict[str, Builder] = {
    "Furniture": generic_furniture, "Appliances": appliance, "Electronics": radio,
    "Lamps": tablelamp, "Food": generic_food, "Foods": generic_food, "Decor": generic_prop,
    "Props": generic_prop,
}

VARIANTS: dict[Builder, int] = {
    sofa: 3, chair: 3, table: 3, desk: 2, bed: 3, ceilinglamp: 3, tablelamp: 3, tv: 2,
    picture: 3, book: 4, mug: 3, plate: 3, bottle: 3, plant: 2, tvstand: 2, shelf: 3,
    drawers: 3, wallshelf: 3, rug: 3, curtains: 3, hanger: 3, clothes_flat: 3,
    clothespile: 3, walllamp: 3, plate_on_wall: 3, phone: 3, glass: 3, bowl: 3, fruit: 3,
    slab: 3, rounded: 3, box_generic: 3, jar: 3, utensil: 3,
}
"""Builders that take a variant and how many they have (others draw one model)."""


def builder_for(class_name: str, category: str | None = None) -> Builder:
    """The builder of a class: by name, by a word in the name, by category, else a box."""
    name = class_name.lower().replace("_", "").replace(" ", "")
    if name in MODELS:
        return MODELS[name]
    for word, builder in _WORDS:
        if word in name:
            return builder
    return _CATEGORIES.get(category or "", generic_prop)


def variant_of(class_name: str, seed: int, key: int = 0) -> int:
    """The variant a class gets for a seed (objects sharing `key`, e.g. a room, match)."""
    builder = builder_for(class_name)
    n = VARIANTS.get(builder, 1)
    return zlib.crc32(f"{class_name}:{seed}:{key}".encode()) % n


def _clamp(s: Shape, half: np.ndarray) -> Shape:
    """Shrink a shape so its box stays inside [-half, half]."""
    lo = np.clip(s.center - s.half, -half, half - 2e-3)
    hi = np.clip(s.center + s.half, lo + 2e-3, half)
    hs = (hi - lo) / 2
    if s.kind in ("cylinder", "capsule"):  # keep the section round
        across = [a for a in range(3) if a != s.axis]
        r = float(min(hs[across[0]], hs[across[1]]))
        hs[across] = r
        if s.kind == "capsule":
            hs[s.axis] = max(hs[s.axis], r)
    return Shape(s.kind, (lo + hi) / 2, hs, s.role, s.axis)


def local_model(class_name: str, category: str | None, half: np.ndarray,
                variant: int = 0) -> list[Shape]:
    """A class's shapes in the local frame of a box with half sizes (w, d, h)."""
    w, d, h = (max(float(x), 0.004) for x in half)
    kit = Kit(w, d, h, variant)
    builder_for(class_name, category)(kit)
    bound = np.array([w, d, h])
    return [_clamp(s, bound) for s in kit.shapes]


def fit_model(class_name: str, category: str | None, center: np.ndarray, half: np.ndarray,
              front: tuple[int, float], variant: int = 0) -> list[Shape]:
    """A class's model fitted to a box (MuJoCo frame), its local +y facing `front`
    (axis 0 or 1 and sign, as `layout._front_axis` gives)."""
    axis, sign = front
    side = 1 - axis
    local_half = np.array([half[side], half[axis], half[2]])
    perm = np.array([side, axis, 2])  # local axis k -> world axis perm[k]
    flip = np.array([sign if axis == 1 else -sign, sign, 1.0])  # a turn about z
    out = []
    for s in local_model(class_name, category, local_half, variant):
        c = np.zeros(3)
        h = np.zeros(3)
        c[perm] = s.center * flip
        h[perm] = s.half
        out.append(Shape(s.kind, np.asarray(center, float) + c, h, s.role, int(perm[s.axis])))
    return out


__all__ = ["KINDS", "MODELS", "VARIANTS", "Shape", "builder_for", "fit_model",
           "local_model", "variant_of"]
