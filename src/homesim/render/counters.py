"""Kitchen and bathroom counters as they stand in a room: strips along the walls, with
room for what stands in them.

VirtualHome gives an L- or U-shaped counter one box over the whole corner (scene 5's
kitchen counter box holds the kitchen table and its chairs), and a dishwasher stands
inside its counter's box. Drawn as one solid block, such a counter buries them and the
hand that reaches them. Here a counter box deep in both directions (`DEEP`) is drawn as
strips `DEPTH` deep along its sides that face the room's walls (`strips`), and every
counter's shapes are cut around the boxes of the furniture and appliances standing in it
(`carve`), so the dishwasher's front and the table show and can be reached.
"""

from __future__ import annotations

import numpy as np

from homesim.render.models import Shape

DEEP = 0.6
"""Half metres: a counter box deeper than 1.2 m both ways is an L or a U."""
DEPTH = 0.62
"""Metres: the depth of each strip of an L- or U-shaped counter."""
NEAR_WALL = 0.4
"""Metres: a side of a counter's box this near its room's floor edge stands at a wall."""
COUNTERS = frozenset({"kitchencounter", "bathroomcounter"})


def strips(lo: np.ndarray, hi: np.ndarray, room_lo: np.ndarray, room_hi: np.ndarray
           ) -> list[tuple[np.ndarray, np.ndarray, tuple[int, float]]]:
    """(lo, hi, front) of the strips a counter box is drawn as: the box itself unless it
    is deep both ways (`DEEP`); then a strip along each side near a wall of its room, its
    front facing away from that wall (the box itself when no side is)."""
    half = (hi - lo) / 2
    if min(half[0], half[1]) <= DEEP:
        return [(lo, hi, _front_from(lo, hi, room_lo, room_hi))]
    out = []
    for axis in (0, 1):
        for sign in (-1.0, 1.0):
            edge = lo[axis] if sign < 0 else hi[axis]
            wall = room_lo[axis] if sign < 0 else room_hi[axis]
            if abs(edge - wall) > NEAR_WALL:
                continue
            slo, shi = lo.copy(), hi.copy()
            if sign < 0:
                shi[axis] = lo[axis] + DEPTH
            else:
                slo[axis] = hi[axis] - DEPTH
            out.append((slo, shi, (axis, -sign)))
    return out or [(lo, hi, _front_from(lo, hi, room_lo, room_hi))]


def _front_from(lo, hi, room_lo, room_hi) -> tuple[int, float]:
    """The side of a box farthest from its room's walls (axis, sign)."""
    gaps = [(min(lo[a] - room_lo[a], room_hi[a] - hi[a]), a) for a in (0, 1)]
    _, axis = min(gaps)
    sign = 1.0 if lo[axis] - room_lo[axis] < room_hi[axis] - hi[axis] else -1.0
    return axis, sign


def carve(shapes: list[Shape], holes: list[tuple[np.ndarray, np.ndarray]]) -> list[Shape]:
    """Box shapes with the parts inside any of `holes` (lo, hi) cut away (other shapes
    that meet a hole are dropped)."""
    out = shapes
    for hlo, hhi in holes:
        cut = []
        for s in out:
            slo, shi = s.center - s.half, s.center + s.half
            if np.any(shi <= hlo + 1e-6) or np.any(slo >= hhi - 1e-6):
                cut.append(s)
            elif s.kind == "box":
                cut += [Shape("box", (a + b) / 2, (b - a) / 2, s.role)
                        for a, b in _difference(slo, shi, hlo, hhi)]
        out = cut
    return out


def _difference(lo: np.ndarray, hi: np.ndarray, hlo: np.ndarray, hhi: np.ndarray
                ) -> list[tuple[np.ndarray, np.ndarray]]:
    """Boxes covering box (lo, hi) minus box (hlo, hhi), each at least 2 mm thick."""
    out = []
    lo, hi = lo.copy(), hi.copy()
    for axis in range(3):
        if hlo[axis] > lo[axis]:
            a, b = lo.copy(), hi.copy()
            b[axis] = hlo[axis]
            out.append((a, b))
            lo[axis] = hlo[axis]
        if hhi[axis] < hi[axis]:
            a, b = lo.copy(), hi.copy()
            a[axis] = hhi[axis]
            out.append((a, b))
            hi[axis] = hhi[axis]
    return [(a, b) for a, b in out if np.all(b - a > 2e-3)]


__all__ = ["COUNTERS", "carve", "strips"]
