"""Lamps, electronics and appliances."""

from __future__ import annotations

import numpy as np

from homesim.render.models.kit import Kit, builder


@builder(variants=3)
def ceilinglamp(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, 0.01, k.h - 0.1, k.h, "metal")
    if k.v == 0:
        k.cyl(0, 0, r, k.h - 0.14, k.h - 0.1, "glow")
    elif k.v == 1:
        k.ell([0, 0, k.h - 0.2], [r * 0.7, r * 0.7, min(0.12, k.h)], "glow")
    else:
        k.cyl(0, 0, r * 0.8, k.h - 0.3, k.h - 0.1, "glow")


@builder(variants=3)
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


@builder(variants=3)
def tablelamp(k: Kit) -> None:
    r = min(k.w, k.d)
    b = k.bottom
    k.cyl(0, 0, r * 0.45, b, b + 0.03, "metal")
    k.cyl(0, 0, 0.012, b + 0.03, k.h * 0.2, "metal")
    if k.v == 2:
        k.ell([0, 0, b + 0.25 * 2 * k.h], [r * 0.5, r * 0.5, 0.25 * k.h], "body")
    shade = k.h * 0.5
    k.cyl(0, 0, r, k.h - shade, k.h, "glow", kind="cylinder" if k.v != 1 else "ellipsoid")


@builder()
def floorlamp(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r * 0.5, k.bottom, k.bottom + 0.03, "metal")
    k.cyl(0, 0, 0.015, k.bottom, k.h - 0.3, "metal")
    k.cyl(0, 0, r, k.h - 0.35, k.h, "glow")


@builder(variants=2)
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


@builder()
def monitor(k: Kit) -> None:
    tv(k)


@builder()
def computer(k: Kit) -> None:
    if k.h > 0.3:  # a tower
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "black")
        k.box([-k.w * 0.6, k.d - 0.005, k.h - 0.12], [k.w * 0.6, k.d, k.h - 0.08], "metal")
        k.cyl(0, k.d - 0.01, 0.01, k.h - 0.2, k.h - 0.18, "glow")
    else:
        k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "black")


@builder()
def keyboard(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.bottom + 0.6 * 2 * k.h], "black")
    k.box([-k.w + 0.01, -k.d + 0.01, k.bottom], [k.w - 0.01, k.d - 0.01, k.h], "white")


@builder()
def mouse(k: Kit) -> None:
    k.ell([0, 0, k.bottom], [min(k.w, 0.035), min(k.d, 0.06), 2 * k.h], "black")


@builder(variants=3)
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


@builder(variants=2)
def speaker(k: Kit) -> None:
    """A loudspeaker: a dark cabinet with a woofer and a tweeter on its front (0), or a
    round grille (1)."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.006, k.h], "black")
    r = min(k.w * 0.75, k.h * 0.3)
    if k.v == 1:
        k.rod([0, k.d - 0.003, 0], 1, min(k.w, k.h) * 0.85, 0.003, "fabric")
        return
    k.rod([0, k.d - 0.003, -k.h * 0.35], 1, r, 0.003, "metal")
    k.rod([0, k.d - 0.003, k.h * 0.45], 1, r * 0.4, 0.003, "metal")


@builder()
def amplifier(k: Kit) -> None:
    """An amplifier: a flat dark box, a display and two knobs on its front."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.006, k.h], "black")
    k.box([-k.w * 0.3, k.d - 0.006, 0], [k.w * 0.3, k.d, k.h * 0.5], "screen")
    for s in (-1, 1):
        k.rod([s * k.w * 0.7, k.d - 0.003, 0], 1, min(k.h * 0.35, k.w * 0.12), 0.003, "chrome")


@builder()
def ceilingfan(k: Kit) -> None:
    """A ceiling fan: a rod from the ceiling, a motor hub and four blades."""
    h = k.h
    hub = k.h - min(0.35, 2 * h * 0.7)
    k.cyl(0, 0, 0.015, hub, k.h, "metal")
    k.cyl(0, 0, min(k.w, k.d) * 0.12, hub - 0.06, hub + 0.04, "metal")
    t = 0.006
    k.box([-k.w, -0.06, hub - t], [k.w, 0.06, hub + t], "wood")
    k.box([-0.06, -k.d, hub - t], [0.06, k.d, hub + t], "wood")


