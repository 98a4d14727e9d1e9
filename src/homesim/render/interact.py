"""Hands on objects: where a hand touches, where the agent stands to reach it.

A reach aims at a point on the object's surface (the point of its box nearest the
shoulder, or a door's handle). When grounding's standing spot leaves it out of the arm's
reach, `ReachPlanner` finds where to stand instead, on the same floor model
(`homesim.world.floor`): on the straight line toward the object while the floor is
walkable, else around it; crouching for low points, leaning (the IK bends the spine) for
far ones.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from homesim.render.agent import AgentShape
from homesim.render.clearance import Clearance
from homesim.render.gl import mujoco
from homesim.render.ik import MAX_LEAN, ArmIK, Grasp, crouched
from homesim.render.layout import Box, Layout
from homesim.render.navigation import segment_hits, wall_boxes
from homesim.render.poses import SPARE, Pose, spared, standing, write_qpos

TOUCH = 0.01
"""Metres: a hand this close to an object's surface touches it (grab, press, open)."""
STEP = 0.05
"""Metres between the standing points tried on the way to an object."""
CROUCH = (0.0, 0.2, 0.35)
"""Pelvis drops (metres) tried, in order, for points below `LOW`."""
LOW = 0.75
"""Metres: points lower than this may be reached crouching."""
COMFORT_LEAN = 0.5
"""Radians of spine pitch: the agent steps closer rather than bow more than this."""
AROUND = (0.35, 0.5, 0.65)
"""Metres from the target (horizontally) of the standing points tried around it when the
way straight to it is blocked."""
MAX_AROUND = 24
"""At most this many of those are tried (nearest to the agent first)."""
PALM_IN = 0.045
"""Metres: a grasp's contact point lies this far past the object's near edge (at most
half way across), so the palm covers the face back to the wrist."""
PALM_HALF_WIDTH = 0.04
"""Metres: a grasp's contact point stays this far above the object's bottom, so the
palm's edge does not sink into what it stands on."""

FLAT = 0.035
"""Metres: objects at most this tall (a plate, a book lying, a remote) are taken from above
first, the palm on their top; taller ones by the side first."""
KNEE = 0.45
"""Metres: objects whose top is lower than this (on the floor) are also taken from above
first."""
TOUCH_TOP = 1.1
SMALL_FACE = 0.15
"""Metres: a face touched no wider or taller than this is pressed by the fingertips."""
FINGERTIPS = 0.145
"""Metres from the palm's contact point to the fingertips' end (hand flat)."""
"""Metres: objects whose top is lower than this are touched on the top first."""
HAND_ROOM = 0.05
"""Metres the palm and the closing fingers need out of the face they take."""
WALL_SLACK = 0.05
"""Metres: the end of the line to a reached point not checked for walls (what hangs on a
wall is reached from its room)."""
CLEAR = 0.02
"""Metres: a reach pose whose body passes deeper than this into anything but what the
hand takes (or holds) is tried after those that do not."""
LEAN_BACK = 0.15
"""Radians: a reach whose body passes into something is tried again with the spine bent
this much less each time (the hand stops short rather than the head entering a wall)."""
WRIST = 0.02
"""Metres: a grasp holds when the palm touches the object and the wrist is this near its
box (a palm touching with only its edge, the hand turned away, does not)."""

GraspOf = Callable[[np.ndarray], list[Grasp]]
"""Ways a hand may take an object, best first, for the agent standing at a floor point."""


def box_gap(box: Box, point: np.ndarray) -> float:
    """Distance from a point to a box (0 inside it)."""
    d = np.maximum(np.abs(np.asarray(point, float) - box.center) - box.half, 0.0)
    return float(np.linalg.norm(d))


def out_of_walls(box: Box, walls: tuple[np.ndarray, np.ndarray], keep: float = 0.02) -> Box:
    """The part of a box outside the wall boxes (lo, hi) it overlaps: cut along the axis
    it enters each the least, keeping the larger side (a faucet or a switch whose box
    reaches into the wall behind it is touched on what stands out); `box` itself when
    less than `keep` metres would be left."""
    lo, hi = box.lo.copy(), box.hi.copy()
    cut = False
    for wlo, whi in zip(*walls, strict=True):
        inner = np.minimum(hi, whi) - np.maximum(lo, wlo)
        if np.any(inner <= 0.0):
            continue
        axis, cut = int(np.argmin(inner[:2])), True
        if whi[axis] - lo[axis] < hi[axis] - wlo[axis]:  # the wall on the low side
            lo[axis] = whi[axis]
        else:
            hi[axis] = wlo[axis]
    if not cut or np.any(hi - lo < keep):
        return box
    return Box.from_bounds(lo, hi)


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


