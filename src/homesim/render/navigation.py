"""Paths for the agent: A* on the home's walk grid, the floor model grounding uses.

The grid is the walkable floor of `homesim.world.floor.FloorModel`: the cells where
grounding would let the agent stand (its square on a room's floor, clear of obstacles)
and doorways' passages, joined into one walkable region (pockets left out). Grounding
chooses standing spots on that region, so the agent walks to them on the floor they were
chosen on. Paths are shortened by line of sight, so the agent walks
straight segments around furniture and through doorways.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass

import numpy as np

from homesim.errors import ExecutionError, LimitError
from homesim.limits import MAX_WALK_CELLS
from homesim.render.layout import Box, Layout
from homesim.world.floor import CELL

__all__ = ["CELL", "LEG_LEVEL", "PASSABLE", "Grid", "astar", "build_grid", "goal_cells",
           "plan_path", "segment_hits", "smooth", "wall_boxes"]

PASSABLE = frozenset({"floor", "ceiling", "door", "doorjamb", "rug", "character"})
"""Parts the body passes through (`homesim.render.interact` steps up to furniture among
the others; walking uses the floor model, not parts)."""
REACH_LEVEL = 0.9
"""Metres: the height of the line from a standing cell to what it reaches that must not
cross a wall (below door lintels)."""
WALLED_MORE = (0.0, 0.3, 0.6)
"""Metres beyond the reach asked for that a walk may stop at to stand on the object's
side of the walls (a desk facing a wall 20 cm away is reached from its end)."""
LEG_LEVEL = (0.08, 1.2)
"""Parts between these heights (metres) are in the body's way when it steps up to
furniture (`homesim.render.interact`)."""


@dataclass
class Grid:
    """Occupancy grid: ``free[i, j]`` is True when cell (i=x, j=y) can be walked."""

    origin: np.ndarray  # world (x, y) of cell (0, 0)'s centre
    free: np.ndarray  # (nx, ny) bool
    walls: tuple[np.ndarray, np.ndarray] = (np.zeros((0, 3)), np.zeros((0, 3)))
    """(lo, hi) of the walls' boxes: no one reaches through them (`goal_cells`)."""

    def cell(self, xy) -> tuple[int, int]:
        ij = np.round((np.asarray(xy, float) - self.origin) / CELL).astype(int)
        return (int(np.clip(ij[0], 0, self.free.shape[0] - 1)),
                int(np.clip(ij[1], 0, self.free.shape[1] - 1)))

    def point(self, ij: tuple[int, int]) -> np.ndarray:
        return self.origin + np.asarray(ij, float) * CELL

    def nearest_free(self, xy, seen_from=None) -> tuple[int, int]:
        """The free cell closest to a point; with `seen_from` (a floor point), the
        closest without a wall between it and that point, when there is one (one stands
        up from a chair into its own room, not through the wall behind the desk)."""
        idx = np.argwhere(self.free)
        if len(idx) == 0:
            raise ExecutionError("the home has no free floor to walk on")
        pts = self.origin + idx * CELL
        order = np.argsort(np.sum((pts - np.asarray(xy)[:2]) ** 2, axis=1), kind="stable")
        k = int(order[0])
        if seen_from is not None and len(self.walls[0]):
            start = np.r_[np.asarray(seen_from, float)[:2], REACH_LEVEL]
            k = next((int(i) for i in order if not segment_hits(
                start, np.r_[pts[i] - start[:2], 0.0], *self.walls)), k)
        return int(idx[k][0]), int(idx[k][1])

    def line_free(self, a: np.ndarray, b: np.ndarray) -> bool:
        """Whether every cell under the segment a-b (sampled each half cell) is free."""
        n = int(np.ceil(np.linalg.norm(b - a) / (CELL / 2))) + 1
        t = np.linspace(0.0, 1.0, n)[:, None]
        ij = np.round((a + t * (b - a) - self.origin) / CELL).astype(int)
        ij = np.clip(ij, 0, np.array(self.free.shape) - 1)
        return bool(self.free[ij[:, 0], ij[:, 1]].all())


def build_grid(layout: Layout) -> Grid:
    """The occupancy grid of a home's layout: its walk grid (the floor model)."""
    walk = layout.walk
    if walk is None:
        raise ExecutionError("the home has no floor to walk on (no rooms with boxes)")
    check_walk_cells(walk.shape, walk.cell)
    free = np.zeros(walk.shape, bool)
    for j, a, b, _ in walk.main_runs():
        free[a:b + 1, j] = True
    return Grid(np.array(walk.origin, float), free, wall_boxes(layout))


def wall_boxes(layout: Layout) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi), (n, 3) each: the boxes of a layout's walls."""
    walls = [b for p in layout.parts if p.class_name == "wall" for b in p.boxes]
    return (np.array([b.lo for b in walls]).reshape(-1, 3),
            np.array([b.hi for b in walls]).reshape(-1, 3))


