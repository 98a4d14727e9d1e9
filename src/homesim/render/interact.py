"""Hands on objects: where a hand touches, where the agent stands to reach it.

A reach aims at a point on the object's surface (the point of its box nearest the
shoulder, or a door's handle). When grounding's standing spot leaves it out of the arm's
reach, `ReachPlanner` finds where to stand instead: on the straight line toward the
object, as far as the body fits between the obstacles, crouching for low points, leaning
(the IK bends the spine) for far ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from homesim.render.agent import AgentShape
from homesim.render.ik import ArmIK, crouched
from homesim.render.layout import Box, Layout
from homesim.render.poses import Pose, standing

TOUCH = 0.01
"""Metres: a hand this close to an object's surface touches it (grab, press, open)."""
BODY_RADIUS = 0.16
"""Metres: the agent's footprint when it steps up to furniture (narrower than the 0.25 m
the path planner keeps while walking)."""
PASSABLE = frozenset({"floor", "ceiling", "door", "doorjamb", "rug", "character"})
"""Classes of parts the body may overlap when it steps close to reach."""
LEG_LEVEL = (0.08, 1.2)
"""Heights (m) between which a part blocks the body."""
STEP = 0.05
"""Metres between the standing points tried on the way to an object."""
CROUCH = (0.0, 0.2, 0.35)
"""Pelvis drops (metres) tried, in order, for points below `LOW`."""
LOW = 0.75
"""Metres: points lower than this may be reached crouching."""
AROUND = (0.35, 0.5, 0.65)
"""Metres from the target (horizontally) of the standing points tried around it when the
way straight to it is blocked."""
MAX_AROUND = 24
"""At most this many of those are tried (nearest to the agent first)."""


def box_gap(box: Box, point: np.ndarray) -> float:
    """Distance from a point to a box (0 inside it)."""
    d = np.maximum(np.abs(np.asarray(point, float) - box.center) - box.half, 0.0)
    return float(np.linalg.norm(d))


def surface_point(box: Box, toward: np.ndarray, inset: float = 0.004) -> np.ndarray:
    """The point of a box nearest `toward`, `inset` metres inside its surface (the box's
    centre when `toward` is inside it)."""
    toward = np.asarray(toward, float)
    p = np.clip(toward, box.lo, box.hi)
    d = toward - p
    n = float(np.linalg.norm(d))
    if n < 1e-9:
        return box.center.copy()
    inner = np.minimum(box.half, inset)
    return np.clip(p - inset * d / n, box.lo + inner, box.hi - inner)


@dataclass(frozen=True)
class ReachPlan:
    """A reach: the pose at its end (standing where it must, crouched if low) and the
    distance the hand stays from its target point."""

    pose: Pose
    gap: float  # metres


class ReachPlanner:
    """Finds a standing point from which a hand reaches a target point."""

    def __init__(self, layout: Layout, ik: ArmIK, shape: AgentShape):
        self.ik, self.shape = ik, shape
        self.walk = layout.walk
        self.obstacles = [(b.lo[:2], b.hi[:2]) for p in layout.parts
                          if p.class_name not in PASSABLE and p.movable is None
                          for b in p.boxes
                          if b.hi[2] > LEG_LEVEL[0] and b.lo[2] < LEG_LEVEL[1]]

    def fits(self, xy: np.ndarray) -> bool:
        """Whether the agent can stand at `xy`: on (or a cell from) the floor model's
        walkable floor, and its body clear of furniture and walls."""
        if self.walk is None or not self.walk.reachable(float(xy[0]), float(xy[1])):
            return False
        for lo, hi in self.obstacles:
            d = np.maximum(np.maximum(lo - xy, xy - hi), 0.0)
            if float(np.hypot(d[0], d[1])) < BODY_RADIUS:
                return False
        return True

    def reach_from(self, xy: np.ndarray, side: str, point: np.ndarray,
                   grip: np.ndarray | None = None) -> ReachPlan:
        """The best reach of `point` standing at `xy`, facing it (crouching if low);
        `grip`: with the point held at this offset from the hand (see `ArmIK.reach`)."""
        d = point[:2] - xy
        yaw = math.atan2(d[1], d[0]) if np.hypot(*d) > 1e-6 else 0.0
        base = standing(self.shape, xy, yaw)
        best: ReachPlan | None = None
        for drop in CROUCH if point[2] < LOW else CROUCH[:1]:
            reached, _ = self.ik.reach(crouched(base, self.shape, drop), side, point, grip)
            gap = float(np.linalg.norm(self.ik.held_point(reached, side, grip) - point))
            if best is None or gap < best.gap - 1e-4:
                best = ReachPlan(reached, gap)
            if gap <= TOUCH:
                break
        assert best is not None
        return best

    def plan(self, start_xy: np.ndarray, side: str, point: np.ndarray,
             grip: np.ndarray | None = None) -> ReachPlan:
        """Where to stand to reach `point`: the first point on the way from `start_xy`
        toward it (every `STEP` metres, while the body fits) from which the hand touches
        it; else the nearest point around it (`AROUND`) from which it does; else the
        point tried from which the hand comes closest."""
        d = point[:2] - start_xy
        dist = float(np.hypot(*d))
        best = self.reach_from(start_xy, side, point, grip)
        for s in np.arange(STEP, dist, STEP):
            if best.gap <= TOUCH:
                return best
            xy = start_xy + d / dist * s
            if not self.fits(xy):
                break
            plan = self.reach_from(xy, side, point, grip)
            if plan.gap < best.gap - 1e-3:
                best = plan
        if best.gap <= TOUCH:
            return best
        for xy in self.around(start_xy, point)[:MAX_AROUND]:
            plan = self.reach_from(xy, side, point, grip)
            if plan.gap < best.gap - 1e-3:
                best = plan
            if plan.gap <= TOUCH:
                break
        return best

    def around(self, start_xy: np.ndarray, point: np.ndarray) -> list[np.ndarray]:
        """Points where the body fits around `point` (`AROUND` distances, 16 directions),
        nearest to `start_xy` first."""
        spots = [point[:2] + r * np.array([math.cos(a), math.sin(a)])
                 for r in AROUND for a in np.linspace(0.0, 2 * math.pi, 16, endpoint=False)]
        spots = [xy for xy in spots if self.fits(xy)]
        return sorted(spots, key=lambda xy: float(np.hypot(*(xy - start_xy))))

    def clear_line(self, a: np.ndarray, b: np.ndarray) -> bool:
        """Whether the body fits all along the segment a-b (checked every 5 cm)."""
        n = max(2, int(np.ceil(np.linalg.norm(b - a) / 0.05)) + 1)
        return all(self.fits(a + t * (b - a)) for t in np.linspace(0.0, 1.0, n)[1:])
