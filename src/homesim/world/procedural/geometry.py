"""Plane geometry of procedural homes: rectangles on the floor and a walkable-floor grid.

Frame: Unity's, as in the built-in homes: metres, y up, the floor plan in (x, z).
A `Rect` is a floor footprint ``(x0, z0, x1, z1)`` with ``x0 < x1`` and ``z0 < z1``.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable

Rect = tuple[float, float, float, float]

CELL = 0.2
"""Side (m) of a cell of the walkability grid."""
AGENT_HALF = 0.2
"""Half the agent's footprint (m), as `homesim.ground.standing.AGENT_SIZE` / 2."""
DOOR_REACH = 0.45
"""Cells whose centre is this near (m) a doorway count as at the door."""


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
    no obstacle footprint."""

    def __init__(self, room: Rect, obstacles: Iterable[Rect]):
        self.room = room
        self.nx = max(1, int((room[2] - room[0]) / CELL))
        self.nz = max(1, int((room[3] - room[1]) / CELL))
        self.free = [[True] * self.nz for _ in range(self.nx)]
        inner = grow(room, -AGENT_HALF)
        for i in range(self.nx):
            x = self.x(i)
            if not inner[0] <= x <= inner[2]:
                self.free[i] = [False] * self.nz
        for j in range(self.nz):
            z = self.z(j)
            if not inner[1] <= z <= inner[3]:
                for i in range(self.nx):
                    self.free[i][j] = False
        for ob in obstacles:
            self.block(ob)

    def x(self, i: int) -> float:
        return self.room[0] + (i + 0.5) * CELL

    def z(self, j: int) -> float:
        return self.room[1] + (j + 0.5) * CELL

    def cells_near(self, r: Rect, reach: float) -> list[tuple[int, int]]:
        """Grid cells whose centre lies within `reach` of rectangle `r` (a box-distance)."""
        g = grow(r, reach)
        i0 = max(0, int((g[0] - self.room[0]) / CELL))
        i1 = min(self.nx - 1, int((g[2] - self.room[0]) / CELL))
        j0 = max(0, int((g[1] - self.room[1]) / CELL))
        j1 = min(self.nz - 1, int((g[3] - self.room[1]) / CELL))
        return [(i, j) for i in range(i0, i1 + 1) for j in range(j0, j1 + 1)
                if g[0] <= self.x(i) <= g[2] and g[1] <= self.z(j) <= g[3]]

    def block(self, ob: Rect) -> None:
        for i, j in self.cells_near(ob, AGENT_HALF):
            self.free[i][j] = False

    def component(self, start: list[tuple[int, int]]) -> set[tuple[int, int]]:
        """Free cells reachable from the free cells of `start` (4-connected)."""
        seen = {c for c in start if self.free[c[0]][c[1]]}
        todo = deque(seen)
        while todo:
            i, j = todo.popleft()
            for a, b in ((i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)):
                if (0 <= a < self.nx and 0 <= b < self.nz and self.free[a][b]
                        and (a, b) not in seen):
                    seen.add((a, b))
                    todo.append((a, b))
        return seen

    def walkable(self, doors: list[Rect], targets: list[Rect], reach: float = 0.7
                 ) -> str | None:
        """None when every door and every target is reachable from the first door;
        otherwise what is not (a short reason)."""
        if not doors:
            return None
        comp = self.component(self.cells_near(doors[0], DOOR_REACH))
        if not comp:
            return "no free floor at a door"
        for k, d in enumerate(doors[1:], 1):
            if comp.isdisjoint(self.cells_near(d, DOOR_REACH)):
                return f"door {k} cannot be reached from door 0"
        for k, t in enumerate(targets):
            if comp.isdisjoint(self.cells_near(t, reach)):
                return f"object {k} has no free floor within {reach} m"
        return None
