"""How deep the agent's body passes into the objects around it (a check, not a physics
engine: the animation avoids it, this measures what is left).

Each geom of the agent is sampled by points on its surface (a capsule's ends and sides,
an ellipsoid's axes, a box's corners and faces); each object geom is taken as its
oriented bounding box as posed. A point's depth in a box is how far it lies inside it
(0 outside). `penetrations` gives, per part of the body (an agent body: head, torso,
forearm...), the deepest point inside any object's geom, leaving out what a hand may be
inside: what it holds, and what it acts on at the moment of the effect.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from homesim.render.gl import mujoco
from homesim.render.scene import SceneModel

_GEOM = mujoco.mjtGeom
_SIGNS = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float)
_AXES = np.concatenate([np.eye(3), -np.eye(3)])
REACH = 1.2
"""Metres: object geoms farther than this (bounding sphere) from the agent's root are not
tested (the longest limb reaches less far)."""


@dataclass(frozen=True)
class Penetration:
    """A part of the body inside an object: the agent body's name, the object's node, and
    how deep its deepest point lies (metres)."""

    part: str
    node: int
    depth: float


def _local_points(kind: int, size: np.ndarray) -> np.ndarray:
    """Surface points of a geom in its own frame (MuJoCo's size conventions)."""
    if kind == _GEOM.mjGEOM_SPHERE:
        return _AXES * size[0]
    if kind == _GEOM.mjGEOM_ELLIPSOID:
        return _AXES * size[:3]
    if kind in (_GEOM.mjGEOM_CAPSULE, _GEOM.mjGEOM_CYLINDER):
        r, half = size[0], size[1]
        ring = np.array([[r, 0, 0], [-r, 0, 0], [0, r, 0], [0, -r, 0]], float)
        pts = [ring + np.array([0.0, 0.0, z]) for z in (-half, 0.0, half)]
        if kind == _GEOM.mjGEOM_CAPSULE:
            pts.append(np.array([[0, 0, half + r], [0, 0, -half - r]], float))
        return np.concatenate(pts)
    if kind == _GEOM.mjGEOM_BOX:
        return np.concatenate([_SIGNS * size[:3], _AXES * size[:3]])
    return np.zeros((1, 3))


def _half_extents(kind: int, size: np.ndarray) -> np.ndarray:
    """Half sizes of a geom's bounding box in its own frame."""
    if kind == _GEOM.mjGEOM_SPHERE:
        return np.full(3, size[0])
    if kind == _GEOM.mjGEOM_CAPSULE:
        return np.array([size[0], size[0], size[1] + size[0]])
    if kind == _GEOM.mjGEOM_CYLINDER:
        return np.array([size[0], size[0], size[1]])
    return np.asarray(size[:3], float).copy()


class Clearance:
    """Measures the body against a scene's objects (one per scene)."""

    def __init__(self, scene: SceneModel):
        self.scene = scene
        m = scene.model
        self.agent_geoms = np.array([g for g in range(m.ngeom)
                                     if m.geom(g).name.startswith("agent:")], int)
        self.object_geoms = np.array([g for g in range(m.ngeom)
                                      if int(scene.geom_node[g]) != scene.character_id], int)
        self.points = [_local_points(int(m.geom_type[g]), m.geom_size[g])
                       for g in self.agent_geoms]
        self.halves = np.array([_half_extents(int(m.geom_type[g]), m.geom_size[g])
                                for g in self.object_geoms])
        self.part_of = [m.body(int(m.geom_bodyid[g])).name.removeprefix("a:")
                        for g in self.agent_geoms]
        self.root = m.body("agent").id

    @cached_property
    def hand_parts(self) -> dict[str, frozenset[str]]:
        """Per side, the body parts of the hand (palm, fingers, thumb)."""
        parts = set(self.part_of)
        return {s: frozenset(p for p in parts if p.startswith(f"{s}_") and p[2:] in (
            "hand", "fingers", "fingertips", "thumb")) for s in ("l", "r")}

    def penetrations(self, data: mujoco.MjData, hands_in: Mapping[str, Collection[int]],
                     tolerance: float = 0.0) -> list[Penetration]:
        """Per body part, the deepest point inside an object's geom deeper than
        `tolerance` (metres), as `data` is posed (kinematics done). `hands_in`: per side
        ("l", "r"), the nodes that hand may be inside (what it holds or acts on)."""
        m = self.scene.model
        root = data.xpos[self.root]
        near = self.object_geoms[np.linalg.norm(
            data.geom_xpos[self.object_geoms] - root, axis=1)
            <= REACH + m.geom_rbound[self.object_geoms]]
        if len(near) == 0:
            return []
        index = np.searchsorted(self.object_geoms, near)
        centers, rots = data.geom_xpos[near], data.geom_xmat[near].reshape(-1, 3, 3)
        halves, nodes = self.halves[index], self.scene.geom_node[near]
        worst: dict[str, Penetration] = {}
        for g, pts, part in zip(self.agent_geoms, self.points, self.part_of, strict=True):
            world = data.geom_xpos[g] + pts @ data.geom_xmat[g].reshape(3, 3).T
            # (objects, points, 3): each point in each object's frame
            local = np.einsum("oji,opj->opi", rots, world[None] - centers[:, None])
            depth = np.min(halves[:, None] - np.abs(local), axis=2).max(axis=1)
            allowed = self._allowed(part, hands_in)
            for k in np.flatnonzero(depth > tolerance):
                node = int(nodes[k])
                if node in allowed:
                    continue
                best = worst.get(part)
                if best is None or depth[k] > best.depth:
                    worst[part] = Penetration(part, node, float(depth[k]))
        return sorted(worst.values(), key=lambda p: -p.depth)

    def lowest(self, data: mujoco.MjData, parts: Collection[str]) -> float:
        """The lowest height (m) of the surface points of some body parts, as posed."""
        low = np.inf
        for g, pts, part in zip(self.agent_geoms, self.points, self.part_of, strict=True):
            if part in parts:
                world = data.geom_xpos[g] + pts @ data.geom_xmat[g].reshape(3, 3).T
                low = min(low, float(world[:, 2].min()))
        return low

    def _allowed(self, part: str, hands_in: Mapping[str, Collection[int]]) -> Collection[int]:
        for side, parts in self.hand_parts.items():
            if part in parts:
                return hands_in.get(side, ())
        return ()


__all__ = ["Clearance", "Penetration"]
