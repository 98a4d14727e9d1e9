"""Turn an executed program into a timeline of frames: agent poses and object states.

The symbolic simulator's trace drives everything: which node each step targets, what it
grabs (HOLDS_RH / HOLDS_LH added), where it puts it (ON / INSIDE added when a hold is
removed), what opens or switches on (state changes). Each action plays the animation its
catalog row names (`ActionSpec.motion`); animations are registered here by name with
`@animation(...)`, as effects are in `homesim.sim.effects`: walking along an A* path with
a gait, reaching with IK, sitting, lying, turning. Where grounding chose a standing spot
for a step (`Grounding.standing`), the agent walks to that spot.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np

from homesim.errors import ExecutionError
from homesim.program.actions import ACTIONS
from homesim.render.agent import AgentShape
from homesim.render.clearance import Clearance
from homesim.render.gl import mujoco
from homesim.render.ik import ArmIK, Grasp, wrist_joints
from homesim.render.interact import (
    CLEAR,
    COMFORT_LEAN,
    TOUCH,
    GraspOf,
    ReachPlanner,
    box_gap,
    hand_room_clear,
    out_of_walls,
    palm_grasps,
    touch_grasps,
)
from homesim.render.layout import SEAT_HEIGHT, Box, room_of_point
from homesim.render.navigation import build_grid, plan_path, walled
from homesim.render.poses import (
    SPARE,
    Pose,
    blend,
    carrying,
    gripping,
    lying,
    sitting,
    spared,
    standing,
    walk_cycle,
    write_qpos,
)
from homesim.render.props import Props
from homesim.render.scene import SceneModel
from homesim.sim.execute import ExecutionResult, StepRecord
from homesim.sim.state import Changes
from homesim.world.graph import EnvironmentGraph
from homesim.world.vocab import HOLDS_LH, HOLDS_RH, INSIDE, ON, S_CLOSED, S_OPEN

WALK_SPEED = 1.2  # m/s
RUN_SPEED = 2.6  # m/s
STRIDE = 1.3  # metres per gait cycle (two steps)
TURN_SPEED = 3.0  # rad/s
AT_SPOT = 0.05
"""An agent this close (m) to its step's standing spot does not walk to it."""
SPOT_REACH = 1.0
"""Metres: a standing spot farther than this from what its step acts on (where that is
now) is not used (`Animator._spot_for`)."""
HEAD_RADIUS = 0.065
"""The head's radius as a share of the agent's height (as `agent.agent_mjcf` draws it)."""
GRAVITY = 9.81
SWING_SECONDS = 1.0
"""How long a door or an appliance's front takes to swing open or closed."""
HANDLE_SLIP = 0.03
"""Metres: the hand lets go of a swinging handle once the arm cannot follow it closer."""
BODY_CLEAR = 0.25
"""Metres: a swinging front stays this far from the point the agent stands on."""
SWING_STAND = (0.45, 0.55, 0.65)
"""Metres from a handle of the standing points tried out of the front's way..."""
MAX_SWING_SPOTS = 12
"""... at most this many (the nearest to the agent first)."""
REST_GAP = 0.005
"""Metres between the body and the seat or mattress it rests on."""
REST_CLEAR = 0.01
"""Metres: a sitting or lying pose whose body passes deeper than this into anything is
tried after those that do not."""
SIT_SHIFTS = (0.0, 0.04, 0.08, 0.12, 0.16, -0.06, -0.12)
"""Metres the pelvis is moved toward a seat's front edge when the back would enter the
backrest (or back, when the legs would enter a desk)..."""
SIT_TURNS = (0.0, 0.3, -0.3, 0.6, -0.6)
"""... radians it is turned when the legs would enter what stands in front..."""
SIT_KNEES = (1.22, 1.6)
"""... and knee angles tried (the second draws the feet back under the seat)."""
HOVER = 0.009
"""Metres: a touch whose fingers would enter the wall behind what they press (a light
switch, a faucet) is tried again this far off its face, then twice as far."""
SIT_ALONG = tuple(x for k in range(1, 7) for x in (0.2 * k, -0.2 * k))
"""Metres along a seat (sideways) tried when sitting at the spot would put the body into
something lying there."""
BACK_OFF = (0.1, 0.2, 0.3)
"""Metres back from where it stands the agent tries, when its body there passes into
something, before it uses a held object in place."""
SIT_SLIDE = 0.1
"""Metres between the places along a seat tried for one that is clear with a free floor
before it..."""
SIT_TRIES = 8
"""... at most this many such places that are not clear."""
SIT_APPROACH = (0.35, 0.5, 0.65)
"""Metres from the seated pelvis of the floor points tried to sit down from, when the one
before the seat's front is taken."""
SIT_WAY = (0.15, 0.3, 0.45, 0.6, 0.75, 0.9)
"""... and the points of the way from there, bending over the seat, that must be clear."""
SIT_INSET = 0.35
"""Metres from a seat's front edge to where the pelvis sits (less on a shallow seat)."""
SIT_FRONT = 0.3
"""Metres in front of a seat's front edge where the agent stands before sitting down..."""
SIT_ABOVE = 0.18
"""... and how high above the seated pose the pelvis passes over the front edge."""
READ_AT = (0.32, 0.12)
"""Metres in front of and below the eyes where a read object's centre is held."""
PILLOW_IN = 0.3
"""Metres from a bed's head end to where the head lies."""
LIE_NECKS = (0.3, 0.5, 0.7, 0.9)
"""Neck bends (radians) tried until the head rests above the pillow."""

Standing = Mapping[int, tuple[float, float]]
"""Step index -> (x, z) standing spot chosen by grounding (Unity frame = MuJoCo x, y)."""


@dataclass(frozen=True)
class Attach:
    """A hand taking an object: the frame (the last before the object moves with the
    hand) and the distance between the hand and the object's box then (metres)."""

    frame: int
    node: int
    side: str
    gap: float


@dataclass(frozen=True)
class Interaction:
    """The hands acting on objects in one step: the frames from the start of the reach to
    the hand's return, and the frame of the effect (`peak`: grab, put, switch, swing).
    `nodes` are the step's objects (the one acted on first); `room` the room it happens
    in (the acted-on object's, else the agent's); `side` the hand."""

    step: int
    nodes: tuple[int, ...]
    side: str
    start: int
    peak: int
    end: int
    room: int | None


class Reached(NamedTuple):
    """A reach done: the pose at its end, the pose it started from, its first frame and
    the frame the hand arrived."""

    pose: Pose
    rest: Pose
    start: int
    peak: int


@dataclass
class Timeline:
    """Per-frame state of the scene: arrays indexed by frame, and each step's frames."""

    qpos: list[np.ndarray] = field(default_factory=list)  # (nq,) per frame
    mocap: list[np.ndarray] = field(default_factory=list)  # (nmocap, 3) per frame
    lamps: list[frozenset[int]] = field(default_factory=list)  # lamp node ids lit
    screens: list[frozenset[int]] = field(default_factory=list)  # screen node ids on
    step_frames: list[tuple[int, int]] = field(default_factory=list)  # [start, end]
    focus: list[int] = field(default_factory=list)  # per step: the node it acts on, or -1
    attaches: list[Attach] = field(default_factory=list)  # objects taken (gap: hand-box)
    releases: list[Attach] = field(default_factory=list)  # put down (gap: how far it moved)
    interactions: list[Interaction] = field(default_factory=list)
    rests: list[tuple[int, int]] = field(default_factory=list)
    """(first, last) frames of each sit or lie: from getting down to the end of its step."""

    def __len__(self) -> int:
        return len(self.qpos)


