"""Plane geometry of procedural homes: rectangles on the floor and a walkable-floor grid.

Frame: Unity's, as in the built-in homes: metres, y up, the floor plan in (x, z).
A `Rect` is a floor footprint ``(x0, z0, x1, z1)`` with ``x0 < x1`` and ``z0 < z1``.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

Rect = tuple[float, float, float, float]

CELL = 0.2
"""Side (m) of a cell of the walkability grid."""
AGENT_HALF = 0.3
"""Clearance (m) kept around obstacles: the renderer's walking agent has a 0.25 m radius
(`homesim.render.navigation.AGENT_RADIUS`, on a 0.1 m grid), wider than grounding's
0.4 m square (`homesim.world.standing.AGENT_SIZE`)."""
DOOR_REACH = 0.6
"""Cells whose centre is this near (m) a doorway count as at the door."""
SLACK = 0.03
"""Extra margin (m) the generator keeps over the checks."""


def blocks(box: tuple[float, float, float, float, float, float]) -> bool:
    """Whether a box (x0, y0, z0, x1, y1, z1) is in the agent's way: it reaches into the
    body's height (0.08-1.5 m: grounding's 0.1-1.5 m, `homesim.world.standing`, and the
    renderer's legs from 0.08 m, `homesim.render.navigation.LEG_LEVEL`); sockets too."""
    return box[1] < 1.5 and box[4] > 0.08


def overlaps(a: Rect, b: Rect, margin: float = 0.0) -> bool:
    """Whether two rectangles overlap by more than `margin` on both axes."""
    return (min(a[2], b[2]) - max(a[0], b[0]) > margin
            and min(a[3], b[3]) - max(a[1], b[1]) > margin)


def inside(a: Rect, b: Rect, tol: float = 1e-6) -> bool:
    """Whether `a` lies within `b`."""
    return (a[0] >= b[0] - tol and a[1] >= b[1] - tol and a[2] <= b[2] + tol
            and a[3] <= b[3] + tol)


def grow(r: Rect, d: float) -> Rect:
    return (r[0] - d, r[1] - d, r[2] + d, r[3] + d)


class FreeFloor:
    """Cells of a room's floor where the agent's square fits, and walks between them.

    A cell is free when the agent's square centred on it lies in the room and touches
    no obstacle footprint. Grids are numpy arrays (x index, z index): a room is ~40 x 40
    cells and the furnisher asks thousands of times per home, so flood fills run as
    whole-array dilations instead of cell-by-cell."""

    def __init__(self, room: Rect, obstacles: Iterable[Rect], strict: bool = False,
                 masks: dict[tuple[Rect, float], np.ndarray] | None = None):
        """`strict` (the generator) asks for a few centimetres more room than the checks
        (`homesim.world.procedural.checks`), so rounding never makes a home it built fail
        them. `masks` keeps the masks of `near` across floors of the same room."""
        self.room = room
        self.slack = SLACK if strict else 0.0
        self.nx = max(1, int((room[2] - room[0]) / CELL))
        self.nz = max(1, int((room[3] - room[1]) / CELL))
        self.xs = room[0] + (np.arange(self.nx) + 0.5) * CELL
        self.zs = room[1] + (np.arange(self.nz) + 0.5) * CELL
        inner = grow(room, -AGENT_HALF)
        fx = (self.xs >= inner[0]) & (self.xs <= inner[2])
        fz = (self.zs >= inner[1]) & (self.zs <= inner[3])
        self.free = fx[:, None] & fz[None, :]
        self._near: dict[tuple[Rect, float], np.ndarray] = {} if masks is None else masks
        for ob in obstacles:
            self.block(ob)

    def copy(self) -> FreeFloor:
        """The same floor, to block more on (it shares the masks `near` made)."""
        other = object.__new__(FreeFloor)
        other.__dict__.update(self.__dict__)
        other.free = self.free.copy()
        return other

    def x(self, i: int) -> float:
        return float(self.xs[i])

    def z(self, j: int) -> float:
        return float(self.zs[j])

    def near(self, r: Rect, reach: float) -> np.ndarray:
        """Mask of the cells whose centre lies within `reach` of rectangle `r` (per axis);
        read only (masks are kept: the furnisher asks for the same ones many times)."""
        mask = self._near.get((r, reach))
        if mask is None:
            g = grow(r, reach)
            mx = (self.xs >= g[0]) & (self.xs <= g[2])
            mz = (self.zs >= g[1]) & (self.zs <= g[3])
            mask = self._near[(r, reach)] = mx[:, None] & mz[None, :]
        return mask

    def cells_near(self, r: Rect, reach: float) -> list[tuple[int, int]]:
        """The cells of `near` as (i, j) pairs, in order."""
        return [(int(i), int(j)) for i, j in zip(*np.nonzero(self.near(r, reach)),
                                                 strict=True)]

    def block(self, ob: Rect) -> None:
        self.free &= ~self.near(ob, AGENT_HALF + self.slack)

    def reach_from(self, start: np.ndarray) -> np.ndarray:
        """Mask of the free cells reachable (4-connected) from the free cells of `start`.

        Alternate sweeps along rows and columns: a run of free cells in a line is reached
        as soon as one of its cells is, so the sweeps needed are the turns of the longest
        path (a few), not its length in cells."""
        rows, cols = _Runs(self.free), _Runs(self.free.T)
        seen = start & self.free
        while True:
            grown = cols.spread(rows.spread(seen).T).T
            if np.array_equal(grown, seen):
                return seen
            seen = grown

    def component(self, start: list[tuple[int, int]]) -> set[tuple[int, int]]:
        """Free cells reachable from the free cells of `start`, as (i, j) pairs."""
        mask = np.zeros_like(self.free)
        for i, j in start:
            mask[i, j] = True
        return {(int(i), int(j)) for i, j in zip(*np.nonzero(self.reach_from(mask)),
                                                 strict=True)}

    def walkable(self, doors: list[Rect], targets: list[Rect], reach: float = 0.7
                 ) -> str | None:
        """None when every door and every target is reachable from the first door;
        otherwise what is not (a short reason)."""
        if not doors:
            return None
        comp = self.reach_from(self.near(doors[0], DOOR_REACH - self.slack))
        if not comp.any():
            return "no free floor at a door"
        for k, d in enumerate(doors[1:], 1):
            if not (comp & self.near(d, DOOR_REACH - self.slack)).any():
                return f"door {k} cannot be reached from door 0"
        for k, t in enumerate(targets):
            if not (comp & self.near(t, reach - self.slack)).any():
                return f"object {k} has no free floor within {reach} m"
        return None


class _Runs:
    """The runs of free cells along the second axis of a grid, numbered in order."""

    def __init__(self, free: np.ndarray):
        self.free = free
        padded = np.zeros((free.shape[0], free.shape[1] + 1), bool)
        padded[:, 1:] = free
        starts = padded[:, 1:] & ~padded[:, :-1]
        self.ids = np.cumsum(starts.ravel()).reshape(free.shape)
        self.count = int(self.ids.max(initial=0)) + 1

    def spread(self, seen: np.ndarray) -> np.ndarray:
        """Every free cell of a run that holds a cell of `seen`."""
        hit = np.zeros(self.count, bool)
        hit[self.ids[seen & self.free]] = True
        return hit[self.ids] & self.free
