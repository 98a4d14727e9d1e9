"""Close-ups of interactions: one virtual camera per hands-on step, as the paper films.

For each `Interaction` of a timeline (a hand reaching an object, from the start of the
reach to its return), the cameras of the room where it happens are tried: each one's
position is kept, it is turned toward the hand and the object, and its field of view is
narrowed until they fill the frame (with a margin). The camera kept is the one that sees
the object and the hand best at the moment of the effect (rays cast with `mj_ray`
against every geom), nearer ones first. A step is never filmed from another room: a room
without cameras gets no close-up.
"""

from __future__ import annotations

import math

import numpy as np

from homesim.render.animate import Interaction, Timeline
from homesim.render.cameras import CameraSpec, look_at
from homesim.render.gl import mujoco
from homesim.render.scene import SceneModel

MARGIN = 1.3
"""The frame spans this many times the angular extent of hand and object."""
MIN_FOVY = 18.0
MAX_FOVY = 80.0
"""Degrees: the narrowest and widest close-up."""
FRAMED = 5
"""Hand positions sampled along the reach (start to peak) that the shot must contain."""


def plan_shots(scene: SceneModel, timeline: Timeline, aspect: float) -> list[CameraSpec]:
    """A close-up camera for each interaction whose room has cameras (`CameraSpec.shot`
    is the interaction's index); `aspect` = width / height of the images."""
    data = mujoco.MjData(scene.model)
    shots = []
    for k, it in enumerate(timeline.interactions):
        cams = [c for c in scene.cameras if c.room_id == it.room and c.shot < 0]
        if not cams:
            continue
        framed = _framed_points(scene, timeline, it, data)
        _pose(scene, timeline, it.peak, data)
        targets = _targets(scene, it, data)
        best = max(cams, key=lambda c: _score(scene, data, c, it, targets))
        shots.append(_aim(best, framed, aspect, k, it.step))
    return shots


def _pose(scene: SceneModel, timeline: Timeline, frame: int, data: mujoco.MjData) -> None:
    data.qpos[:] = timeline.qpos[frame]
    if scene.model.nmocap:
        data.mocap_pos[:] = timeline.mocap[frame]
    mujoco.mj_kinematics(scene.model, data)


def node_corners(scene: SceneModel, data: mujoco.MjData, node: int) -> np.ndarray:
    """World corners (8 per geom) of the bounding boxes of a node's geoms as posed."""
    m = scene.model
    out = []
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    for g in np.flatnonzero(scene.geom_node == node):
        center, half = m.geom_aabb[g, :3], m.geom_aabb[g, 3:]
        local = center + signs * half
        out.append(data.geom_xpos[g] + local @ data.geom_xmat[g].reshape(3, 3).T)
    return np.concatenate(out) if out else np.zeros((0, 3))


def _framed_points(scene: SceneModel, timeline: Timeline, it: Interaction,
                   data: mujoco.MjData) -> np.ndarray:
    """What the shot must contain: the hand along the reach, the objects at its start
    and at the effect."""
    site = scene.hand_sites[it.side]
    pts = []
    for f in np.linspace(it.start, it.peak, FRAMED).round().astype(int):
        _pose(scene, timeline, int(f), data)
        pts.append(data.site_xpos[site].copy()[None])
    for f in (it.start, it.peak):
        _pose(scene, timeline, f, data)
        pts.extend(node_corners(scene, data, n)[None] for n in it.nodes)
    return np.concatenate([p.reshape(-1, 3) for p in pts])


def _targets(scene: SceneModel, it: Interaction, data: mujoco.MjData) -> list[np.ndarray]:
    """Points to see at the effect: the acted-on object's centre and four points around
    it (its box shrunk by half)."""
    corners = node_corners(scene, data, it.nodes[0])
    if len(corners) == 0:
        return []
    c = corners.mean(axis=0)
    return [c] + [c + 0.5 * (p - c) for p in corners[[0, 3, 5, 6]]]


def visible(scene: SceneModel, data: mujoco.MjData, eye: np.ndarray, point: np.ndarray,
            nodes: tuple[int, ...]) -> bool:
    """Whether the first geom on the ray from `eye` to `point` belongs to one of `nodes`
    (or nothing stands before the point)."""
    vec = point - eye
    dist = float(np.linalg.norm(vec))
    if dist < 1e-6:
        return True
    geom = np.zeros(1, np.int32)
    hit = mujoco.mj_ray(scene.model, data, eye, vec / dist, None, 1, -1, geom)
    if hit < 0 or hit >= dist - 1e-3:
        return True
    return int(scene.geom_node[geom[0]]) in nodes


def _score(scene: SceneModel, data: mujoco.MjData, cam: CameraSpec, it: Interaction,
           targets: list[np.ndarray]) -> float:
    """How well a camera position sees the object (2 per share of points seen) and the
    hand (1 when seen) at the effect; nearer cameras win ties."""
    seen = sum(visible(scene, data, cam.pos, p, it.nodes) for p in targets)
    obj = seen / len(targets) if targets else 0.0
    hand = data.site_xpos[scene.hand_sites[it.side]]
    hand_seen = visible(scene, data, cam.pos, hand, (scene.character_id, *it.nodes))
    dist = float(np.linalg.norm(hand - cam.pos))
    return 2.0 * obj + float(hand_seen) - 0.05 * dist


def _aim(cam: CameraSpec, points: np.ndarray, aspect: float, shot: int,
         step: int) -> CameraSpec:
    """`cam` turned to the middle of `points` with the narrowest field of view that
    holds them all (times `MARGIN`)."""
    center = 0.5 * (points.min(axis=0) + points.max(axis=0))
    xa, ya = look_at(cam.pos, center)
    fwd = np.cross(ya, xa)
    rel = points - cam.pos
    z = np.maximum(rel @ fwd, 0.05)
    tan_y = float(np.max(np.abs(rel @ ya) / z))
    tan_x = float(np.max(np.abs(rel @ xa) / z)) / aspect
    fovy = math.degrees(2 * math.atan(MARGIN * max(tan_x, tan_y)))
    fovy = float(np.clip(fovy, MIN_FOVY, MAX_FOVY))
    return CameraSpec(f"shot{shot}", cam.room_id, cam.pos.copy(), xa, ya, fovy, shot, step)


def shot_frames(scene: SceneModel, timeline: Timeline) -> list[int]:
    """Per frame: the camera index of the close-up filming it, or -1."""
    out = [-1] * len(timeline)
    for i, cam in enumerate(scene.cameras):
        if cam.shot >= 0 and cam.shot < len(timeline.interactions):
            it = timeline.interactions[cam.shot]
            out[it.start:it.end + 1] = [i] * (it.end + 1 - it.start)
    return out