class Animator:
    """Builds a `Timeline` for one program on one scene: the agent's motions and frames.

    `standing` (step index -> (x, z)) holds grounding's standing spots: a step that walks
    goes to its spot, so render and grounding share one floor model.
    """

    def __init__(self, scene: SceneModel, graph: EnvironmentGraph, shape: AgentShape,
                 fps: float = 30, seed: int = 0, standing: Standing | None = None):
        # fps may be fractional: the activity dataset animates at fps / speed, so every
        # motion takes 1/speed of its time (homesim.dataset).
        self.scene, self.graph, self.shape, self.fps = scene, graph, shape, fps
        self.rng = np.random.default_rng(seed)
        self.ik = ArmIK(scene)
        self.planner = ReachPlanner(scene.layout, self.ik, shape, Clearance(scene))
        self.step_index = -1
        self.grid = build_grid(scene.layout)
        self.data = mujoco.MjData(scene.model)
        self.qpos = scene.model.qpos0.copy()
        self.props = Props(scene, graph, self.grid, self.rng)
        self.standing = dict(standing or {})
        self.spot: np.ndarray | None = None  # the current step's standing spot (x, y)
        start = scene.layout.start
        if not self.grid.free[self.grid.cell(start)]:
            start = self.grid.point(self.grid.nearest_free(start))
        self.pose = standing_pose(shape, start)
        self.posture = "stand"
        self._rest_from: int | None = None  # the frame the current step began to sit or lie
        self.reaching: frozenset[str] = frozenset()
        self.timeline = Timeline()

    # -- frame output ---------------------------------------------------------------
    def emit(self, pose: Pose) -> None:
        """Append one frame with the agent in `pose` and held objects in its hands."""
        self.pose = pose
        props = self.props
        for side in props.held:
            if pose.tilt == 0.0 and side not in self.reaching:
                pose = self._carrying(pose, side)
        pose = gripping(pose, props.held)  # hands close on what they hold
        write_qpos(self.qpos, pose, self.scene.joint_qpos)
        for n, angle in props.hinge_angle.items():
            self.qpos[self.scene.hinge_qpos[n]] = angle
        if props.held:
            self._carry()
        tl = self.timeline
        tl.qpos.append(self.qpos.copy())
        tl.mocap.append(props.mocap.copy())
        tl.lamps.append(props.lit_lamps())
        tl.screens.append(frozenset(props.screens))

    def _carry(self) -> None:
        """Move held objects with the hands of the pose just written (each keeps where
        the hand took it: its grip offset in the hand's frame)."""
        self.data.qpos[:] = self.qpos
        mujoco.mj_kinematics(self.scene.model, self.data)
        m = self.scene.model
        for side, n in self.props.held.items():
            site = self.scene.hand_sites[side]
            rot = self.data.xmat[m.site_bodyid[site]].reshape(3, 3)
            grip = self.props.grip.get(side, np.zeros(3))
            self.props.move(n, self.data.site_xpos[site] + rot @ grip)

    def _carried(self, pose: Pose, side: str) -> Pose:
        """`pose` as `emit` draws it when the `side` arm is not reaching: carrying what
        that hand holds (standing or sitting upright)."""
        if side in self.props.held and pose.tilt == 0.0:
            return self._carrying(pose, side)
        return pose

    def _carrying(self, pose: Pose, side: str) -> Pose:
        """`pose` with the `side` arm carrying (`CARRY`), its wrist turned as it took
        what it holds."""
        return carrying(pose, side).with_joints(**self.props.wrist.get(side, {}))

    def ray_test(self, skip: tuple[int, ...] = ()) -> Callable[[np.ndarray, np.ndarray,
                                                                  float], bool]:
        """A test of whether a ray (start, unit direction, length) through the scene as it
        is now meets nothing but the agent and the nodes `skip`."""
        m, d = self.scene.model, self.data
        d.qpos[:] = self.qpos
        if m.nmocap:
            d.mocap_pos[:] = self.props.mocap
        mujoco.mj_kinematics(m, d)
        ignore = {self.scene.character_id, *skip}
        geom = np.zeros(1, np.int32)

        def clear(start: np.ndarray, direction: np.ndarray, length: float) -> bool:
            travelled = 0.0
            while travelled < length:
                hit = mujoco.mj_ray(m, d, start + travelled * direction, direction, None,
                                    1, -1, geom)
                if hit < 0 or travelled + hit >= length:
                    return True
                if int(self.scene.geom_node[geom[0]]) not in ignore:
                    return False
                travelled += hit + 1e-4
            return True
        return clear

    def hold(self, seconds: float, pose: Pose | None = None) -> None:
        for _ in range(max(1, round(seconds * self.fps))):
            self.emit(pose or self.pose)

    def move_to(self, target: Pose, seconds: float, during=None) -> None:
        """Blend from the current pose to `target`; `during(t)` runs before each frame."""
        start = self.pose
        n = max(1, round(seconds * self.fps))
        for i in range(1, n + 1):
            if during is not None:
                during(i / n)
            self.emit(blend(start, target, i / n))

    # -- motions ----------------------------------------------------------------------
    def stand_up(self) -> None:
        if self.posture == "stand":
            return
        spot = self.grid.point(self.grid.nearest_free(self.pose.xy + 0.5 * np.array(
            [math.cos(self.pose.yaw), math.sin(self.pose.yaw)]), seen_from=self.pose.xy))
        self.move_to(standing(self.shape, spot, self.pose.yaw), 1.0)
        self.posture = "stand"

    def turn_to(self, point: np.ndarray) -> None:
        d = point[:2] - self.pose.xy
        if np.hypot(*d) < 1e-3:
            return
        yaw = math.atan2(d[1], d[0])
        diff = abs((yaw - self.pose.yaw + math.pi) % (2 * math.pi) - math.pi)
        if diff < 0.05:
            return
        target = Pose(self.pose.x, self.pose.y, self.pose.z, yaw, self.pose.tilt,
                      self.pose.joints)
        self.move_to(target, max(0.2, diff / TURN_SPEED))

    def walk(self, target: Box, run: bool = False, reach: float = 0.7) -> None:
        """Walk to the step's standing spot if it has one, else within `reach` of
        `target`; then face the target."""
        self.stand_up()
        if self.spot is not None:
            path = plan_path(self.grid, self.pose.xy, Box(np.r_[self.spot, 0.0],
                                                          np.zeros(3)), 0.0)
            path.append(self.spot.copy())  # the spot itself, even off render's grid
        else:
            path = plan_path(self.grid, self.pose.xy, target, reach)
        self.follow(path, run)
        self.move_to(standing(self.shape, self.pose.xy, self.pose.yaw), 0.25)
        self.turn_to(target.center)

    def follow(self, path: list[np.ndarray], run: bool) -> None:
        """Walk (or run) along way points with a gait."""
        speed = RUN_SPEED if run else WALK_SPEED
        base = standing(self.shape, self.pose.xy, self.pose.yaw)
        phase = 0.0
        for a, b in itertools.pairwise(path):
            length = float(np.linalg.norm(b - a))
            if length < 1e-3:
                continue
            self.turn_to(np.r_[b, 0.0])
            yaw = math.atan2(b[1] - a[1], b[0] - a[0])
            n = max(1, round(length / speed * self.fps))
            for i in range(1, n + 1):
                p = a + (b - a) * i / n
                phase += 2 * math.pi * (length / n) / STRIDE
                pose = Pose(float(p[0]), float(p[1]), base.z, yaw, 0.0, base.joints)
                self.emit(walk_cycle(pose, phase, run))

    def reach(self, side: str, point: np.ndarray, seconds: float = 0.6,
              at_peak=None, during=None, back: bool = True, step: bool = True,
              nodes: tuple[int, ...] = (), hold: float = 0.15,
              grip: np.ndarray | None = None, seed: Mapping[str, float] | None = None,
              grasp_of: GraspOf | None = None, acts_on: tuple[int, ...] = ()) -> Reached:
        """Reach `point` with a hand, call `at_peak()`, hold `hold` seconds and come back.

        Standing, the agent first steps toward the point until the hand can touch it
        (`ReachPlanner`: on the way, crouching for low points; `step=False` stays put
        and moves the arm only).
        `nodes`: the objects acted on, recorded as an `Interaction` of the step. `grip`:
        bring the point held at this offset from the hand (a held object's centre) to
        `point` rather than the hand. `seed`: joint angles the arm's IK starts from.
        `grasp_of`: take hold with the palm as it says (`palm_grasp`), the wrist turning.
        `acts_on`: objects the hand may enter besides `nodes` (a door's handle)."""
        self._plan_around(side, nodes + acts_on)
        reached = None
        if self.posture != "stand" or not step:
            if self.posture == "stand":
                self.turn_to(point)
            reached = self._reach_in_place(side, point, grip, seed, grasp_of, step)
            if reached is None:  # seated, out of reach or through something: get up
                self.stand_up()
        if reached is None:
            plan = self.planner.plan(self.pose.xy, side, point, grip, grasp_of)
            self.step_to(plan.pose.xy, point)
            reached = plan.pose
        rest = self.pose
        self.pose = self._carried(rest, side)  # the arm starts where it was drawn
        self.reaching = frozenset({side})
        start = len(self.timeline)
        self.move_to(reached, seconds, during)
        peak = len(self.timeline) - 1
        if at_peak is not None:
            at_peak()
        self.hold(hold, reached)
        if back:  # to where the arm is drawn once the reach is over (carrying or not)
            self.move_to(self._carried(rest, side), seconds * 0.8)
            self.pose = rest
            self.reaching = frozenset()
        if nodes:
            self.note_interaction(nodes, side, start, peak)
        return Reached(reached, rest, start, peak)

    def _reach_in_place(self, side: str, point: np.ndarray, grip: np.ndarray | None,
                        seed: Mapping[str, float] | None, grasp_of: GraspOf | None,
                        step: bool) -> Pose | None:
        """The arm's reach of `point` without moving the feet (seated, or `step=False`);
        None when seated and the hand does not touch, or the body passes deeper into
        something than it sits (`ReachPlanner.inside`): the agent then stands up and
        steps."""
        seeded = self.pose.with_joints(**(seed or {}))
        if grasp_of is not None:
            tries = [self.ik.grasp(seeded, side, g, lean=step) for g in grasp_of(self.pose.xy)]
            reached, gap = next(((p, gap) for p, gap in tries if gap <= TOUCH),
                                min(tries, key=lambda t: t[1]))
        else:
            reached, _ = self.ik.reach(seeded, side, point, grip, lean=step)
            gap = float(np.linalg.norm(self.ik.held_point(reached, side, grip) - point))
        if self.posture == "stand" or not step:
            return reached
        seated = max(CLEAR, self.planner.inside(self.pose) + 1e-3)  # as it sits already
        return reached if gap <= TOUCH and self.planner.inside(reached) <= seated else None

    def _plan_around(self, side: str, nodes: tuple[int, ...]) -> None:
        """Tell the reach planner where things are now and what the `side` hand may be
        inside (what it acts on and holds). Held objects are set aside: they move with
        the hand the planner is still choosing."""
        data, props = self.ik.data, self.props
        if self.scene.model.nmocap:
            data.mocap_pos[:] = props.mocap
            for n in props.held.values():
                if n in self.scene.mocap:
                    data.mocap_pos[self.scene.mocap[n]] = (0.0, 0.0, -50.0)
        self.planner.hands_in = {side: set(nodes) | {n for n in props.held.values()}}
        other = "l" if side == "r" else "r"
        self.planner.spare = None if other in props.held else other

    def note_interaction(self, nodes: tuple[int, ...], side: str, start: int,
                         peak: int) -> None:
        """Record the frames of a hands-on action of the current step, in the room of
        its object (where an object taken in it lay; a carried one's is the agent's)."""
        props = self.props
        first = nodes[0]
        taken = [a for a in self.timeline.attaches if a.node == first and start <= a.frame]
        if taken and first in self.scene.mocap:  # taken here: where it lay
            at = self.timeline.mocap[taken[0].frame][self.scene.mocap[first]][:2]
            room = self.graph.room_of(first)
            floor = self.scene.layout.room_floors.get(room) if room is not None else None
            if floor is None or np.any(np.abs(at - floor.center[:2]) > floor.half[:2]):
                room = room_of_point(self.scene.layout, at)
        elif first in props.held.values() and len(nodes) == 1:  # carried: the agent's
            room = None
        else:
            room = self.graph.room_of(nodes[-1] if len(nodes) > 1 else first)
        if room is None or room not in self.scene.layout.room_floors:
            room = room_of_point(self.scene.layout, self.pose.xy)
        self.timeline.interactions.append(Interaction(
            self.step_index, nodes, side, start, peak, len(self.timeline) - 1, room))

    def step_to(self, xy: np.ndarray, face: np.ndarray) -> None:
        """A few steps to `xy` (straight when the way is clear), then face `face`."""
        xy = np.asarray(xy, float)
        if float(np.linalg.norm(xy - self.pose.xy)) > 0.01:
            if self.planner.clear_line(self.pose.xy, xy):
                path = [self.pose.xy.copy(), xy]
            else:  # round the furniture on the grid, then step onto the point
                try:
                    path = plan_path(self.grid, self.pose.xy,
                                     Box(np.r_[xy, 0.0], np.zeros(3)), 0.0)
                except ExecutionError:  # no way on the grid: straight there
                    path = [self.pose.xy.copy()]
                path.append(xy)
            self.follow(path, run=False)
            self.move_to(standing(self.shape, self.pose.xy, self.pose.yaw), 0.2)
        d = face[:2] - self.pose.xy
        yaw = math.atan2(d[1], d[0])
        if abs((yaw - self.pose.yaw + math.pi) % (2 * math.pi) - math.pi) > 1e-3:
            target = Pose(self.pose.x, self.pose.y, self.pose.z, yaw, self.pose.tilt,
                          self.pose.joints)
            diff = abs((yaw - self.pose.yaw + math.pi) % (2 * math.pi) - math.pi)
            self.move_to(target, max(0.1, diff / TURN_SPEED))

    def back_off(self) -> None:
        """Standing where the body passes deeper than `CLEAR` into something (a hand
        hanging into the counter it took a glass from: scene5), a step back to the first
        point `BACK_OFF` behind from which it does not, if any (before a held object is
        used in place)."""
        if self.posture != "stand":
            return
        pose = self.pose
        for side in self.props.held:
            pose = self._carried(pose, side)
        if self._clash(pose) <= CLEAR:
            return
        ahead = np.array([math.cos(pose.yaw), math.sin(pose.yaw)])
        for d in BACK_OFF:
            xy = self.pose.xy - d * ahead
            if self.planner.fits(xy) and self._clash(replace(
                    pose, x=float(xy[0]), y=float(xy[1]))) <= CLEAR:
                self.step_to(xy, xy + ahead)
                return

    def shoulder(self, side: str) -> np.ndarray:
        """World position of a shoulder in the current pose."""
        return self.ik.site(self.pose, f"j:{side}_shoulder")

    def sit(self, node: int) -> None:
        """Walk to a seat and sit on it, facing away from it: on the seat's drawn top,
        as far back as the body clears the backrest (`_seated`)."""
        seat = self.props.box_of(node)
        self.walk(seat, reach=0.5)
        spot, yaw = self._seat_spot(node, seat)
        ahead = np.array([math.cos(yaw), math.sin(yaw)])
        seated, approach = self._sit_place(node, seat, spot, yaw)
        if approach is not None:
            self.step_to(approach, approach + ahead)
        else:
            self.turn_to(self.pose.xy + ahead)
        self._rest_from = len(self.timeline)
        self.move_to(_over_seat(seated), 0.6)  # bending over the seat's front edge...
        self.move_to(seated, 0.5)  # ... then down onto it
        self.posture = "sit"

    def _seat_edge(self, node: int, seat: Box, spot: np.ndarray, axis: int,
                   sign: float) -> float:
        """Where the seat's drawn top begins, coming in from the box's front face along
        `axis` across from `spot` (an L sofa's box is empty in front of its back seat)."""
        front = seat.center[axis] + sign * seat.half[axis]
        xy = spot.copy()
        for d in np.arange(0.0, 2 * seat.half[axis], 0.05):
            xy[axis] = front - sign * d
            top = self._top_at(node, xy, SEAT_HEIGHT + 0.35)
            if top is not None and top > 0.2:
                return float(xy[axis])
        return float(front)

    def _seat_spot(self, node: int, seat: Box) -> tuple[np.ndarray, float]:
        """Where the pelvis goes on a seat and which way the agent faces: the seat's
        front (`Part.front`: a chair faces its desk, a sofa its TV) `SIT_INSET` in from
        its front edge, across from where the agent stands; else away from the seat's
        middle toward the agent."""
        inset = np.minimum(seat.half[:2], SIT_INSET)
        spot = np.clip(self.pose.xy, seat.lo[:2] + inset, seat.hi[:2] - inset)
        part = self.scene.layout.part(node)
        if part is not None and part.front is not None:
            axis, sign = part.front
            spot[axis] = self._seat_edge(node, seat, spot, axis, sign) - sign * inset[axis]
            yaw = (0.0 if sign > 0 else math.pi) if axis == 0 else math.copysign(math.pi / 2,
                                                                                 sign)
            return spot, yaw
        away = self.pose.xy - spot
        yaw = math.atan2(away[1], away[0]) if np.hypot(*away) > 1e-3 else self.pose.yaw + math.pi
        return spot, yaw

    def lie(self, node: int) -> None:
        """Walk to a bed and lie on it on the back, the head on the pillow end (away from
        its foot, the side facing the room) resting above what lies there."""
        bed = self.props.box_of(node)
        self.walk(bed, reach=0.5)
        part = self.scene.layout.part(node)
        axis, sign = part.front if part is not None and part.front else (
            0 if bed.half[0] >= bed.half[1] else 1, 1.0)
        yaw = (0.0 if sign > 0 else math.pi) if axis == 0 else (
            math.pi / 2 if sign > 0 else -math.pi / 2)
        self._rest_from = len(self.timeline)
        self.move_to(self._lying_on(node, bed, axis, sign, yaw), 1.4)
        self.posture = "lie"

    # -- resting on furniture ------------------------------------------------------------
    def _top_at(self, node: int, xy: np.ndarray, below: float) -> float | None:
        """The highest top lower than `below` (m) of the node's drawn shapes over `xy`."""
        part = self.scene.layout.part(node)
        if part is None:
            return None
        tops = [float(sh.center[2] + sh.half[2]) for sh in part.shapes
                if np.all(np.abs(xy - sh.center[:2]) <= sh.half[:2])
                and sh.center[2] + sh.half[2] < below]
        return max(tops, default=None)

    def _clash(self, pose: Pose) -> float:
        """How deep (m) the body in `pose` passes into anything (objects where they are)."""
        self._plan_around("r", ())
        self.planner.hands_in = {}
        return self.planner.inside(pose)

    def _rested(self, pose: Pose, top: float, parts: tuple[str, ...]) -> Pose:
        """`pose` raised or lowered so the lowest point of `parts` lies on `top`."""
        write_qpos(self.ik.data.qpos, pose, self.scene.joint_qpos)
        mujoco.mj_kinematics(self.scene.model, self.ik.data)
        low = self.planner.clearance.lowest(self.ik.data, parts) if self.planner.clearance \
            else pose.z
        return replace(pose, z=pose.z + top + REST_GAP - low)

    def _seated(self, node: int, spot: np.ndarray, yaw: float) -> Pose:
        """Sitting on a seat near `spot` facing `yaw`: the pelvis and thighs on the seat's
        top, moved toward its front edge and turned a little until the body clears the
        backrest, arms and whatever stands in front (the least deep pose otherwise)."""
        ahead = np.array([math.cos(yaw), math.sin(yaw)])
        best: tuple[float, Pose] | None = None
        for shift, turn, knee in itertools.product(SIT_SHIFTS, SIT_TURNS, SIT_KNEES):
            xy = spot + shift * ahead
            top = self._top_at(node, xy, SEAT_HEIGHT + 0.35) or SEAT_HEIGHT
            pose = sitting(self.shape, xy, yaw + turn, top).with_joints(
                l_knee=knee, r_knee=knee)
            pose = self._rested(pose, top, ("agent", "l_thigh", "r_thigh"))
            depth = self._clash(pose)
            if best is None or depth < best[0] - 1e-3:
                best = (depth, pose)
            if depth <= REST_CLEAR:
                break
        assert best is not None
        return best[1]

    def _sit_place(self, node: int, seat: Box, spot: np.ndarray, yaw: float
                   ) -> tuple[Pose, np.ndarray | None]:
        """How to sit on a seat and where to stand before getting down (None: where the
        agent stands). At `spot` when the body clears everything on its way down there
        (`_sit_clash`) and the floor before the seat is free; else the nearest place
        along the seat (every `SIT_SLIDE` m) that is clear with a free floor before it
        (a pillow or the arm at the spot, a coffee table before it: gen-1, -3, -4, where
        the agent slid up to 1 m sideways across the seat getting down); else the least
        deep place of `_seated_along` with a way down from beside the seat
        (`_sit_approach`); else the least deep of those tried with a free floor before
        them."""
        ahead = np.array([math.cos(yaw), math.sin(yaw)])
        along = np.array([-math.sin(yaw), math.cos(yaw)])
        edge = float(abs(ahead @ seat.half[:2]))  # from the seat's axis to its front edge
        room = float(abs(along @ seat.half[:2])) - SIT_INSET / 2
        fronted: list[tuple[float, Pose, np.ndarray]] = []
        offsets = sorted((SIT_SLIDE * k for k in range(-int(2 * room / SIT_SLIDE) - 1,
                                                        int(2 * room / SIT_SLIDE) + 2)),
                         key=lambda o: (abs(o), o < 0))
        for offset in offsets:
            xy = spot + offset * along
            if offset and abs(float(along @ (xy - seat.center[:2]))) > room:
                continue
            front = xy + ahead * (max(edge - float(abs(ahead @ (xy - seat.center[:2]))), 0.0)
                                  + SIT_FRONT)
            if not self.planner.fits(front):
                continue
            pose = self._seated(node, xy, yaw)
            depth = self._sit_clash(pose)
            if depth <= REST_CLEAR:
                return pose, front
            fronted.append((depth, pose, front))
            if len(fronted) >= SIT_TRIES:
                break
        spot, seated = self._seated_along(node, seat, spot, yaw)
        approach = self._sit_approach(seated)
        if approach is not None or not fronted:
            return seated, approach
        depth, pose, front = min(fronted, key=lambda t: t[0])
        return pose, front

    def _seated_along(self, node: int, seat: Box, spot: np.ndarray, yaw: float
                      ) -> tuple[np.ndarray, Pose]:
        """Where on a seat to sit and how (`_seated`): at `spot`, else, where the body
        there passes into something (a pillow on the sofa), moved along the seat by
        `SIT_ALONG` until it does not (the least deep otherwise)."""
        pose = self._seated(node, spot, yaw)
        best = (self._sit_clash(pose), spot, pose)
        along = np.array([-math.sin(yaw), math.cos(yaw)])
        room = float(abs(along @ seat.half[:2])) - SIT_INSET / 2
        for offset in SIT_ALONG:
            if best[0] <= REST_CLEAR:
                break
            xy = spot + offset * along
            if abs(float(along @ (xy - seat.center[:2]))) > room:
                continue
            pose = self._seated(node, xy, yaw)
            depth = self._sit_clash(pose)
            if depth < best[0] - 1e-3:
                best = (depth, xy, pose)
        return best[1], best[2]

    def _sit_approach(self, seated: Pose) -> np.ndarray | None:
        """Where to stand before sitting down when the floor before the seat's front is
        taken (a chair pushed under its desk): the floor point near the seat, nearest to
        the agent (on the floor model first), from which the body clears everything on its
        way to the seat (gen-4: the legs through the desk, sliding in from its end); None
        if there is none."""
        over = _over_seat(seated)
        spots = [seated.xy + r * np.array([math.cos(a), math.sin(a)]) for r in SIT_APPROACH
                 for a in np.linspace(0.0, 2 * math.pi, 16, endpoint=False)]
        # on the floor model first; else where the standing body fits between things
        spots.sort(key=lambda xy: (not self.planner.fits(xy),
                                   float(np.linalg.norm(xy - self.pose.xy))))
        for xy in spots:
            start = standing(self.shape, xy, seated.yaw)
            if all(self._clash(blend(start, over, t)) <= REST_CLEAR for t in (0.0, *SIT_WAY)):
                return xy
        return None

    def _sit_clash(self, seated: Pose) -> float:
        """How deep the body passes into things sitting down: seated, bent over the
        seat's front on the way (`_over_seat`) and half way down from there."""
        over = _over_seat(seated)
        return max(self._clash(p) for p in (seated, over, blend(over, seated, 0.5)))

    def _lying_on(self, node: int, bed: Box, axis: int, sign: float, yaw: float) -> Pose:
        """Lying on the back along the bed, the head `PILLOW_IN` from its head end, the
        back on the mattress, the neck bent until the head rests above the pillow."""
        base = lying(self.shape, bed.center[:2], yaw, bed.hi[2])
        head = self.ik.site(base, "j:head")[:2] - base.xy
        end = bed.center[:2].copy()
        end[axis] -= sign * (bed.half[axis] - PILLOW_IN)  # where the head goes
        xy = end - head
        top = self._top_at(node, xy, bed.hi[2] + 0.01) or float(bed.hi[2])
        best: tuple[float, Pose] | None = None
        for neck in LIE_NECKS:
            pose = replace(base, x=float(xy[0]), y=float(xy[1])).with_joints(neck_pitch=neck)
            pose = self._rested(pose, top, ("agent", "torso"))
            depth = self._clash(pose)
            if best is None or depth < best[0] - 1e-3:
                best = (depth, pose)
            if depth <= REST_CLEAR:
                break
        assert best is not None
        return best[1]

    def look(self, target: np.ndarray, point: bool = False) -> None:
        """Turn (when standing) and tilt the head toward a point; point at it if asked."""
        if self.posture == "stand":
            self.turn_to(target)
        d = target - np.r_[self.pose.xy, self.pose.z + 0.6 * self.shape.height]
        yaw = math.atan2(d[1], d[0]) - self.pose.yaw
        yaw = (yaw + math.pi) % (2 * math.pi) - math.pi
        pitch = -math.atan2(d[2], max(np.hypot(d[0], d[1]), 1e-3))
        looking = self.pose.with_joints(neck_yaw=float(np.clip(yaw, -1.2, 1.2)),
                                        neck_pitch=float(np.clip(pitch, -0.7, 0.8)))
        rest = self.pose
        self.move_to(looking, 0.4)
        if point and self.posture == "stand":
            side = self.props.free_side()
            hand = self.ik.hand(looking, side)
            aim = hand + 0.6 * (target - hand) / max(np.linalg.norm(target - hand), 1e-3)
            self.reach(side, aim, 0.5, step=False)
        else:
            self.hold(1.0)
        self.move_to(rest.with_joints(neck_yaw=0.0, neck_pitch=0.0), 0.3)

    def within_reach(self, node_id: int, reach: float) -> bool:
        box = self.props.box_of(node_id)
        d = np.maximum(np.abs(self.pose.xy - box.center[:2]) - box.half[:2], 0.0)
        return bool(np.hypot(*d) <= reach)

    def walk_if_far(self, node_id: int, reach: float = 0.8) -> None:
        """Walk to the step's spot (else near the node) unless already there; standing
        only."""
        if self.posture != "stand":
            return
        if self.spot is not None:
            far = float(np.linalg.norm(self.pose.xy - self.spot)) > AT_SPOT
        else:
            far = not self.within_reach(node_id, reach + 0.3)
        if far:
            self.walk(self.props.box_of(node_id), reach=reach)

    def forward(self, distance: float) -> np.ndarray:
        """The floor point `distance` metres ahead of the agent, (x, y, 0)."""
        return np.r_[self.pose.xy + distance * np.array([math.cos(self.pose.yaw),
                                                        math.sin(self.pose.yaw)]), 0.0]

    # -- the program ----------------------------------------------------------------
    def _spot_for(self, spot: tuple[float, float] | None, rec: StepRecord) -> np.ndarray | None:
        """A step's standing spot, unless what it acts on now lies more than `SPOT_REACH`
        from it: grounding chose its spots where things stood at the start (a keyboard
        since put into a drawer), or beside what holds the object (one end of a long
        counter); nor one with a wall between it and the object (grounding's floor model
        has no walls: a desk against the wall of the next room); render then walks to the
        object itself."""
        if spot is None:
            return None
        xy = np.array(spot, float)
        node = rec.nodes[-1] if rec.nodes else None
        if (node is None or self.props.is_body_part(node) or node in self.props.held.values()
                or node in self.scene.layout.room_floors):
            return xy
        try:
            box = self.props.box_of(node)
        except ExecutionError:
            return xy
        gap = np.maximum(np.abs(xy - box.center[:2]) - box.half[:2], 0.0)
        return xy if float(np.hypot(*gap)) <= SPOT_REACH and not walled(self.grid, xy, box) \
            else None

    def run(self, result: ExecutionResult) -> Timeline:
        """Animate every step of an executed program (it must be executable)."""
        if not result.executable:
            raise ExecutionError(f"cannot render a program that does not execute: "
                                 f"{result.message}")
        if result.trace is None:
            raise ExecutionError("render needs the run's trace (run_program(..., trace=True))")
        self.hold(0.3)
        for i, rec in enumerate(result.trace):
            first = len(self.timeline)
            spot = self.standing.get(i)
            self.step_index = i
            self.spot = self._spot_for(spot, rec)
            self._rest_from = None
            animation_for(rec.step.action.key)(self, rec)
            self.timeline.step_frames.append((first, len(self.timeline) - 1))
            if self._rest_from is not None:
                self.timeline.rests.append((self._rest_from, len(self.timeline) - 1))
            self.timeline.focus.append(rec.nodes[-1] if rec.nodes else -1)
        self.spot = None
        self.hold(0.3)
        last = self.timeline.step_frames[-1] if self.timeline.step_frames else (0, 0)
        if self.timeline.step_frames:
            self.timeline.step_frames[-1] = (last[0], len(self.timeline) - 1)
        return self.timeline