def palm_grasps(box: Box, side: str, from_xy: np.ndarray,
                inset: float = 0.004) -> list[Grasp]:
    """Palm grasps of a box by the agent standing at `from_xy`, best first: by the side
    face on the hand's side (the right face for the right hand) and from above (the palm
    on the top); flat (`FLAT`) and low (`KNEE`) objects from above first. The heel of the
    palm lies just past the face's near edge (`PALM_IN`), so the palm covers the face back
    to the wrist, and the fingers point on, away from the agent, to wrap round the far
    side. Contact points are `inset` metres inside their face."""
    u = _toward(box, from_xy)
    both = [_side_grasp(box, side, u, inset), _top_grasp(box, u, inset)]
    out = both[::-1] if 2.0 * box.half[2] <= FLAT or box.hi[2] <= KNEE else both
    # the palm on the top with the fingers across, where the far side is against a wall
    across = np.array([-u[1], u[0]]) * (1.0 if side == "l" else -1.0)
    grasps = [*out, _top_grasp(box, across, inset), _top_grasp(box, -across, inset)]
    return [replace(g, box=(box.lo, box.hi)) for g in grasps]


def _toward(box: Box, from_xy: np.ndarray) -> np.ndarray:
    """The horizontal unit direction from a floor point to a box's centre."""
    u = box.center[:2] - np.asarray(from_xy, float)[:2]
    n = float(np.hypot(*u))
    return u / n if n > 1e-9 else np.array([1.0, 0.0])


def touch_grasps(box: Box, from_xy: np.ndarray, inset: float = 0.004,
                 side: str | None = None) -> list[Grasp]:
    """Ways a hand lays its palm on an object to touch, press or switch it, best first:
    on the side face toward the agent (the fingers up, flat against it; a face at most
    `SMALL_FACE` across, a light switch on its wall, is first pressed by the fingertips
    of the `side` hand, the palm beside it, so the hand does not hide it) and on the top
    (the fingers pointing on, away from the agent); the top first for objects lower than
    `TOUCH_TOP`. Contact points are `inset` inside the face, at its middle."""
    u = _toward(box, from_xy)
    axis = 0 if abs(u[0]) * box.half[1] >= abs(u[1]) * box.half[0] else 1
    point = box.center.copy()
    point[axis] -= np.sign(u[axis] or 1.0) * (box.half[axis] - min(inset, box.half[axis]))
    palm = np.zeros(3)
    palm[axis] = np.sign(u[axis] or 1.0)
    face = [Grasp(point, palm, np.array([0.0, 0.0, 1.0]), flat=True)]
    if 2 * max(box.half[2], box.half[1 - axis]) <= SMALL_FACE:
        face = _fingertip_presses(box, point, palm, axis, side) + face
    at = np.r_[box.center[:2], box.hi[2] - min(inset, box.half[2])]
    down = np.array([0.0, 0.0, -1.0])
    top = Grasp(at, down, np.r_[u, 0.0], flat=True)
    across = [Grasp(at, down, np.array([-u[1] * s, u[0] * s, 0.0]), flat=True)
              for s in (1.0, -1.0)]
    first = [top, *face] if box.hi[2] < TOUCH_TOP else [*face, top]
    return first + across  # the fingers along a wall behind it


def _fingertip_presses(box: Box, point: np.ndarray, palm: np.ndarray, axis: int,
                       side: str | None) -> list[Grasp]:
    """The palm flat beside a small face, the fingers level along it and their tips
    (`FINGERTIPS`) on its near 30 %: a light switch pressed, and still seen. Fingers
    toward the body's middle first (to the left for the right hand)."""
    left = np.zeros(3)
    left[1 - axis] = palm[axis] * (1.0 if axis == 0 else -1.0)  # the agent's left
    width = float(box.half[1 - axis])
    out = []
    for fingers in ((left, -left) if side != "l" else (-left, left)):
        out.append(Grasp(point - (FINGERTIPS + 0.4 * width) * fingers, palm, fingers,
                         flat=True))
    return out


