"""Furniture models: sofas, chairs, tables, beds, cabinets, shelves, bathroom fixtures,
textiles, windows and pictures."""

from __future__ import annotations

import numpy as np

from homesim.render.models.kit import Kit, Shape, builder

L_SOFA = 0.8
"""Half metres: a sofa box at least 1.6 m deep as well as wide is an L-shaped sofa."""


@builder(variants=3)
def sofa(k: Kit) -> None:
    """A sofa: legs, base, seat cushions, backrest, arms (variants 1, 2) and back pillows
    (variants 0, 2); a box deep and wide (`L_SOFA`) is an L: a straight sofa along the
    back and a chaise along one end (the end by the variant), the corner inside free."""
    if k.w >= L_SOFA and k.d >= L_SOFA:
        _l_sofa(k)
        return
    _straight_sofa(k)


def _l_sofa(k: Kit) -> None:
    depth = min(0.95, k.d * 0.6)  # of each wing
    back = Kit(k.w, depth / 2, k.h, k.v)
    _straight_sofa(back)
    k.add(back, np.array([0.0, -k.d + depth / 2, 0.0]))
    end = 1.0 if k.v % 2 else -1.0
    wing_len = k.d - depth / 2
    chaise = Kit(depth / 2, wing_len, k.h, k.v)  # a seat without back, toward the front
    _chaise(chaise)
    k.add(chaise, np.array([end * (k.w - depth / 2), k.d - wing_len, 0.0]))


def _chaise(k: Kit) -> None:
    b = k.bottom
    seat = b + min(0.45, 1.2 * k.h)
    k.legs(b + 0.06, 0.025, 0.04, "darkwood", square=True)
    k.box([-k.w, -k.d, b + 0.06], [k.w, k.d, seat - 0.12], "fabric")
    k.box([-k.w + 0.01, -k.d, seat - 0.12], [k.w - 0.01, k.d - 0.01, seat], "cushion")


def _straight_sofa(k: Kit) -> None:
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


@builder(variants=3)
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


@builder()
def bench(k: Kit) -> None:
    top = k.h - min(0.05, k.h * 0.2)
    k.legs(top, 0.03, 0.05, "darkwood", square=True)
    k.box([-k.w, -k.d, top], [k.w, k.d, k.h], "wood")


@builder(variants=3)
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


@builder(variants=2)
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


@builder(variants=3)
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


@builder()
def cabinet(k: Kit) -> None:
    carcass(k, doors=max(1, min(4, round(k.w / 0.3))))


@builder(variants=3)
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


@builder()
def counter(k: Kit) -> None:
    top = k.h - min(0.04, k.h * 0.2)
    sub = Kit(k.w, k.d, (top - k.bottom) / 2, k.v)
    carcass(sub, doors=max(1, min(6, round(k.w / 0.3))))
    k.add(sub, np.array([0.0, 0.0, (top + k.bottom) / 2]))
    k.box([-k.w, -k.d, top], [k.w, k.d, k.h], "stone")


@builder(variants=3)
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


@builder(variants=3)
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


@builder()
def sink(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    t = min(0.02, w * 0.1)
    k.box([-w, -d, b], [w, d, b + 0.01], "metal")
    for s in (-1, 1):
        k.box([s * w - t if s > 0 else -w, -d, b], [w if s > 0 else -w + t, d, k.h], "metal")
        k.box([-w, s * d - t if s > 0 else -d, b], [w, d if s > 0 else -d + t, k.h], "metal")


@builder()
def faucet(k: Kit) -> None:
    r = min(k.w, k.d) * 0.25
    k.cyl(0, -k.d + r, r, k.bottom, k.h - r, "chrome")
    k.rod([0, r / 2, k.h - r], 1, r * 0.8, k.d - r * 1.5, "chrome")


@builder()
def toilet(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    seat = b + min(0.42, 2 * k.h * 0.9)
    k.box([-w * 0.45, -d * 0.3, b], [w * 0.45, d * 0.5, seat - 0.06], "white")
    k.ell([0, d * 0.15, seat - 0.05], [w * 0.7, d * 0.8, 0.05], "white")
    k.box([-w, -d, seat - 0.05], [w, -d + min(0.2, d * 0.4), k.h], "white")


@builder()
def bathtub(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    k.box([-w, -d, b], [w, d, b + 0.1], "white")
    for s in (-1, 1):
        k.box([s * w - 0.08 if s > 0 else -w, -d, b], [w if s > 0 else -w + 0.08, d, k.h],
              "white")
        k.box([-w, s * d - 0.08 if s > 0 else -d, b], [w, d if s > 0 else -d + 0.08, k.h],
              "white")


@builder(variants=3)
def rug(k: Kit) -> None:
    """A plain rug (0), one with a border (1), or a round one (2)."""
    if k.v == 2:
        k.cyl(0, 0, min(k.w, k.d), k.bottom, k.h, "fabric")
        return
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * (0.5 if k.v else 1)], "fabric")
    if k.v == 1:
        b = min(0.12, k.w * 0.2, k.d * 0.2)
        k.box([-k.w + b, -k.d + b, k.bottom], [k.w - b, k.d - b, k.h], "cushion")


@builder(variants=3)
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


@builder()
def towelrack(k: Kit) -> None:
    k.rod([0, 0, 0], 0, min(k.h, k.d, 0.012), k.w, "chrome")


@builder(variants=3)
def hanger(k: Kit) -> None:
    """A bar hanger: wood (0), metal (1), or with a garment on it (2)."""
    k.rod([0, 0, k.h - 0.02], 1, 0.008, k.d, "metal" if k.v == 1 else "wood")
    if k.v == 2:
        k.box([-k.w * 0.5, -k.d * 0.9, k.bottom], [k.w * 0.5, k.d * 0.9, k.h - 0.03], "fabric")


@builder(variants=3)
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


@builder(variants=3)
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


@builder()
def stall(k: Kit) -> None:  # drawn by the enclosure shaper; kept for completeness
    k.box([-k.w, -k.d, k.bottom], [k.w, -k.d + 0.03, k.h], "body")


@builder()
def window(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    t = 0.04
    k.box([-w, -d, b], [w, d, b + t], "white")
    k.box([-w, -d, k.h - t], [w, d, k.h], "white")
    k.box([-w, -d, b], [-w + t, d, k.h], "white")
    k.box([w - t, -d, b], [w, d, k.h], "white")
    k.box([-0.015, -d, b], [0.015, d, k.h], "white")
    k.box([-w + t, -0.005, b + t], [w - t, 0.005, k.h - t], "glass")


@builder(variants=3)
def picture(k: Kit) -> None:
    t = min(0.03, k.w * 0.15, k.h * 0.15)
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d * 0.5, k.h], "darkwood" if k.v else "metal")
    k.box([-k.w + t, k.d * 0.5, k.bottom + t], [k.w - t, k.d, k.h - t], f"art{k.v}")


@builder()
def generic_furniture(k: Kit) -> None:
    """A body on a plinth with a top: shelves, stands, unknown furniture."""
    k.box([-k.w, -k.d, k.bottom + 0.05], [k.w, k.d, k.h - 0.03], "body")
    k.box([-k.w * 0.95, -k.d * 0.95, k.bottom], [k.w * 0.95, k.d * 0.95, k.bottom + 0.05],
          "darkwood")
    k.box([-k.w, -k.d, k.h - 0.03], [k.w, k.d, k.h], "wood")


@builder(variants=2)
def tvstand(k: Kit) -> None:
    if k.v == 1:
        carcass(k, drawers=2)
    else:
        generic_furniture(k)