def _over_seat(seated: Pose) -> Pose:
    """On the way to a seated pose: bent over the seat's front edge, `SIT_ABOVE` higher."""
    return replace(seated, z=seated.z + SIT_ABOVE, joints={**seated.joints, "spine_pitch": 0.35})


def standing_pose(shape: AgentShape, xy: np.ndarray) -> Pose:
    """The start pose (a name apart from `Animator`'s `standing` argument)."""
    return standing(shape, xy, 0.0)


# ------------------------------------------------------------------- the registry
Animation = Callable[[Animator, StepRecord], None]
MOTIONS: dict[str, Animation] = {}
"""Motion name (`ActionSpec.motion`) -> animation; every name the catalog uses has one."""


def animation(*names: str) -> Callable[[Animation], Animation]:
    """Register a function as the animation of the given motion names."""

    def register(fn: Animation) -> Animation:
        for name in names:
            MOTIONS[name] = fn
        return fn

    return register


def animation_for(key: str) -> Animation:
    """The animation of the catalog action `key` (through its `motion` column)."""
    return MOTIONS[ACTIONS[key].motion]


def _target(anim: Animator, rec: StepRecord) -> int | None:
    """The node a step acts on; None without one, or when it is a part of the agent's
    body (nothing to walk to or look at: `_at_body` acts there)."""
    if not rec.nodes or anim.props.is_body_part(rec.nodes[0]):
        return None
    return rec.nodes[0]