@builder()
def radio(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "body")
    r = min(k.w, k.h) * 0.45
    k.rod([-k.w * 0.45, k.d - 0.005, 0], 1, r, 0.005, "black")
    k.box([k.w * 0.1, k.d - 0.01, 0], [k.w * 0.9, k.d, k.h * 0.6], "black")


@builder(variants=3)
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


@builder()
def clock(k: Kit) -> None:
    thin = 0 if k.w < k.d else 1
    r = min(max(k.w, k.d), k.h)
    half = min(k.w, k.d)
    k.rod([0, 0, 0], thin, r, half, "white")
    k.rod([0, 0, 0], thin, r * 1.0, half * 0.3, "black")


# -- appliances -----------------------------------------------------------------------------

@builder()
def appliance(k: Kit) -> None:
    """A box appliance with a control strip on its front."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "body")
    k.box([-k.w * 0.9, k.d - 0.01, k.h * 0.6], [k.w * 0.9, k.d, k.h * 0.9], "black")


@builder()
def fridge(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.03, k.h], "body")
    split = k.bottom + 2 * k.h * 0.62
    k.box([-k.w, k.d - 0.03, k.bottom], [k.w, k.d - 0.01, split - 0.005], "body")
    k.box([-k.w, k.d - 0.03, split + 0.005], [k.w, k.d - 0.01, k.h], "body")
    for z0, z1 in ((split - 0.45, split - 0.05), (split + 0.05, split + 0.3)):
        k.box([k.w - 0.08, k.d - 0.01, z0], [k.w - 0.06, k.d, min(z1, k.h)], "chrome")


@builder()
def stove(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    k.box([-w, -d, b], [w, d - 0.02, k.h - 0.02], "body")
    k.box([-w, -d, k.h - 0.02], [w, d, k.h], "black")
    for sx in (-1, 1):
        for sy in (-1, 1):
            k.cyl(sx * w * 0.45, sy * d * 0.4, min(w, d) * 0.22, k.h - 0.025, k.h, "metal")
    k.box([-w * 0.85, d - 0.02, b + 0.1], [w * 0.85, d, k.h - 0.2], "glass_dark")
    k.box([-w * 0.7, d - 0.01, k.h - 0.17], [w * 0.7, d, k.h - 0.15], "chrome")


@builder()
def stovefan(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.bottom + 0.08], "metal")
    k.box([-k.w * 0.3, -k.d, k.bottom + 0.08], [k.w * 0.3, -k.d + 0.3 * k.d, k.h], "metal")


@builder()
def microwave(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "body")
    k.box([-k.w + 0.02, k.d - 0.01, k.bottom + 0.03], [k.w * 0.4, k.d, k.h - 0.03],
          "glass_dark")
    k.box([k.w * 0.5, k.d - 0.01, k.bottom + 0.03], [k.w - 0.02, k.d, k.h - 0.03], "black")


@builder()
def washer(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d - 0.01, k.h], "white")
    r = min(k.w, k.h) * 0.55
    k.rod([0, k.d - 0.005, -k.h * 0.1], 1, r, 0.005, "glass_dark")
    k.box([-k.w, k.d - 0.01, k.h - 0.12], [k.w, k.d, k.h - 0.02], "metal")


@builder()
def toaster(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h - 0.01], "chrome")
    for s in (-1, 1):
        k.box([s * k.w * 0.3 - 0.015, -k.d * 0.7, k.h - 0.01],
              [s * k.w * 0.3 + 0.015, k.d * 0.7, k.h], "black")


@builder()
def coffeemaker(k: Kit) -> None:
    w, d, b = k.w, k.d, k.bottom
    k.box([-w, -d, b], [w, -d + d * 0.8, k.h], "black")
    k.box([-w, -d, k.h - 2 * k.h * 0.25], [w, d, k.h], "black")
    k.box([-w, -d, b], [w, d, b + 0.03], "black")
    k.cyl(0, d * 0.4, min(w, d) * 0.5, b + 0.03, b + 2 * k.h * 0.5, "glass")


@builder()
def oventray(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "metal")