def segment_hits(start: np.ndarray, vec: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> bool:
    """Whether the segment from `start` along `vec` meets any of the boxes (lo, hi)
    ((n, 3) arrays; the slab test)."""
    step = np.where(np.abs(vec) < 1e-12, 1e-12, vec)
    t1, t2 = (lo - start) / step, (hi - start) / step
    enter = np.minimum(t1, t2).max(axis=1)
    leave = np.maximum(t1, t2).min(axis=1)
    return bool(np.any((enter <= leave) & (leave >= 0.0) & (enter <= 1.0)))


def check_walk_cells(shape: tuple[int, int], cell: float) -> None:
    """Refuse a walk grid over `MAX_WALK_CELLS` cells (before it is allocated)."""
    if shape[0] * shape[1] > MAX_WALK_CELLS:
        raise LimitError(f"the home's floor spans {shape[0] * cell:.0f} m x {shape[1] * cell:.0f} "
                         f"m: {shape[0] * shape[1]} walk cells, more than the renderer plans "
                         f"on (MAX_WALK_CELLS = {MAX_WALK_CELLS})", "MAX_WALK_CELLS")


_STEPS = [(1, 0, 1.0), (-1, 0, 1.0), (0, 1, 1.0), (0, -1, 1.0),
          (1, 1, 1.4142), (1, -1, 1.4142), (-1, 1, 1.4142), (-1, -1, 1.4142)]


def astar(grid: Grid, start: tuple[int, int], goals: set[tuple[int, int]],
          aim: np.ndarray) -> list[tuple[int, int]]:
    """Shortest 8-connected path from `start` to any goal cell (heuristic: to `aim`)."""
    if start in goals:
        return [start]
    aim_ij = (aim - grid.origin) / CELL
    nx, ny = grid.free.shape
    # Cells as flat indices into the grid padded with a blocked rim (no bounds checks);
    # the index orders cells as (i, j) does, so ties in the heap break the same way. The
    # heuristic of every cell is computed at once (the same values as cell by cell).
    width = ny + 2
    free = np.pad(grid.free, 1).ravel().tolist()
    ii, jj = np.meshgrid(np.arange(-1, nx + 1), np.arange(-1, ny + 1), indexing="ij")
    h = np.maximum(np.hypot(ii - aim_ij[0], jj - aim_ij[1]) - 12.0, 0.0).ravel().tolist()
    steps = [(di * width + dj, di * width, dj, w) for di, dj, w in _STEPS]
    goal = [False] * len(free)
    for i, j in goals:
        if 0 <= i < nx and 0 <= j < ny:
            goal[(i + 1) * width + j + 1] = True
    came = [-1] * len(free)
    cost = [math.inf] * len(free)
    first = (start[0] + 1) * width + start[1] + 1
    cost[first] = 0.0
    heap = [(h[first], first)]
    while heap:
        _, cur = heapq.heappop(heap)
        if goal[cur]:
            path = [cur]
            while came[cur] >= 0:
                cur = came[cur]
                path.append(cur)
            return [(k // width - 1, k % width - 1) for k in reversed(path)]
        base = cost[cur]
        for step, di, dj, w in steps:
            nb = cur + step
            if not free[nb]:
                continue
            if di and dj and not (free[cur + di] and free[cur + dj]):
                continue  # no cutting corners
            c = base + w
            if c < cost[nb]:
                cost[nb] = c
                came[nb] = cur
                heapq.heappush(heap, (c + h[nb], nb))
    raise ExecutionError("no walkable path to the target")


def goal_cells(grid: Grid, target: Box, reach: float = 0.75) -> set[tuple[int, int]]:
    """Free cells within `reach` metres of a box's footprint (where the agent may stand)
    without a wall between them and it; where there are none, such cells up to
    `WALLED_MORE` farther, else the cells within `reach` (or the nearest) anyway."""
    idx = np.argwhere(grid.free)
    pts = grid.origin + idx * CELL
    d = np.maximum(np.abs(pts - target.center[:2]) - target.half[:2], 0.0)
    dist = np.hypot(d[:, 0], d[:, 1])
    for more in WALLED_MORE:
        open_ = [c for c in idx[dist <= reach + more]
                 if not walled(grid, grid.point(c), target)]
        if open_:
            return {(int(i), int(j)) for i, j in open_}
    near = idx[dist <= reach]
    if len(near) == 0:  # nothing close enough: the nearest free cells
        near = idx[dist <= dist.min() + CELL]
    return {(int(i), int(j)) for i, j in near}


def walled(grid: Grid, xy: np.ndarray, target: Box) -> bool:
    """Whether a wall stands between floor point `xy` and the nearest point of a box's
    footprint (the level line at `REACH_LEVEL`)."""
    lo, hi = grid.walls
    nearest = np.clip(xy, target.center[:2] - target.half[:2], target.center[:2] + target.half[:2])
    start = np.r_[xy, REACH_LEVEL]
    return bool(len(lo)) and segment_hits(start, np.r_[nearest - xy, 0.0], lo, hi)


def smooth(grid: Grid, cells: list[tuple[int, int]]) -> list[np.ndarray]:
    """Way points: drop every cell that the previous way point can see past."""
    pts = [grid.point(c) for c in cells]
    if len(pts) <= 2:
        return pts
    out = [pts[0]]
    i = 0
    while i < len(pts) - 1:
        j = len(pts) - 1
        while j > i + 1 and not grid.line_free(pts[i], pts[j]):
            j -= 1
        out.append(pts[j])
        i = j
    return out


def plan_path(grid: Grid, start_xy: np.ndarray, target: Box,
              reach: float = 0.75) -> list[np.ndarray]:
    """Way points (x, y) from a position to a spot within reach of a target box."""
    start = grid.cell(start_xy)
    if not grid.free[start]:
        start = grid.nearest_free(start_xy)
    goals = goal_cells(grid, target, reach)
    cells = astar(grid, start, goals, target.center[:2])
    pts = smooth(grid, cells)
    pts[0] = np.asarray(start_xy, float)[:2].copy() if len(pts) > 1 else pts[0]
    return pts