@animation("idle")
def idle(anim: Animator, rec: StepRecord) -> None:
    """Wearing and anything else without a motion of its own: a short pause."""
    anim.hold(0.8)


@animation("walk", "run")
def walk(anim: Animator, rec: StepRecord) -> None:
    target = _target(anim, rec)
    if target is None:
        return idle(anim, rec)
    anim.walk(anim.props.box_of(target), run=rec.step.action.motion == "run")


@animation("find")
def find(anim: Animator, rec: StepRecord) -> None:
    """Walk to the object, or only look for it when it is already at hand."""
    target = _target(anim, rec)
    if target is not None and anim.within_reach(target, 1.0):
        anim.look(anim.props.box_of(target).center)
    else:
        walk(anim, rec)


@animation("look", "point")
def look(anim: Animator, rec: StepRecord) -> None:
    target = _target(anim, rec)
    if target is None:
        return idle(anim, rec)
    anim.look(anim.props.box_of(target).center, point=rec.step.action.motion == "point")


@animation("sit")
def sit(anim: Animator, rec: StepRecord) -> None:
    target = _target(anim, rec)
    if target is None:
        return idle(anim, rec)
    anim.sit(target)


@animation("lie")
def lie(anim: Animator, rec: StepRecord) -> None:
    target = _target(anim, rec)
    if target is None:
        return rest(anim, rec)
    anim.lie(target)


