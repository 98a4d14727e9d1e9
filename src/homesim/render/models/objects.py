"""Small objects: tableware, bottles and jars, paper, food, bathroom things, decor, and
the generic shapes of classes without a model of their own."""

from __future__ import annotations

import numpy as np

from homesim.render.models.kit import Kit, builder


@builder(variants=3)
def mug(k: Kit) -> None:
    r = min(k.w, k.d) * 0.78
    k.cyl(-k.w + r, 0, r, k.bottom, k.h, "body" if k.v else "white")
    hx = -k.w + 2 * r
    k.box([hx, -0.006, -k.h * 0.5], [min(k.w, hx + r * 0.6), 0.006, k.h * 0.6], "body"
          if k.v else "white")


@builder(variants=3)
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


@builder()
def wineglass(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r * 0.7, k.bottom, k.bottom + 0.005, "glass")
    k.ell([0, 0, k.h * 0.2], [r, r, k.h * 0.8], "glass")


@builder(variants=3)
def plate(k: Kit) -> None:
    """A round plate, flat on the table whatever its box's height: plain (0), with a
    coloured rim (1), or a deep one with a raised rim (2)."""
    r = min(k.w, k.d)
    top = k.bottom + min(2 * k.h, 0.025 if k.v != 2 else 0.04)
    k.cyl(0, 0, r * 0.7 if k.v else r, k.bottom, top - 0.006 if k.v else top, "white")
    if k.v:
        k.cyl(0, 0, r, k.bottom + 0.006, top, "body" if k.v == 1 else "white")


@builder(variants=3)
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


@builder()
def pot(k: Kit) -> None:
    r = min(k.w, k.d) * 0.7
    k.cyl(0, 0, r, k.bottom, k.h, "metal")
    k.rod([r + (k.w - r) / 2, 0, k.h * 0.5], 0, min(0.012, k.h), (k.w - r) / 2, "black")


@builder()
def fryingpan(k: Kit) -> None:
    r = min(k.w, k.d) * 0.6
    k.cyl(-k.w + r, 0, r, k.bottom, k.h, "black")
    k.rod([r / 2 + k.w / 2 - r / 2, 0, 0], 0, min(0.015, k.h), (k.w - r) / 2 + r / 4,
          "black")


@builder(variants=4)
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


@builder(variants=3)
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


@builder(variants=3)
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


@builder()
def carton(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * 0.7], "body")
    k.box([-k.w, -k.d * 0.2, k.h * 0.7], [k.w, k.d * 0.2, k.h], "white")
    k.box([-k.w, k.d - 0.002, -k.h * 0.3], [k.w * 0.6, k.d, k.h * 0.3], "label")


@builder()
def package(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h], "body")
    k.box([-k.w * 0.7, k.d - 0.002, -k.h * 0.4], [k.w * 0.7, k.d, k.h * 0.5], "label")


@builder()
def tube(k: Kit) -> None:
    big = int(np.argmax([k.w, k.d, k.h]))
    half = np.array([k.w, k.d, k.h])
    r = float(min(np.delete(half, big)))
    center = np.zeros(3)
    k.rod(center, big, r, half[big], "body", kind="capsule")
    cap = center.copy()
    cap[big] = half[big] - r
    k.rod(cap, big, r * 0.6, r, "accent")


@builder(variants=3)
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


@builder()
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


@builder(variants=3)
def fruit(k: Kit) -> None:
    """A round fruit (0), a flatter one (1), or one with a stalk and leaf (2)."""
    if k.v == 1:
        k.ell([0, 0, -k.h * 0.15], [k.w, k.d, k.h * 0.85], "body")
        return
    k.ell([0, 0, 0], [k.w, k.d, k.h], "body")
    if k.v == 2:
        k.box([0, -0.002, k.h * 0.7], [min(k.w, 0.03), 0.002, k.h], "leaf")


@builder()
def bananas(k: Kit) -> None:
    long = 0 if k.w > k.d else 1
    half = np.array([k.w, k.d, k.h])
    r = min(half[1 - long] / 3, k.h)
    for i in (-1, 0, 1):
        c = np.zeros(3)
        c[1 - long] = i * r * 1.8
        k.rod(c, long, r, half[long], "body", kind="capsule")


@builder()
def cake(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "body")


@builder()
def cupcake(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r * 0.75, k.bottom, 0, "accent")
    k.ell([0, 0, 0], [r, r, k.h], "body")


@builder(variants=3)
def slab(k: Kit) -> None:
    """Flat things (paper, towels, folders, slices): a slab (0), one with a band (1), or
    two stacked (2)."""
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h if k.v != 2 else 0], "body")
    if k.v == 1:
        k.box([-k.w, -k.d * 0.2, k.bottom], [k.w, k.d * 0.2, k.h], "accent")
    elif k.v == 2:
        k.box([-k.w * 0.9, -k.d * 0.9, 0], [k.w * 0.85, k.d * 0.9, k.h], "body")