def _side_grasp(box: Box, side: str, u: np.ndarray, inset: float) -> Grasp:
    """The palm flat on the box's side face on the hand's side, at the box's middle
    height (at least `PALM_HALF_WIDTH` above its bottom)."""
    outward = np.array([u[1], -u[0]]) if side == "r" else np.array([-u[1], u[0]])
    across = 0 if abs(outward[0]) >= abs(outward[1]) else 1
    along = 1 - across
    sign = 1.0 if outward[across] >= 0.0 else -1.0
    ahead = 1.0 if u[along] >= 0.0 else -1.0
    c, h = box.center, box.half
    point = c.copy()
    point[across] = c[across] + sign * (h[across] - min(inset, h[across]))
    point[along] = c[along] - ahead * h[along] + ahead * min(h[along], PALM_IN)
    point[2] = min(max(c[2], box.lo[2] + PALM_HALF_WIDTH), box.hi[2] - min(inset, h[2]))
    palm, fingers = np.zeros(3), np.zeros(3)
    palm[across] = -sign
    fingers[along] = ahead
    return Grasp(point, palm, fingers)


def hand_room_clear(grasp: Grasp, clear_ray) -> bool:
    """Whether the hand fits where `grasp` puts it: rays out of the taken face (from the
    heel, the contact point and the fingers' end) meet nothing within `HAND_ROOM`.
    `clear_ray(start, direction, length)` answers for one ray."""
    out = -grasp.palm
    return all(clear_ray(grasp.point + along * grasp.fingers + 0.006 * out, out, HAND_ROOM)
               for along in (-0.03, 0.0, 0.06))


def _top_grasp(box: Box, u: np.ndarray, inset: float) -> Grasp:
    """The palm down on a flat box's top, `PALM_IN` past its near edge along the
    horizontal direction `u` (unit) from the agent, the fingers pointing along `u`."""
    c, h = box.center, box.half
    reach = float(abs(u[0]) * h[0] + abs(u[1]) * h[1])  # the near edge along u
    xy = c[:2] - u * reach + u * min(reach, PALM_IN)
    xy = np.clip(xy, box.lo[:2], box.hi[:2])
    point = np.r_[xy, box.hi[2] - min(inset, h[2])]
    return Grasp(point, np.array([0.0, 0.0, -1.0]), np.r_[u, 0.0])


@dataclass(frozen=True)
class ReachPlan:
    """A reach: the pose at its end (standing where it must, crouched if low), the
    distance the hand stays from its target point and how deep the body then passes
    into things other than what the hand takes (metres)."""

    pose: Pose
    gap: float  # metres
    inside: float = 0.0
    wrist: float = 0.0  # metres from the wrist to the object's box (grasps)

    @property
    def clear(self) -> bool:
        return self.inside <= CLEAR

    @property
    def touches(self) -> bool:
        return self.gap <= TOUCH and self.wrist <= WRIST