@animation("rest")
def rest(anim: Animator, rec: StepRecord) -> None:
    """Sleeping: stay as one is."""
    anim.hold(1.0)


@animation("stand_up")
def stand_up(anim: Animator, rec: StepRecord) -> None:
    anim.stand_up()
    anim.hold(0.3)


@animation("use_held")
def use_held(anim: Animator, rec: StepRecord) -> None:
    """Drink or eat: bring the held object to the mouth; read: hold it before the eyes.
    An object not held is touched where it is."""
    target = _target(anim, rec)
    if target is None:
        return idle(anim, rec)
    props = anim.props
    side = props.side_holding(target)
    if side is None:
        _touch(anim, target, {})
        return
    anim.back_off()
    sign = 1.0 if side == "l" else -1.0
    bent = {f"{side}_sh_pitch": -1.0, f"{side}_elbow": -2.3, f"{side}_sh_yaw": 0.0,
            f"{side}_sh_roll": 0.3 * sign}  # forearm folded up before the chest
    anim.reach(side, _face_spot(anim, target, rec.step.action.key), 0.7, step=False,
               nodes=(target,), hold=0.8, grip=props.grip.get(side), seed=bent)


def _face_spot(anim: Animator, obj: int, action: str) -> np.ndarray:
    """Where a held object's centre goes to be drunk or eaten (its rim at the lips) or
    read (before the eyes)."""
    head, fwd, up = anim.ik.head_frame(anim.pose)  # the face's forward and up (lying too)
    if action == "READ":  # held open before the eyes, a little below them
        return head + READ_AT[0] * fwd - READ_AT[1] * up
    head_r = HEAD_RADIUS * anim.shape.height
    half = anim.props.half_of(obj)
    mouth = head + 0.9 * head_r * fwd - 0.45 * head_r * up
    return mouth + (float(max(half[:2])) + 0.01) * fwd - 0.5 * half[2] * up


