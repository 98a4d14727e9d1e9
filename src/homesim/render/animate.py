"""Turn an executed program into a timeline of frames: agent poses and object states.

The symbolic simulator's trace drives everything: which node each step targets, what it
grabs (HOLDS_RH / HOLDS_LH added), where it puts it (ON / INSIDE added when a hold is
removed), what opens or switches on (state changes). Each action has a motion:
walking along an A* path with a gait, reaching with IK, sitting, lying, turning.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from homesim.errors import ExecutionError
from homesim.render.agent import AgentShape
from homesim.render.gl import mujoco
from homesim.render.ik import ArmIK
from homesim.render.layout import SEAT_HEIGHT, Box, lights_on_by_switch, to_mujoco
from homesim.render.navigation import build_grid, plan_path
from homesim.render.poses import (
    Pose,
    blend,
    carrying,
    lying,
    sitting,
    standing,
    walk_cycle,
    write_qpos,
)
from homesim.render.scene import SceneModel
from homesim.sim.execute import ExecutionResult, StepRecord
from homesim.world.graph import EnvironmentGraph
from homesim.world.vocab import (
    HOLDS_LH,
    HOLDS_RH,
    INSIDE,
    ON,
    S_CLOSED,
    S_OFF,
    S_ON,
    S_OPEN,
)

WALK_SPEED = 1.2  # m/s
RUN_SPEED = 2.6  # m/s
STRIDE = 1.3  # metres per gait cycle (two steps)
TURN_SPEED = 3.0  # rad/s
MOVE_KEYS = frozenset({"WALK", "RUN", "FIND"})
REACH_KEYS = frozenset({"GRAB", "SWITCHON", "SWITCHOFF", "OPEN", "CLOSE", "TOUCH", "PUSH",
                        "PULL", "MOVE", "SQUEEZE", "PLUGIN", "PLUGOUT", "TYPE", "WIPE", "WASH",
                        "RINSE", "SCRUB", "CUT", "PUTBACK", "PUTIN", "POUR", "PUTOBJBACK"})


@dataclass
class Timeline:
    """Per-frame state of the scene: arrays indexed by frame, and each step's frames."""

    qpos: list[np.ndarray] = field(default_factory=list)  # (nq,) per frame
    mocap: list[np.ndarray] = field(default_factory=list)  # (nmocap, 3) per frame
    lamps: list[frozenset[int]] = field(default_factory=list)  # lamp node ids lit
    screens: list[frozenset[int]] = field(default_factory=list)  # screen node ids on
    step_frames: list[tuple[int, int]] = field(default_factory=list)  # [start, end]
    focus: list[int] = field(default_factory=list)  # per step: the node it acts on, or -1

    def __len__(self) -> int:
        return len(self.qpos)