@builder(variants=3)
def pillow(k: Kit) -> None:
    """A pillow or cushion lying flat at the bottom of its box (however its box stands):
    a soft slab with a seam (0), a plain one (1), or a round cushion (2)."""
    flat = min(k.h, 0.07, 0.3 * max(k.w, k.d))
    w = max(k.w, k.d) if k.h > flat * 2 and k.w < k.h else k.w
    w = min(w, k.w)
    z = k.bottom + flat
    if k.v == 2:
        r = min(k.w, k.d)
        k.ell([0, 0, z], [r, r, flat], "cushion")
        return
    k.ell([0, 0, z], [w, k.d, flat], "cushion")
    if k.v == 0:
        k.box([-w * 0.8, -k.d * 0.02, z - flat * 0.1], [w * 0.8, k.d * 0.02, z + flat * 0.1],
              "fabric")


@builder(variants=3)
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


@builder()
def candle(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "white")


@builder(variants=2)
def plant(k: Kit) -> None:
    r = min(k.w, k.d)
    pot_top = k.bottom + 2 * k.h * 0.35
    k.cyl(0, 0, r * 0.55, k.bottom, pot_top, "white" if k.v else "body")
    k.ell([0, 0, (pot_top + k.h) / 2], [r, r, (k.h - pot_top) / 2], "leaf")


@builder()
def garbagecan(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "metal")


@builder()
def bucket(k: Kit) -> None:
    r = min(k.w, k.d)
    k.cyl(0, 0, r, k.bottom, k.h, "body")


@builder()
def knifeblock(k: Kit) -> None:
    k.box([-k.w, -k.d, k.bottom], [k.w, k.d, k.h * 0.5], "wood")
    k.box([-k.w * 0.6, -k.d * 0.6, k.h * 0.5], [k.w * 0.6, k.d * 0.6, k.h], "black")


@builder()
def slippers(k: Kit) -> None:
    for s in (-1, 1):
        k.ell([s * k.w * 0.5, 0, 0], [k.w * 0.45, k.d, k.h], "body")


@builder()
def toy(k: Kit) -> None:
    """Toy blocks: a stack of three coloured cubes and a ball."""
    s = min(k.w, k.d, k.h) * 0.5
    b = k.bottom
    for i, (x, role) in enumerate(((-k.w + s, "body"), (-k.w + 3.1 * s, "accent"))):
        k.box([x - s, -s, b], [x + s, s, b + 2 * s], role)
        if i == 0:
            k.box([x - s * 0.9, -s * 0.9, b + 2 * s], [x + s * 0.9, s * 0.9, b + 3.8 * s],
                  "accent")
    r = min(s, k.w * 0.3)
    k.ell([k.w - r, k.d - r, b + r], [r, r, r], "white")


@builder()
def teddybear(k: Kit) -> None:
    """A sitting teddy bear: body, head with ears and a snout, arms and legs."""
    w, d, h, b = k.w, k.d, k.h, k.bottom
    k.ell([0, -d * 0.1, b + h * 0.55], [w * 0.55, d * 0.5, h * 0.38], "fabric")  # body
    head = b + h * 1.45
    k.ell([0, 0, head], [w * 0.42, d * 0.42, h * 0.3], "fabric")
    k.ell([0, d * 0.35, head - h * 0.06], [w * 0.16, d * 0.14, h * 0.1], "white")  # snout
    for s in (-1, 1):
        k.ell([s * w * 0.32, 0, head + h * 0.25], [w * 0.14, d * 0.08, h * 0.1], "fabric")
        k.ell([s * w * 0.55, d * 0.1, b + h * 0.7], [w * 0.2, d * 0.2, h * 0.25], "fabric")
        k.ell([s * w * 0.35, d * 0.45, b + h * 0.18], [w * 0.22, d * 0.4, h * 0.18], "fabric")


@builder()
def ball(k: Kit) -> None:
    """A ball with a band (a sports ball)."""
    r = min(k.w, k.d, k.h)
    k.ell([0, 0, k.bottom + r], [r, r, r], "body")
    k.ell([0, 0, k.bottom + r], [r * 1.01, r * 0.15, r * 1.01], "white")


@builder()
def spectacles(k: Kit) -> None:
    """Glasses lying folded: two lenses in a dark frame, a bridge, the folded temples."""
    w, d, b = k.w, k.d, k.bottom
    r = min(w * 0.45, d * 0.9, 0.03)
    top = b + min(2 * k.h, 0.012)
    for s in (-1, 1):
        k.cyl(s * w * 0.5, 0, r, b + 0.002, top - 0.002, "glass")
        k.cyl(s * w * 0.5, 0, r * 1.12, b, b + 0.003, "black")
    k.box([-w * 0.12, -0.003, top - 0.006], [w * 0.12, 0.003, top], "black")
    k.box([-w * 0.95, -d, b], [w * 0.95, -d + 0.004, top], "black")


@builder(variants=3)
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


@builder()
def generic_prop(k: Kit) -> None:
    """A small object: tall ones as bottles, flat ones as slabs, others packages."""
    if k.h > 1.8 * max(k.w, k.d):
        bottle(k)
    elif k.h < 0.25 * max(k.w, k.d):
        slab(k)
    else:
        package(k)


@builder()
def generic_food(k: Kit) -> None:
    if k.h < 0.3 * max(k.w, k.d):
        cake(k) if abs(k.w - k.d) < 0.2 * max(k.w, k.d) else slab(k)
    else:
        rounded(k)