@animation("let_go")
def let_go(anim: Animator, rec: StepRecord) -> None:
    """Drop a held object: it falls to the floor in front of the agent."""
    obj = _target(anim, rec)
    props = anim.props
    side = None if obj is None else props.side_holding(obj)
    if obj is None or side is None:
        anim.hold(0.5)
        return

    def release() -> None:
        del props.held[side]
        props.grip.pop(side, None)
        props.wrist.pop(side, None)
    done = anim.reach(side, anim.forward(0.4) + np.r_[0, 0, 0.6], 0.5, at_peak=release,
                      back=False, step=False, nodes=(obj,), hold=0.0)
    start = props.mocap[anim.scene.mocap[obj]].copy() if obj in anim.scene.mocap else None
    if start is not None:
        floor = props.half_of(obj)[2]
        fall = max(start[2] - floor, 0.0)
        n = max(1, math.ceil(math.sqrt(2 * fall / GRAVITY) * anim.fps))
        for i in range(1, n + 1):
            t = i / n
            props.move(obj, np.r_[start[:2], start[2] - fall * t * t])
            anim.emit(done.pose)
    anim.move_to(done.rest, 0.4)
    anim.reaching = frozenset()


@animation("reach")
def reach(anim: Animator, rec: StepRecord) -> None:
    """Hands on an object: grab it, put what is held, swing a door, or press and touch."""
    nodes, ch = rec.nodes, rec.changes
    if not nodes:
        return idle(anim, rec)
    if anim.props.is_body_part(nodes[0]):
        return _at_body(anim, nodes[0])
    if len(nodes) > 1:  # put or pour: go to the destination
        anim.walk_if_far(nodes[1])
    elif nodes[0] not in anim.props.held.values():
        anim.walk_if_far(nodes[0])
    if _grab(anim, ch) or _put(anim, ch, nodes):
        return
    states = {n: (before, after) for n, before, after in ch.states}
    if nodes[0] in anim.props.hinge_angle and nodes[0] in states:
        _swing(anim, nodes[0], states[nodes[0]][1])
        return
    _touch(anim, nodes[0], states, nodes)