class Animator:
    """Builds a `Timeline` for one program on one scene."""

    def __init__(self, scene: SceneModel, graph: EnvironmentGraph, shape: AgentShape,
                 fps: int = 30, seed: int = 0):
        self.scene, self.graph, self.shape, self.fps = scene, graph, shape, fps
        self.rng = np.random.default_rng(seed)
        self.ik = ArmIK(scene)
        self.grid = build_grid(scene.layout)
        m = scene.model
        self.data = mujoco.MjData(m)
        self.qpos = m.qpos0.copy()
        self.mocap = np.array(m.body_pos[m.body_mocapid >= 0])[np.argsort(
            m.body_mocapid[m.body_mocapid >= 0])]
        self.boxes: dict[int, Box] = {}
        for node in graph:
            if (b := to_mujoco(node)) is not None:
                self.boxes[node.id] = b
        self.held: dict[str, int] = {}  # side -> node id
        self.lit = {n for n, p in self._parts() if p.lamp and p.is_on}
        self.screens = {n for n, p in self._parts() if p.screen is not None and p.is_on}
        self.switch_rooms = lights_on_by_switch(graph)
        self.hinge_angle = {n: (scene.hinge_open[n] if p.hinge.is_open else 0.0)
                            for n, p in self._parts() if p.hinge is not None}
        start = scene.layout.start
        cell = self.grid.cell(start)
        if not self.grid.free[cell]:
            start = self.grid.point(self.grid.nearest_free(start))
        self.pose = standing(shape, start, 0.0)
        self.posture = "stand"
        self.timeline = Timeline()

    def _parts(self):
        return ((p.node_id, p) for p in self.scene.layout.parts)

    # -- frame output ---------------------------------------------------------------
    def _lit_lamps(self) -> frozenset[int]:
        on = set(self.lit)
        for n, p in self._parts():
            if p.lamp and p.class_name in ("ceilinglamp", "walllamp"):
                room = self.graph.room_of(n)
                if self.switch_rooms.get(room, True):
                    on.add(n)
        return frozenset(on)

    def emit(self, pose: Pose) -> None:
        """Append one frame with the agent in `pose` and held objects in its hands."""
        self.pose = pose
        for side in self.held:
            pose = carrying(pose, side) if pose.tilt == 0.0 and side not in self._reaching \
                else pose
        write_qpos(self.qpos, pose, self.scene.joint_qpos)
        for n, angle in self.hinge_angle.items():
            self.qpos[self.scene.hinge_qpos[n]] = angle
        if self.held:
            self.data.qpos[:] = self.qpos
            mujoco.mj_kinematics(self.scene.model, self.data)
            for side, n in self.held.items():
                if n in self.scene.mocap:
                    hand = self.data.site_xpos[self.scene.hand_sites[side]]
                    self.mocap[self.scene.mocap[n]] = hand
        tl = self.timeline
        tl.qpos.append(self.qpos.copy())
        tl.mocap.append(self.mocap.copy())
        tl.lamps.append(self._lit_lamps())
        tl.screens.append(frozenset(self.screens))

    _reaching: frozenset[str] = frozenset()

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
            [math.cos(self.pose.yaw), math.sin(self.pose.yaw)])))
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
        self.stand_up()
        path = plan_path(self.grid, self.pose.xy, target, reach)
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
        self.move_to(standing(self.shape, self.pose.xy, self.pose.yaw), 0.25)
        self.turn_to(target.center)

    def reach(self, side: str, point: np.ndarray, seconds: float = 0.6,
              at_peak=None, during=None, back: bool = True) -> None:
        """Reach `point` with a hand, call `at_peak()`, and come back."""
        self.turn_to(point)
        rest = self.pose
        self._reaching = frozenset({side})
        reached, _ = self.ik.reach(rest, side, point)
        self.move_to(reached, seconds, during)
        if at_peak is not None:
            at_peak()
        self.hold(0.15, reached)
        if back:
            self.move_to(rest, seconds * 0.8)
        self._reaching = frozenset()

    def sit(self, seat: Box) -> None:
        self.walk(seat, reach=0.5)
        inset = np.minimum(seat.half[:2], 0.35)
        spot = np.clip(self.pose.xy, seat.lo[:2] + inset, seat.hi[:2] - inset)
        away = self.pose.xy - spot
        yaw = math.atan2(away[1], away[0]) if np.hypot(*away) > 1e-3 else self.pose.yaw + math.pi
        top = seat.hi[2]
        height = SEAT_HEIGHT if top > 0.7 else top
        self.turn_to(self.pose.xy + np.array([math.cos(yaw), math.sin(yaw)]))
        self.move_to(sitting(self.shape, spot, yaw, height), 1.0)
        self.posture = "sit"

    def lie(self, bed: Box) -> None:
        self.walk(bed, reach=0.5)
        along = 0 if bed.half[0] >= bed.half[1] else 1
        yaw = 0.0 if along == 0 else math.pi / 2
        self.move_to(lying(self.shape, bed.center[:2], yaw, bed.hi[2]), 1.4)
        self.posture = "lie"

    # -- the program ----------------------------------------------------------------
    def box_of(self, node_id: int) -> Box:
        if node_id in self.scene.mocap:  # a movable object: where it is now
            c = self.mocap[self.scene.mocap[node_id]]
            return Box(c.copy(), self.boxes[node_id].half)
        if node_id in self.scene.layout.room_floors:  # a room: its middle's free spot
            middle = self.scene.layout.room_floors[node_id].center
            spot = self.grid.point(self.grid.nearest_free(middle[:2]))
            return Box(np.r_[spot, 0.0], np.full(3, 0.05))
        if node_id not in self.boxes:
            raise ExecutionError(f"node {node_id} has no 3D box to walk to")
        return self.boxes[node_id]

    def free_side(self) -> str:
        return "r" if "r" not in self.held else "l"

    def handle_point(self, node_id: int) -> np.ndarray:
        """Where a hand goes to open, close or switch something."""
        box = self.box_of(node_id)
        p = box.center.copy()
        part = self.scene.layout.part(node_id)
        if part is not None and part.hinge is not None:
            h = part.hinge
            p = h.pivot + 1.8 * h.panel.center
            p[2] = min(max(h.pivot[2], 0.5), 1.3)
        if p[2] > 1.7:
            p[2] = 1.7
        near = np.clip(self.pose.xy, box.lo[:2], box.hi[:2])  # the side facing the agent
        p[:2] = 0.5 * p[:2] + 0.5 * near
        return p

    def placement(self, obj: int, rel: str, dest: int) -> np.ndarray:
        """Where an object ends up when put ON or INSIDE a destination."""
        box = self.box_of(dest)
        half = self.boxes[obj].half if obj in self.boxes else np.full(3, 0.05)
        room = np.maximum(box.half[:2] - half[:2] - 0.05, 0.0)
        jitter = self.rng.uniform(-1.0, 1.0, 2) * np.minimum(room, 0.2)
        near = np.clip(self.pose.xy, box.lo[:2] + half[:2], box.hi[:2] - half[:2])
        xy = 0.5 * (box.center[:2] + jitter) + 0.5 * near
        z = box.hi[2] + half[2] if rel == ON else box.lo[2] + 0.05 + half[2]
        return np.r_[xy, z]

    def step(self, rec: StepRecord) -> None:
        key = rec.step.action.key
        nodes = rec.nodes
        ch = rec.changes
        target = nodes[0] if nodes else None
        if key == "FIND" and target is not None and self.within_reach(target, 1.0):
            self.look(self.box_of(target).center)  # already there: just look for it
        elif key in MOVE_KEYS and target is not None:
            self.walk(self.box_of(target), run=key == "RUN")
        elif key in ("TURNTO", "LOOKAT", "WATCH", "POINTAT", "GREET") and target is not None:
            self.look(self.box_of(target).center, point=key in ("POINTAT", "GREET"))
        elif key == "SIT" and target is not None:
            self.sit(self.box_of(target))
        elif key in ("LIE", "SLEEP") and target is not None:
            self.lie(self.box_of(target))
        elif key in ("LIE", "SLEEP"):
            self.hold(1.0)
        elif key in ("STANDUP", "WAKEUP"):
            self.stand_up()
            self.hold(0.3)
        elif key in ("DROP", "RELEASE") and target is not None:
            self.release_held(ch, target, floor=True)
        elif key in ("DRINK", "EAT", "READ") and target is not None:
            self.use_held(target)
        elif key in REACH_KEYS and target is not None:
            self.manipulate(key, nodes, ch)
        else:  # wearing, plugging, anything without a motion of its own
            self.hold(0.8)

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
            side = self.free_side()
            hand = self.ik.hand(looking, side)
            aim = hand + 0.6 * (target - hand) / max(np.linalg.norm(target - hand), 1e-3)
            self.reach(side, aim, 0.5)
        else:
            self.hold(1.0)
        self.move_to(rest.with_joints(neck_yaw=0.0, neck_pitch=0.0), 0.3)

    def use_held(self, obj: int) -> None:
        """Drink, eat or read: bring the object (held, or at hand) up to the face."""
        side = next((s for s, n in self.held.items() if n == obj), self.free_side())
        face = self.ik.hand(self.pose, side)
        head = np.r_[self.pose.xy, self.pose.z + 0.62 * self.shape.height]
        fwd = np.array([math.cos(self.pose.yaw), math.sin(self.pose.yaw), 0.0])
        face = head + 0.25 * fwd - np.array([0, 0, 0.1])
        self.reach(side, face, 0.6)

    def release_held(self, ch, obj: int, floor: bool) -> None:
        side = next((s for s, n in self.held.items() if n == obj), None)
        if side is None:
            self.hold(0.5)
            return
        spot = np.r_[self.pose.xy + 0.4 * np.array([math.cos(self.pose.yaw),
                                                   math.sin(self.pose.yaw)]), 0.0]
        half = self.boxes[obj].half if obj in self.boxes else np.full(3, 0.05)

        def let_go():
            del self.held[side]
            if obj in self.scene.mocap:
                self.mocap[self.scene.mocap[obj]] = spot + np.r_[0, 0, half[2]]
        self.reach(side, spot + np.r_[0, 0, 0.5], 0.5, at_peak=let_go)

    def manipulate(self, key: str, nodes: tuple[int, ...], ch) -> None:
        target = nodes[0]
        grabbed = {rel: b for a, rel, b in ch.added if rel in (HOLDS_RH, HOLDS_LH)}
        released = {b for a, rel, b in ch.removed if rel in (HOLDS_RH, HOLDS_LH)}
        states = {n: (before, after) for n, before, after in ch.states}
        if key in ("PUTBACK", "PUTIN", "POUR") and len(nodes) > 1:
            self.walk_if_far(nodes[1])
        elif target not in self.held.values():
            self.walk_if_far(target)
        if grabbed:
            rel, obj = next(iter(grabbed.items()))
            side = "r" if rel == HOLDS_RH else "l"
            point = self.box_of(obj).center

            def attach():
                self.held[side] = obj
            self.reach(side, point, 0.6, at_peak=attach)
            return
        if released:
            obj = next(iter(released))
            side = next((s for s, n in self.held.items() if n == obj), self.free_side())
            dest = [(rel, b) for a, rel, b in ch.added if a == obj and rel in (ON, INSIDE)]
            rel, where = dest[0] if dest else (ON, nodes[-1])
            final = self.placement(obj, rel, where)

            def put():
                self.held.pop(side, None)
                if obj in self.scene.mocap:
                    self.mocap[self.scene.mocap[obj]] = final
            self.reach(side, final + np.r_[0, 0, 0.05], 0.6, at_peak=put)
            return
        side = self.free_side()
        if target in self.hinge_angle and target in states:
            after = states[target][1]
            start = self.hinge_angle[target]
            goal = self.scene.hinge_open[target] if S_OPEN in after else 0.0 \
                if S_CLOSED in after else start

            def swing(t):
                self.hinge_angle[target] = start + (goal - start) * t
            point = self.handle_point(target)
            self.reach(side, point, 0.4)
            self.reach(side, point, 0.6, during=swing)
            return
        point = self.handle_point(target)
        self.reach(side, point, 0.6, at_peak=lambda: self.apply_states(states))

    def within_reach(self, node_id: int, reach: float) -> bool:
        box = self.box_of(node_id)
        d = np.maximum(np.abs(self.pose.xy - box.center[:2]) - box.half[:2], 0.0)
        return bool(np.hypot(*d) <= reach)

    def walk_if_far(self, node_id: int, reach: float = 0.8) -> None:
        if not self.within_reach(node_id, reach + 0.3) and self.posture == "stand":
            self.walk(self.box_of(node_id), reach=reach)

    def apply_states(self, states: dict[int, tuple[frozenset[str], frozenset[str]]]) -> None:
        for n, (_before, after) in states.items():
            if S_ON in after or S_OFF in after:
                on = S_ON in after
                cls = self.graph.node(n).class_name if n in self.graph.nodes else ""
                if cls == "lightswitch":
                    room = self.graph.room_of(n)
                    self.switch_rooms[room] = on
                for target in (self.lit, self.screens):
                    if on and ((n in self.scene.lamp_mat and target is self.lit)
                               or (n in self.scene.screen_geom and target is self.screens)):
                        target.add(n)
                    elif not on:
                        target.discard(n)

    def run(self, result: ExecutionResult) -> Timeline:
        """Animate every step of an executed program (it must be executable)."""
        if not result.executable:
            raise ExecutionError(f"cannot render a program that does not execute: "
                                 f"{result.message}")
        if result.trace is None:
            raise ExecutionError("render needs the execution trace (execute(..., trace=True))")
        self.hold(0.3)
        for rec in result.trace:
            first = len(self.timeline)
            self.step(rec)
            self.timeline.step_frames.append((first, len(self.timeline) - 1))
            self.timeline.focus.append(rec.nodes[-1] if rec.nodes else -1)
        self.hold(0.3)
        last = self.timeline.step_frames[-1] if self.timeline.step_frames else (0, 0)
        if self.timeline.step_frames:
            self.timeline.step_frames[-1] = (last[0], len(self.timeline) - 1)
        return self.timeline