class ReachPlanner:
    """Finds a standing point from which a hand reaches a target point."""

    def __init__(self, layout: Layout, ik: ArmIK, shape: AgentShape,
                 clearance: Clearance | None = None):
        self.ik, self.shape = ik, shape
        self.walk = layout.walk
        self.clearance = clearance
        self.walls = wall_boxes(layout)
        self.hands_in: dict[str, set[int]] = {}
        """Per hand, the nodes it may be inside during the reach being planned (what it
        takes or holds); set by the caller before `plan`."""
        self.max_lean = MAX_LEAN
        """Radians: how far the spine may bend forward in the reaches being weighed."""
        self.spare: str | None = None
        """The arm (side) that holds nothing and does not reach, which a reach whose body
        passes into something may move out of the way (`SPARE`); set by the caller."""

    def inside(self, pose: Pose) -> float:
        """How deep (m) the body in `pose` passes into anything but what the hands may be
        inside (`hands_in`); objects where the IK's data has them."""
        if self.clearance is None:
            return 0.0
        ik = self.ik
        write_qpos(ik.data.qpos, pose, ik.scene.joint_qpos)
        mujoco.mj_kinematics(ik.model, ik.data)
        found = self.clearance.penetrations(ik.data, self.hands_in, CLEAR)
        return max((p.depth for p in found), default=0.0)

    def spare_arm(self, pose: Pose, side: str, depth: float) -> tuple[Pose, float]:
        """`pose` (whose body lies `depth` deep in something) with the spare arm (not
        `side`'s) at the first of `SPARE` that brings the body clear, else the least deep
        of them if less deep than `depth`; and how deep the body then is."""
        other = self.spare
        if other is None or other == side:
            return pose, depth
        best = (pose, depth)
        for angles in SPARE:
            tried = spared(pose, other, angles)
            deep = self.inside(tried)
            if deep < best[1] - 1e-3:
                best = (tried, deep)
            if deep <= CLEAR:
                break
        return best

    def fits(self, xy: np.ndarray) -> bool:
        """Whether the agent may stand at `xy`: the nearest cell of the floor model
        (`homesim.world.floor`, the one grounding's spots come from) is walkable."""
        if self.walk is None:
            return False
        return self.walk.walkable(*self.walk.index(float(xy[0]), float(xy[1])))

    def reach_from(self, xy: np.ndarray, side: str, point: np.ndarray,
                   grip: np.ndarray | None = None, grasp_of: GraspOf | None = None
                   ) -> ReachPlan:
        """The best reach of `point` standing at `xy`, facing it (crouching if low);
        `grip`: with the point held at this offset from the hand (see `ArmIK.reach`);
        `grasp_of`: taking hold of an object instead, the first of its grasps from `xy`
        that the hand can make (else the one it comes closest to)."""
        if grasp_of is None:
            return self._reach_from(xy, side, point, grip, None)
        best: ReachPlan | None = None
        for grasp in grasp_of(xy):
            plan = self._reach_from(xy, side, grasp.point, None, grasp)
            if best is None or _better(plan, best):
                best = plan
            if plan.touches and plan.clear:
                break
        assert best is not None
        return best

    def _reach_from(self, xy: np.ndarray, side: str, point: np.ndarray,
                    grip: np.ndarray | None, grasp: Grasp | None) -> ReachPlan:
        d = point[:2] - xy
        yaw = math.atan2(d[1], d[0]) if np.hypot(*d) > 1e-6 else 0.0
        base = standing(self.shape, xy, yaw)
        best: ReachPlan | None = None
        for drop in CROUCH if point[2] < LOW else CROUCH[:1]:
            low = crouched(base, self.shape, drop)
            wrist = 0.0
            if grasp is not None:
                reached, gap = self.ik.grasp(low, side, grasp, max_lean=self.max_lean)
                if grasp.box is not None:
                    lo, hi = grasp.box
                    w = self.ik.site(reached, f"j:{side}_wrist")
                    wrist = float(np.linalg.norm(w - np.clip(w, lo, hi)))
            else:
                reached, _ = self.ik.reach(low, side, point, grip, max_lean=self.max_lean)
                gap = float(np.linalg.norm(self.ik.held_point(reached, side, grip) - point))
            inside = self.inside(reached) if gap <= TOUCH else 0.0
            if inside > CLEAR:
                reached, inside = self.spare_arm(reached, side, inside)
            plan = ReachPlan(reached, gap, inside, wrist)
            if best is None or _better(plan, best):
                best = plan
            if plan.touches and plan.clear:
                break
        assert best is not None
        return best

    def plan(self, start_xy: np.ndarray, side: str, point: np.ndarray,
             grip: np.ndarray | None = None, grasp_of: GraspOf | None = None) -> ReachPlan:
        """Where to stand to reach `point`: the first point on the way from `start_xy`
        toward it (every `STEP` metres, while the body fits) from which the hand touches
        it without bowing more than `COMFORT_LEAN` (else the first from which it touches
        at all); else the nearest point around it (`AROUND`) from which it does; else the
        point tried from which the hand comes closest. A reach whose body then passes into
        something bows less (`upright`)."""
        return self.upright(self._search(start_xy, side, point, grip, grasp_of), side,
                            point, grip, grasp_of)

    def upright(self, plan: ReachPlan, side: str, point: np.ndarray,
                grip: np.ndarray | None = None, grasp_of: GraspOf | None = None
                ) -> ReachPlan:
        """`plan`, or where its body passes deeper than `CLEAR` into something (a head in
        the wall behind a desk, leaning for a thing out of reach), the same reach with the
        spine bent `LEAN_BACK` less at a time: the first whose body is clear (that still
        touches, when `plan` did), else the least deep."""
        depth = plan.inside if plan.touches else self.inside(plan.pose)
        if depth <= CLEAR:
            return plan
        best = replace(plan, inside=depth)
        cap = _lean(plan) - LEAN_BACK
        while cap > -LEAN_BACK:
            self.max_lean = max(cap, 0.0)
            try:
                tried = self.reach_from(plan.pose.xy, side, point, grip, grasp_of)
            finally:
                self.max_lean = MAX_LEAN
            if not tried.touches:
                tried = replace(tried, inside=self.inside(tried.pose))
            if tried.inside <= CLEAR and (tried.touches or not plan.touches):
                return tried
            if tried.inside < best.inside - 1e-3 and tried.touches >= plan.touches:
                best = tried
            cap -= LEAN_BACK
        return best

    def _search(self, start_xy: np.ndarray, side: str, point: np.ndarray,
                grip: np.ndarray | None, grasp_of: GraspOf | None) -> ReachPlan:
        d = point[:2] - start_xy
        dist = float(np.hypot(*d))
        tries = [start_xy + d / dist * s for s in np.arange(STEP, dist, STEP)]
        best = self.reach_from(start_xy, side, point, grip, grasp_of)
        touching = best if (best.touches and best.clear
                            and not self.walled(start_xy, point)) else None
        for xy in tries:
            if touching is not None and _lean(touching) <= COMFORT_LEAN:
                return touching
            if not self.fits(xy):
                break
            plan = self.reach_from(xy, side, point, grip, grasp_of)
            if (plan.touches and plan.clear
                    and (touching is None or _lean(plan) < _lean(touching))):
                touching = plan
            if _better(plan, best):
                best = plan
        if touching is not None:
            return touching
        for xy in self.around(start_xy, point)[:MAX_AROUND]:
            plan = self.reach_from(xy, side, point, grip, grasp_of)
            if _better(plan, best):
                best = plan
            if plan.touches and plan.clear:
                break
        return best

    def around(self, start_xy: np.ndarray, point: np.ndarray) -> list[np.ndarray]:
        """Points where the body fits around `point` (`AROUND` distances, 16 directions)
        without a wall between them and it, nearest to `start_xy` first."""
        spots = [point[:2] + r * np.array([math.cos(a), math.sin(a)])
                 for r in AROUND for a in np.linspace(0.0, 2 * math.pi, 16, endpoint=False)]
        spots = [xy for xy in spots if self.fits(xy) and not self.walled(xy, point)]
        return sorted(spots, key=lambda xy: float(np.hypot(*(xy - start_xy))))

    def walled(self, xy: np.ndarray, point: np.ndarray) -> bool:
        """Whether a wall stands between the floor point `xy` and `point` (the level line
        from above `xy` to it, less its last `WALL_SLACK`: a switch on a wall is reached)."""
        lo, hi = self.walls
        start = np.r_[xy[:2], point[2]]
        vec = np.asarray(point, float) - start
        length = float(np.linalg.norm(vec))
        if length <= WALL_SLACK or not len(lo):
            return False
        return segment_hits(start, vec * (1.0 - WALL_SLACK / length), lo, hi)

    def clear_line(self, a: np.ndarray, b: np.ndarray) -> bool:
        """Whether the body fits all along the segment a-b (checked every 5 cm)."""
        n = max(2, int(np.ceil(np.linalg.norm(b - a) / 0.05)) + 1)
        return all(self.fits(a + t * (b - a)) for t in np.linspace(0.0, 1.0, n)[1:])


def _better(a: ReachPlan, b: ReachPlan) -> bool:
    """Whether reach `a` beats `b`: touching first (the wrist near a grasped object too),
    then the body clear (else less deep in things), then the hand nearer its point."""
    ta, tb = a.touches, b.touches
    if ta != tb:
        return ta
    if ta and (a.clear != b.clear or not a.clear):
        return a.clear if a.clear != b.clear else a.inside < b.inside - 1e-3
    return a.gap < b.gap - 1e-3


def _lean(plan: ReachPlan) -> float:
    return plan.pose.joints.get("spine_pitch", 0.0)