BODY_POINTS: dict[str, tuple[float, float, float]] = {
    "teeth": (0.9, 0.0, -0.45), "face": (0.9, 0.0, 0.0), "eye": (0.85, 0.0, 0.2),
    "hair": (0.2, 0.0, 1.0), "hand": (0.0, 0.0, 0.0), "arm": (0.0, 0.0, 0.0),
    "leg": (0.0, 0.0, 0.0), "feet": (0.0, 0.0, 0.0),
}
"""A body part's word -> where a hand acts on it: (forward, left, up) from the head's
centre in head radii (hands, arms, legs and feet: see `_body_point`)."""


def _body_point(anim: Animator, node: int, side: str) -> np.ndarray:
    """Where the `side` hand (or what it holds) acts on a part of the agent's body: at
    the mouth for teeth, on the face, on the head's top for hair; before the chest where
    the other hand is for hands and arms; at the knee for legs and feet."""
    cls = anim.graph.node(node).class_name.lower()
    word = next((w for w in BODY_POINTS if w in cls), "hand")
    pose, ik = anim.pose, anim.ik
    if word in ("hand", "arm"):
        other = "l" if side == "r" else "r"
        return ik.hand(pose, other) + np.array([0.0, 0.0, 0.03])
    if word in ("leg", "feet"):
        return ik.site(pose, f"j:{'l' if side == 'l' else 'r'}_knee")
    fwd = np.array([math.cos(pose.yaw), math.sin(pose.yaw), 0.0])
    left = np.array([-fwd[1], fwd[0], 0.0])
    r = HEAD_RADIUS * anim.shape.height
    f, lt, up = BODY_POINTS[word]
    return ik.site(pose, "j:head") + r * (f * fwd + lt * left + up * np.array([0, 0, 1.0]))


def _at_body(anim: Animator, node: int) -> None:
    """A step on a part of the agent's body (wash the teeth, comb the hair): the hand
    holding a tool brings it there (the tool just before the point), else a free hand
    touches it; the agent does not walk. The step's object in the timeline is the tool,
    else the body part (drawn as the agent)."""
    props = anim.props
    side = next(iter(props.held), None) or props.free_side()
    held_out = _hold_out_hand(anim, node, side)
    point = _body_point(anim, node, side)
    tool = props.held.get(side)
    grip = props.grip.get(side) if tool is not None else None
    if tool is not None:
        fwd = np.array([math.cos(anim.pose.yaw), math.sin(anim.pose.yaw), 0.0])
        point = point + (float(max(props.half_of(tool)[:2])) + 0.01) * fwd
    sign = 1.0 if side == "l" else -1.0
    bent = {f"{side}_sh_pitch": -1.0, f"{side}_elbow": -2.0, f"{side}_sh_roll": 0.3 * sign}
    anim.reach(side, point, 0.7, step=False, hold=0.8, grip=grip, seed=bent,
               nodes=(tool, node) if tool is not None else (node,))
    if held_out is not None:  # the other arm back as it was
        anim.move_to(held_out, 0.3)


def _hold_out_hand(anim: Animator, node: int, side: str) -> Pose | None:
    """Before the `side` hand acts on the other hand or arm (wash the hands), that arm,
    if it holds nothing, comes before the belly (`SPARE`'s first: not hanging into a wall
    or counter beside the agent); the pose before it, to return to, or None."""
    cls = anim.graph.node(node).class_name.lower()
    other = "l" if side == "r" else "r"
    word = next((w for w in BODY_POINTS if w in cls), "hand")  # as `_body_point`
    if anim.posture != "stand" or other in anim.props.held or word not in ("hand", "arm"):
        return None
    before = anim.pose
    anim.move_to(spared(before, other, SPARE[0]), 0.4)
    return before


def _touch(anim: Animator, node: int, states, nodes: tuple[int, ...] = ()) -> None:
    """Put a free hand on the object's surface (the point nearest the shoulder); the
    step's state changes (switching on...) happen when it arrives."""
    props = anim.props
    side = props.free_side()
    box = out_of_walls(props.box_of(node), anim.planner.walls)

    def grasp_of(xy: np.ndarray) -> list[Grasp]:  # then a hair off the face (`HOVER`)
        grasps = touch_grasps(box, xy, side=side)
        return grasps + [replace(g, point=g.point - k * HOVER * g.palm)
                         for k in (1, 2) for g in grasps]
    anim.reach(side, grasp_of(anim.pose.xy)[0].point, 0.6,
               at_peak=lambda: props.apply_states(states), nodes=nodes or (node,),
               grasp_of=grasp_of)


