"""The objects of an animated scene: where each is, what the agent holds, what is lit.

`Props` follows the state the animation changes (held objects ride in a hand, doors swing,
lamps and screens light up) and answers geometric questions the motions ask (where a
hand goes to open something, where a put object lands). Positions are MuJoCo frame
(metres, z up).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from homesim.errors import ExecutionError
from homesim.render.ik import Grasp
from homesim.render.layout import Box, Part, lights_on_by_switch, render_kind, to_mujoco
from homesim.render.navigation import Grid
from homesim.render.scene import SceneModel
from homesim.world.graph import EnvironmentGraph
from homesim.world.vocab import BODY_PART, GRABBABLE, ON, S_OFF, S_ON

HANDLE_HEIGHT = 1.0
"""Metres: where a hand takes a door or a tall appliance's front (lower fronts: their top)."""
HANDLE_OUT = 0.02
"""Metres: a handle stands this far out of its panel."""
REACH_HEIGHT = 1.1
POURED_AWAY = -50.0
"""Metres: the height a liquid poured into a held recipient goes to (out of every view)."""
"""Metres: things put inside a fridge or cabinet go on the shelf nearest this height."""


class Props:
    """Object state of one animation (see the module docstring)."""

    def __init__(self, scene: SceneModel, graph: EnvironmentGraph, grid: Grid,
                 rng: np.random.Generator):
        self.scene, self.graph, self.grid, self.rng = scene, graph, grid, rng
        m = scene.model
        self.mocap = np.array(m.body_pos[m.body_mocapid >= 0])[np.argsort(
            m.body_mocapid[m.body_mocapid >= 0])]
        self.boxes: dict[int, Box] = {}
        for node in graph:
            if (b := to_mujoco(node)) is not None:
                self.boxes[node.id] = b
        self.held: dict[str, int] = {}  # side -> node id
        # side -> the held object's centre in the frame of the hand's body (set when it is
        # taken, so it rides where the hand touched it: no jump into the palm)
        self.grip: dict[str, np.ndarray] = {}
        # side -> the wrist's hinge angles the hand took it with, kept while it is carried
        # (the object rides where it was taken relative to the forearm too)
        self.wrist: dict[str, dict[str, float]] = {}
        # node id -> where it lay when last taken, and the (relation, node) it was on or in
        self.taken_from: dict[int, tuple[np.ndarray, frozenset[tuple[str, int]]]] = {}
        # node id -> how the hand took it then (its palm's point and turn: `ik.Grasp`)
        self.taken_with: dict[int, Grasp] = {}
        self.lit = {n for n, p in self.parts() if p.lamp and p.is_on}
        self.screens = {n for n, p in self.parts() if p.screen is not None and p.is_on}
        # Room id -> lit; None stands for "outside every room" (a switch there may be used).
        self.switch_rooms: dict[int | None, bool] = dict(lights_on_by_switch(graph).items())
        self.hinge_angle = {n: (scene.hinge_open[n] if p.hinge.is_open else 0.0)
                            for n, p in self.parts() if p.hinge is not None}
        # Ceiling and wall lamps with their rooms (asked for every frame: found once).
        self.room_lamps = [(n, graph.room_of(n)) for n, p in self.parts()
                           if p.lamp and render_kind(p.class_name) == "room_lamp"]

    def parts(self) -> Iterator[tuple[int, Part]]:
        return ((p.node_id, p) for p in self.scene.layout.parts)

    def lit_lamps(self) -> frozenset[int]:
        """Lamps lit now: those switched on, and ceiling and wall lamps of rooms whose
        light switch is on."""
        on = set(self.lit)
        on.update(n for n, room in self.room_lamps if self.switch_rooms.get(room, True))
        return frozenset(on)

    def box_of(self, node_id: int) -> Box:
        """Where a node is now: a movable object where it was put, a room as a small box
        at its middle's free floor."""
        if node_id in self.scene.mocap:
            c = self.mocap[self.scene.mocap[node_id]]
            return Box(c.copy(), self.boxes[node_id].half)
        if node_id in self.scene.layout.room_floors:
            middle = self.scene.layout.room_floors[node_id].center
            spot = self.grid.point(self.grid.nearest_free(middle[:2]))
            return Box(np.r_[spot, 0.0], np.full(3, 0.05))
        if node_id not in self.boxes:
            raise ExecutionError(f"node {node_id} has no 3D box to walk to")
        return self.boxes[node_id]

    def is_body_part(self, node_id: int) -> bool:
        """Whether a node is a part of the agent's body without a box of its own (teeth,
        hair): the animation acts at the body."""
        if node_id in self.boxes or node_id not in self.graph.nodes:
            return False
        return BODY_PART in self.graph.node(node_id).properties

    def half_of(self, node_id: int) -> np.ndarray:
        return self.boxes[node_id].half if node_id in self.boxes else np.full(3, 0.05)

    def side_holding(self, node_id: int) -> str | None:
        return next((s for s, n in self.held.items() if n == node_id), None)

    def free_side(self) -> str:
        return "r" if "r" not in self.held else "l"

    def handle_local(self, node_id: int, agent_xy: np.ndarray) -> np.ndarray:
        """Where a hand takes a hinged front, in its hinge body's frame (closed): on its
        handle or knob (the model's chrome part) where it has one, else near the free
        edge at about 1 m; on the face toward the agent."""
        part = self.scene.layout.part(node_id)
        if part is None or part.hinge is None:
            raise ExecutionError(f"node {node_id} has no hinged front")
        h = part.hinge
        thin = int(np.argmin(h.panel.half[:2]))
        side = 1.0 if agent_xy[thin] >= h.pivot[thin] + h.panel.center[thin] else -1.0
        handles = [sh for sh in getattr(h, "shapes", ()) if sh.role == "chrome"]
        if handles:
            grip = handles[-1]
            p = np.array(grip.center, float)
            p[thin] += side * float(grip.half[thin])
            return p
        p = 1.8 * h.panel.center  # the panel's centre lies half way to its free edge
        p[thin] = h.panel.center[thin] + side * (h.panel.half[thin] + HANDLE_OUT)
        margin = min(0.08, 0.5 * h.panel.half[2])
        lo = h.panel.center[2] - h.panel.half[2] + margin
        hi = h.panel.center[2] + h.panel.half[2] - margin
        p[2] = float(np.clip(HANDLE_HEIGHT - h.pivot[2], lo, hi))
        return p

    def handle_world(self, node_id: int, local: np.ndarray, angle: float) -> np.ndarray:
        """A point of a hinged front (hinge-frame `local`) with the front swung to `angle`."""
        part = self.scene.layout.part(node_id)
        if part is None or part.hinge is None:
            raise ExecutionError(f"node {node_id} has no hinged front")
        h = part.hinge
        c, s = np.cos(angle), np.sin(angle)
        return h.pivot + np.array([c * local[0] - s * local[1], s * local[0] + c * local[1],
                                   local[2]])

    def swept(self, node_id: int, xy: np.ndarray, start: float, goal: float,
              clearance: float) -> bool:
        """Whether a hinged front swinging from angle `start` to `goal` passes within
        `clearance` metres (horizontally) of the floor point `xy`."""
        part = self.scene.layout.part(node_id)
        if part is None or part.hinge is None:
            return False
        h = part.hinge
        rel = np.asarray(xy, float)[:2] - h.pivot[:2]
        for a in np.linspace(start, goal, 13):
            c, s = np.cos(a), np.sin(a)
            local = np.array([c * rel[0] + s * rel[1], -s * rel[0] + c * rel[1]])
            out = np.maximum(np.abs(local - h.panel.center[:2]) - h.panel.half[:2], 0.0)
            if float(np.linalg.norm(out)) < clearance:
                return True
        return False

    def placement(self, obj: int, rel: str, dest: int, agent_xy: np.ndarray) -> np.ndarray:
        """Where an object ends up when put ON or INSIDE a destination: on its top, or
        inside on the level (floor or shelf) nearest `REACH_HEIGHT` that it fits under."""
        box = self.box_of(dest)
        half = self.half_of(obj)
        room = np.maximum(box.half[:2] - half[:2] - 0.05, 0.0)
        jitter = self.rng.uniform(-1.0, 1.0, 2) * np.minimum(room, 0.2)
        near = np.clip(agent_xy, box.lo[:2] + half[:2], box.hi[:2] - half[:2])
        xy = 0.5 * (box.center[:2] + jitter) + 0.5 * near
        z = box.hi[2] + half[2] if rel == ON else self.level_inside(dest, box, half) + half[2]
        return np.r_[xy, z]

    def level_inside(self, dest: int, box: Box, half: np.ndarray) -> float:
        """The height an object of half size `half` rests at inside `dest`: the top of the
        level (its floor or a shelf, `Part.levels`) nearest `REACH_HEIGHT` with room above
        for it; the box's floor (5 cm up) for a destination without levels."""
        part = self.scene.layout.part(dest)
        levels = part.levels if part is not None and part.levels else [box.lo[2] + 0.05]
        ceilings = [*levels[1:], box.hi[2] - 0.03]
        fits = [z for z, top in zip(levels, ceilings, strict=True) if top - z >= 2 * half[2] + 0.01]
        return min(fits or levels[:1], key=lambda z: abs(z + half[2] - REACH_HEIGHT))

    def landing(self, obj: int, dest: int, final: np.ndarray,
                carried: np.ndarray) -> np.ndarray:
        """Where a put object comes to rest when let go at `carried`: at the height of
        `final` (on the destination's top or its floor inside), across the destination
        where it was carried (kept within the destination's footprint). Put on or in
        something held, it stays where it was let go; poured into it (a liquid: taken
        though not GRABBABLE), it is gone into it and no longer drawn (`POURED_AWAY`)."""
        if dest in self.held.values():
            at = np.asarray(carried, float).copy()
            if GRABBABLE not in self.graph.node(obj).properties:
                at[2] = POURED_AWAY
            return at
        box = self.box_of(dest)
        half = self.half_of(obj)
        lo = box.lo[:2] + np.minimum(half[:2], box.half[:2])
        hi = box.hi[:2] - np.minimum(half[:2], box.half[:2])
        return np.r_[np.clip(carried[:2], lo, hi), final[2]]

    def move(self, obj: int, position: np.ndarray) -> None:
        """Set a movable object's position (others stay where they are)."""
        if obj in self.scene.mocap:
            self.mocap[self.scene.mocap[obj]] = position

    def apply_states(self, states: dict[int, tuple[frozenset[str], frozenset[str]]]) -> None:
        """Light lamps and screens switched on, darken those switched off."""
        for n, (_before, after) in states.items():
            if S_ON in after or S_OFF in after:
                self._switch(n, S_ON in after)

    def _switch(self, n: int, on: bool) -> None:
        cls = self.graph.node(n).class_name if n in self.graph.nodes else ""
        if cls == "lightswitch":
            self.switch_rooms[self.graph.room_of(n)] = on
        for target, shown in ((self.lit, self.scene.lamp_mat),
                              (self.screens, self.scene.screen_geom)):
            if on and n in shown:
                target.add(n)
            elif not on:
                target.discard(n)