def _grab(anim: Animator, ch: Changes) -> bool:
    """Reach for what the step put in a hand, if anything; True if it did. The object is
    taken when the hand touches its surface and rides there (no jump into the palm)."""
    grabbed = {rel: b for a, rel, b in ch.added if rel in (HOLDS_RH, HOLDS_LH)}
    if not grabbed:
        return False
    rel, obj = next(iter(grabbed.items()))
    side = "r" if rel == HOLDS_RH else "l"
    props = anim.props
    box = props.box_of(obj)
    props.taken_from[obj] = (box.center.copy(), frozenset(
        (r, b) for a, r, b in ch.removed if a == obj and r in (ON, INSIDE)))

    def attach() -> None:
        hand, rot = anim.ik.hand_frame(anim.pose, side)
        palm = anim.ik.site(anim.pose, f"{side}_palm")
        gap = box_gap(box, palm)
        center = box.center
        if gap > TOUCH:  # out of the arm's reach after all: it comes to the palm
            center = box.center + palm - np.clip(palm, box.lo, box.hi)
            props.move(obj, center)
        props.held[side] = obj
        props.grip[side] = rot.T @ (center - hand)
        props.wrist[side] = {j: anim.pose.joints.get(j, 0.0) for j in wrist_joints(side)}
        props.taken_with[obj] = Grasp(palm + box.center - center,
                                      rot[:, 1] * (-1.0 if side == "l" else 1.0), -rot[:, 2])
        anim.timeline.attaches.append(Attach(len(anim.timeline) - 1, obj, side, gap))

    clear = anim.ray_test(skip=(obj,))

    def grasp_of(xy: np.ndarray) -> list[Grasp]:
        grasps = palm_grasps(box, side, xy)  # where the hand has room first
        return sorted(grasps, key=lambda g: not hand_room_clear(g, clear))
    anim.reach(side, grasp_of(anim.pose.xy)[0].point, 0.6, at_peak=attach, nodes=(obj,),
               grasp_of=grasp_of)
    return True


def _put(anim: Animator, ch: Changes, nodes: tuple[int, ...]) -> bool:
    """Put down what the step took out of a hand, if anything; True if it did. The hand
    brings the object onto the destination's top (or inside it) and lets go there; put
    back on or in what it was taken from, it goes back where it lay."""
    released = {b for a, rel, b in ch.removed if rel in (HOLDS_RH, HOLDS_LH)}
    if not released:
        return False
    props = anim.props
    obj = next(iter(released))
    side = props.side_holding(obj) or props.free_side()
    dest = [(rel, b) for a, rel, b in ch.added if a == obj and rel in (ON, INSIDE)]
    rel, where = dest[0] if dest else (ON, nodes[-1])
    lay, was = props.taken_from.get(obj, (None, frozenset()))
    back = next(((r, b) for r, b in dest if (r, b) in was
                 and b not in anim.scene.layout.room_floors), None)
    if back is not None and lay is not None:  # put back where it was taken from
        rel, where = back
        final = lay
    else:
        final = props.placement(obj, rel, where, anim.pose.xy)

    def put() -> None:
        carried = props.mocap[anim.scene.mocap[obj]].copy() if obj in anim.scene.mocap \
            else final
        props.held.pop(side, None)
        props.grip.pop(side, None)
        props.wrist.pop(side, None)
        landed = final.copy() if back is not None and lay is not None else \
            props.landing(obj, where, final, carried)
        props.move(obj, landed)
        anim.timeline.releases.append(Attach(len(anim.timeline) - 1, obj, side,
                                             float(np.linalg.norm(landed - carried))))
    took = props.taken_with.get(obj) if back is not None and lay is not None else None
    if took is not None:  # the hand as it took it: where it took it from (a high shelf)
        anim.reach(side, took.point, 0.6, at_peak=put, nodes=(obj, where),
                   grasp_of=lambda xy: [took])
    else:
        anim.reach(side, final, 0.6, at_peak=put, nodes=(obj, where),
                   grip=props.grip.get(side))
    return True


def _swing(anim: Animator, target: int, after: frozenset[str]) -> None:
    """Take the handle and swing a door open or closed, the hand on the handle as long
    as the arm can follow it."""
    props = anim.props
    start = props.hinge_angle[target]
    goal = props.scene.hinge_open[target] if S_OPEN in after else 0.0 \
        if S_CLOSED in after else start
    side = props.free_side()
    local = props.handle_local(target, anim.pose.xy)
    handle = props.handle_world(target, local, start)
    if anim.posture == "stand" and props.swept(target, anim.pose.xy, start, goal, BODY_CLEAR):
        spot = _beside_swing(anim, target, side, handle, start, goal)
        if spot is not None:
            anim.step_to(spot, handle)
    done = anim.reach(side, handle, 0.5, back=False, hold=0.1, acts_on=(target,))
    pose, holding = done.pose, True
    depth = anim.planner.inside(pose)  # how deep the body is in something: no deeper
    n = max(1, round(SWING_SECONDS * anim.fps))
    for i in range(1, n + 1):
        angle = start + (goal - start) * (0.5 - 0.5 * math.cos(math.pi * i / n))
        props.hinge_angle[target] = angle
        if holding:  # the hand follows the handle while the arm reaches it and the
            # body bends into nothing (scene3: the head into the toaster on the counter
            # above a dishwasher's front swinging down)
            follow, err = anim.ik.reach(pose, side, props.handle_world(target, local, angle))
            deep = anim.planner.inside(follow) if err <= HANDLE_SLIP else math.inf
            holding = deep <= max(CLEAR, depth)
            pose, depth = (follow, deep) if holding else (pose, depth)
        anim.emit(pose)
    peak = len(anim.timeline) - 1
    anim.move_to(done.rest, 0.5)
    anim.reaching = frozenset()
    anim.note_interaction((target,), side, done.start, peak)


def _beside_swing(anim: Animator, target: int, side: str, handle: np.ndarray,
                  start: float, goal: float) -> np.ndarray | None:
    """A floor point out of the way of a front swinging from `start` to `goal` from which
    the hand takes its handle without bowing much (the nearest to the agent), if any."""
    planner = anim.planner
    spots = [handle[:2] + r * np.array([math.cos(a), math.sin(a)])
             for r in SWING_STAND for a in np.linspace(0.0, 2 * math.pi, 16, endpoint=False)]
    spots = sorted((xy for xy in spots if planner.fits(xy)
                    and not anim.props.swept(target, xy, start, goal, BODY_CLEAR)),
                   key=lambda xy: float(np.hypot(*(xy - anim.pose.xy))))
    for xy in spots[:MAX_SWING_SPOTS]:
        plan = planner.reach_from(xy, side, handle)
        if plan.gap <= TOUCH and plan.pose.joints.get("spine_pitch", 0.0) <= COMFORT_LEAN:
            return xy
    return None


ANIMATIONS: dict[str, Animation] = {key: MOTIONS[a.motion] for key, a in ACTIONS.items()
                                    if a.motion in MOTIONS}
"""Action key -> its animation, derived from the catalog's `motion` column."""
