"""Close-ups of interactions: one virtual camera per hands-on step, as the paper films.

For each `Interaction` of a timeline (a hand reaching an object, from the start of the
reach to its return), the cameras of the room where it happens are tried, each at its
place, swung around the action and moved part of the way toward it (staying in the
room): it is turned toward the hand and the object, and its field of view is narrowed
until they fill the frame (with a margin). The camera kept is the one that shows the
object (and the hand) best at the moment of the effect: candidates are ranked by rays
cast with `mj_ray` against every geom, and the best few drawn in segmentation at a small
size. A step that switches a screen on or off is judged by the screen (the panel that
lights up), not by the set's back. A step is never filmed from another room: a room
without cameras gets no close-up, nor does a step that no candidate view shows.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace

import numpy as np

from homesim.render.animate import Interaction, Timeline
from homesim.render.cameras import CameraSpec, look_at
from homesim.render.flow import intrinsics, project, world_to_cam
from homesim.render.gl import mujoco
from homesim.render.renderer import Renderer
from homesim.render.scene import SceneModel

MARGIN = 1.3
"""The frame spans this many times the angular extent of hand and object."""
MIN_FOVY = 6.0
MAX_FOVY = 80.0
"""Degrees: the narrowest and widest close-up."""
FRAMED = 5
"""Hand positions sampled along the last quarter of the reach (to the effect) that the
shot must contain (the whole second half made small objects, a faucet, too small)."""
TIGHT_MARGIN = 2.0
"""Those tight views span this many times the extent of the hand and the object."""
DOLLY = (0.0, 0.3, 0.55)
"""Each room camera is also tried moved this share of the way toward the action (at its
height, inside the room, out of furniture)..."""
ORBIT = (0.0, 0.45, -0.45, 0.9, -0.9)
"""... and swung around the action by these angles (radians) first..."""
NEAR_DEST = 0.4
"""Metres: a close-up frames a put's destination this far around the object."""
LOW_HEIGHT = 1.5
"""... and each of those also lowered to this height (metres), to see into furniture."""
DRAWN = 16
"""Candidate views (the best by rays) drawn to choose the close-up."""
PROBE_HEIGHT = 120
"""Pixels: the height of those drawings."""
GOOD_SHARE = 0.02
"""An object covering this share of the drawing is seen well enough; beyond it, the hand
being seen counts more."""
SEEN_SHARE = 0.006
"""A candidate showing the object on less than this share of the drawing does not show
it (a little above the 0.5 % the interactions benchmark counts as covered)."""
MIN_RANGE = 1.1
"""Metres: a camera is not moved closer than this to the action."""
RING = (1.3, 1.9)
"""Metres: besides the room cameras, positions this far around the action are tried
(every 30 degrees)..."""
RING_HEIGHTS = (1.35, 1.9)
"""... at these heights (metres)."""
BODY_MAX = 0.35
"""A close-up where the agent's body covers more than this share of the view is widened
(`WIDER`), and tried after those where it does not: the hand and the object, not the
agent's back, fill a close-up."""
WIDER = (1.5, 2.2)
"""Factors a close-up's field of view is widened by when the body fills it."""
TIGHT = 6
"""Where no drawn view shows the object well (`GOOD_SHARE`), this many of the best that
show it or the hand are also drawn framing only the hand and the object at the effect
(a cellphone put back, a light switch: the reach's way and the destination made them
small)."""


def plan_shots(scene: SceneModel, timeline: Timeline, size: tuple[int, int]
               ) -> list[CameraSpec]:
    """A close-up camera for each interaction whose room has cameras (`CameraSpec.shot`
    is the interaction's index), for images of `size` (width, height).

    Candidates are ranked by rays (object and hand seen at the effect); the best `DRAWN`
    are aimed and drawn in segmentation at a small size, and the one kept shows the
    object well (`GOOD_SHARE` of the view) and the hand, else most of the object. Where
    none of them shows the object (`SEEN_SHARE`) or the hand, the step gets no close-up
    (the room camera films it) rather than a view of whatever stands in front."""
    data = mujoco.MjData(scene.model)
    aspect = size[0] / size[1]
    plans = []
    arms: dict[str, frozenset[int]] = {}  # per hand, `_arm_bodies` (the same each time)
    for k, it in enumerate(timeline.interactions):
        framed = _framed_points(scene, timeline, it, data)
        cams = _positions(scene, it.room, 0.5 * (framed.min(axis=0) + framed.max(axis=0)))
        if not cams:
            continue
        _pose(scene, timeline, it.peak, data)
        seen = _seen_part(scene, timeline, it)
        targets = _targets(scene, it, data, seen)
        if it.side not in arms:
            arms[it.side] = _arm_bodies(scene, it.side)
        ends = np.array([*(c.pos for c in cams), *targets,
                         data.site_xpos[scene.hand_sites[it.side]]])
        with _rays_among(scene, data, ends) as groups:
            scored = sorted(((_score(scene, data, c, it, targets, arms[it.side], seen,
                                     groups), i)
                             for i, c in enumerate(cams)), reverse=True)[:DRAWN]
        tight = _effect_points(scene, timeline, it, data)
        plans.append((it, seen, [(_aim(cams[i], framed, aspect, k, it.step),
                                  _aim(cams[i], tight, aspect, k, it.step, TIGHT_MARGIN))
                                 for _, i in scored]))
    if not plans:
        return []
    probe = (max(2, min(size[0], round(PROBE_HEIGHT * aspect))), min(size[1], PROBE_HEIGHT))
    shots = []
    with Renderer(scene, *probe) as renderer, _spare_camera(scene) as spare:
        for it, seen, aimed in plans:
            _pose(scene, timeline, it.peak, data)
            best = _best_view(spare, renderer, data, it, arms[it.side], seen, aimed)
            if best is not None:
                shots.append(best)
    return shots


def _best_view(spare: _SpareCamera, renderer: Renderer, data: mujoco.MjData,
               it: Interaction, arm: frozenset[int], seen: int | None,
               specs: list[tuple[CameraSpec, CameraSpec]]) -> CameraSpec | None:
    """Of candidate views (drawn small; each framing the reach, and framing only the
    object and the hand at the effect), the one that shows the object and the hand with
    the body covering at most `BODY_MAX` (a view the body fills is widened first; where
    none shows the object well, `GOOD_SHARE`, the best `TIGHT` are tried framed at the
    effect only); None when none shows the object (`SEEN_SHARE`) or the hand."""
    drawn = []
    for n, (spec, _) in enumerate(specs):
        for factor in (1.0, *WIDER):
            if factor > 1.0:
                if spec.fovy >= MAX_FOVY - 1e-6:
                    break
                spec = replace(spec, fovy=float(min(spec.fovy * factor, MAX_FOVY)))
            share, hand, body = spare.view(renderer, data, spec, it, arm, seen)
            drawn.append((_view_score(share, hand, body, spec), -n, share, hand, spec))
            if body <= BODY_MAX:
                break
    if max(d[2] for d in drawn) < GOOD_SHARE:  # small in every view: frame it tighter
        ranked = [-d[1] for d in sorted(drawn, key=lambda d: d[:2], reverse=True)
                  if d[3] or d[2] > 0.0]
        for n in list(dict.fromkeys(ranked))[:TIGHT]:
            spec = specs[n][1]
            share, hand, body = spare.view(renderer, data, spec, it, arm, seen)
            drawn.append((_view_score(share, hand, body, spec), -n, share, hand, spec))
    _, _, share, hand, spec = max(drawn, key=lambda d: d[:2])
    return spec if share >= SEEN_SHARE or hand else None


def _seen_part(scene: SceneModel, timeline: Timeline, it: Interaction) -> int | None:
    """The screen geom of the acted-on object when the step switches it on or off (what a
    close-up must show then), else None (the whole object counts)."""
    node = it.nodes[0]
    screen = scene.screen_geom.get(node)
    if screen is None:
        return None
    switched = (node in timeline.screens[it.start]) != (node in timeline.screens[it.end])
    return screen if switched else None


def _view_score(share: float, hand: bool, body: float, spec: CameraSpec) -> float:
    """A drawn candidate's worth: first whether the object is seen at all (`SEEN_SHARE`:
    a view where it hides behind the hand or furniture loses to any that shows it) and
    the body not filling it (`BODY_MAX`), then the object seen well (up to `GOOD_SHARE`),
    the hand seen, more of the object; a view too wide to frame them (at `MAX_FOVY`)
    counts less."""
    cramped = spec.fovy >= MAX_FOVY - 1e-6
    seen = share >= SEEN_SHARE
    return (2.0 * seen + 1.5 * (body <= BODY_MAX) + min(share / GOOD_SHARE, 1.0) + 0.5 * hand
            + share - 0.5 * cramped)


class _SpareCamera:
    """Room camera 0 lent to draw candidate views (put back afterwards)."""

    def __init__(self, scene: SceneModel):
        self.scene = scene
        m = scene.model
        self.saved = (m.cam_pos[0].copy(), m.cam_quat[0].copy(), float(m.cam_fovy[0]))

    def view(self, renderer: Renderer, data: mujoco.MjData, spec: CameraSpec,
             it: Interaction, arm: frozenset[int], seen: int | None = None
             ) -> tuple[float, bool, float]:
        """Drawn from `spec` at the renderer's (small) size: the share of the view the
        acted-on object covers (only geom `seen` of it, when given), whether the hand
        shows (its pixel is on the arm), and the share the agent's body covers."""
        m = self.scene.model
        mat = np.stack([spec.xaxis, spec.yaxis, np.cross(spec.xaxis, spec.yaxis)], axis=1)
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, mat.reshape(-1))
        m.cam_pos[0], m.cam_quat[0], m.cam_fovy[0] = spec.pos, quat, spec.fovy
        mujoco.mj_camlight(m, data)
        renderer.camera_moved(data, 0)  # cull for the candidate, not for camera 0
        # Only the object's and the agent's pixels count: only what may cover them is drawn.
        ids, _ = renderer.ids_depth(data, 0, nodes=(it.nodes[0], self.scene.character_id))
        nodes = np.where(ids >= 0, self.scene.geom_node[np.maximum(ids, 0)], 0)
        body = float(np.count_nonzero(nodes == self.scene.character_id)) / ids.size
        if seen is None:
            share = float(np.count_nonzero(nodes == it.nodes[0])) / ids.size
        else:
            share = float(np.count_nonzero(ids == seen)) / ids.size
        h, w = ids.shape
        k = intrinsics(w, h, spec.fovy)
        uv, z = project(data.site_xpos[self.scene.hand_sites[it.side]][None], k,
                        world_to_cam(data.cam_xpos[0], data.cam_xmat[0]))
        u, v = np.round(uv[0]).astype(int)
        if z[0] <= 0 or not (0 <= u < w and 0 <= v < h) or ids[v, u] < 0:
            return share, False, body
        g = int(ids[v, u])
        return share, int(m.geom_bodyid[g]) in arm, body

    def restore(self) -> None:
        m = self.scene.model
        m.cam_pos[0], m.cam_quat[0], m.cam_fovy[0] = self.saved


@contextmanager
def _spare_camera(scene: SceneModel) -> Iterator[_SpareCamera]:
    spare = _SpareCamera(scene)
    try:
        yield spare
    finally:
        spare.restore()


def _positions(scene: SceneModel, room: int | None, subject: np.ndarray) -> list[CameraSpec]:
    """The room's cameras, and each swung around `subject` (`ORBIT`) and moved part of
    the way toward it (`DOLLY`), at its height and lowered (`LOW_HEIGHT`), where that
    stays inside the room and out of furniture."""
    floor = scene.layout.room_floors.get(room) if room is not None else None
    blockers = [b for p in scene.layout.parts
                if p.class_name not in ("floor", "ceiling", "wall", "doorjamb")
                for b in p.boxes]
    centers = np.array([b.center for b in blockers]).reshape(-1, 3)
    reach = np.array([b.half for b in blockers]).reshape(-1, 3) + 0.1

    def fits(pos: np.ndarray) -> bool:
        return (floor is not None and float(np.linalg.norm(pos - subject)) >= MIN_RANGE
                and bool(np.all(np.abs(pos[:2] - floor.center[:2]) <= floor.half[:2] - 0.2))
                and not bool(np.any(np.all(np.abs(pos - centers) < reach, axis=1))))

    out = []
    base = None
    for cam in scene.cameras:
        if cam.room_id != room or cam.shot >= 0:
            continue
        base = base or cam
        out.append(cam)
        for angle in ORBIT:
            c, s = math.cos(angle), math.sin(angle)
            rel = cam.pos[:2] - subject[:2]
            turned = np.array([c * rel[0] - s * rel[1], s * rel[0] + c * rel[1]])
            swung = np.r_[subject[:2] + turned, cam.pos[2]]
            for t in DOLLY:
                pos = swung.copy()
                pos[:2] += t * (subject[:2] - pos[:2])
                if (angle or t) and fits(pos):
                    out.append(replace(cam, pos=pos))
                low = np.r_[pos[:2], min(LOW_HEIGHT, pos[2])]
                if fits(low):
                    out.append(replace(cam, pos=low))
    if base is not None:  # a ring around the action, in the room
        for r, a, z in itertools.product(RING, np.arange(12) * math.pi / 6, RING_HEIGHTS):
            pos = np.r_[subject[:2] + r * np.array([math.cos(a), math.sin(a)]), z]
            if fits(pos):
                out.append(replace(base, pos=pos))
    return out


def _pose(scene: SceneModel, timeline: Timeline, frame: int, data: mujoco.MjData) -> None:
    data.qpos[:] = timeline.qpos[frame]
    if scene.model.nmocap:
        data.mocap_pos[:] = timeline.mocap[frame]
    mujoco.mj_kinematics(scene.model, data)


_SIGNS = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])


def geom_corners(scene: SceneModel, data: mujoco.MjData, geom: int) -> np.ndarray:
    """(8, 3) world corners of a geom's bounding box as posed."""
    m = scene.model
    local = m.geom_aabb[geom, :3] + _SIGNS * m.geom_aabb[geom, 3:]
    return data.geom_xpos[geom] + local @ data.geom_xmat[geom].reshape(3, 3).T


def node_corners(scene: SceneModel, data: mujoco.MjData, node: int) -> np.ndarray:
    """World corners (8 per geom) of the bounding boxes of a node's geoms as posed."""
    out = [geom_corners(scene, data, int(g)) for g in np.flatnonzero(scene.geom_node == node)]
    return np.concatenate(out) if out else np.zeros((0, 3))


def _framed_points(scene: SceneModel, timeline: Timeline, it: Interaction,
                   data: mujoco.MjData) -> np.ndarray:
    """What the shot must contain: the hand as it comes to the object (the last quarter of
    its reach); the object at the
    effect, and at the start of the reach too unless it rides in a hand (a carried
    object's place then would only widen the view); of where it goes (a put's table,
    fridge), the part within `NEAR_DEST` of it."""
    site = scene.hand_sites[it.side]
    pts = []
    for f in np.linspace((it.start + 3 * it.peak) / 4, it.peak, FRAMED).round().astype(int):
        _pose(scene, timeline, int(f), data)
        pts.append(data.site_xpos[site].copy()[None])
    for f in (it.start, it.peak):
        _pose(scene, timeline, f, data)
        pts.extend(node_corners(scene, data, n)[None] for n in it.nodes[:1]
                   if f == it.peak or n not in scene.mocap)
    first = node_corners(scene, data, it.nodes[0])  # at the effect
    near = 0.5 * (first.min(axis=0) + first.max(axis=0)) if len(first) else None
    for n in it.nodes[1:]:  # where it goes: the part of it near the object
        corners = node_corners(scene, data, n)
        if near is not None:
            corners = np.clip(corners, near - NEAR_DEST, near + NEAR_DEST)
        pts.append(corners[None])
    return np.concatenate([p.reshape(-1, 3) for p in pts])


def _effect_points(scene: SceneModel, timeline: Timeline, it: Interaction,
                   data: mujoco.MjData) -> np.ndarray:
    """The hand and the acted-on object at the effect: what a tight close-up frames."""
    _pose(scene, timeline, it.peak, data)
    hand = data.site_xpos[scene.hand_sites[it.side]].copy()[None]
    return np.concatenate([hand, node_corners(scene, data, it.nodes[0])])


def _targets(scene: SceneModel, it: Interaction, data: mujoco.MjData,
             seen: int | None = None) -> list[np.ndarray]:
    """Points to see at the effect: the centre of the acted-on object (of its geom `seen`,
    when given) and the corners of its box shrunk to 60 %."""
    corners = (node_corners(scene, data, it.nodes[0]) if seen is None
               else geom_corners(scene, data, seen))
    if len(corners) == 0:
        return []
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    c = 0.5 * (lo + hi)
    return [c, *(c + 0.3 * _SIGNS * (hi - lo))]


def visible(scene: SceneModel, data: mujoco.MjData, eye: np.ndarray, point: np.ndarray,
            nodes: tuple[int, ...], bodies: frozenset[int] = frozenset(),
            geoms: frozenset[int] = frozenset(), groups: np.ndarray | None = None) -> bool:
    """Whether the first geom on the ray from `eye` to `point` belongs to one of `nodes`
    or of `bodies`, or is one of `geoms` (or nothing stands before the point); `groups`:
    the geom groups the ray meets (`_rays_among`; None: every geom)."""
    vec = point - eye
    dist = float(np.linalg.norm(vec))
    if dist < 1e-6:
        return True
    geom = np.zeros(1, np.int32)
    hit = mujoco.mj_ray(scene.model, data, eye, vec / dist, groups, 1, -1, geom)
    if hit < 0 or hit >= dist - 1e-3:
        return True
    g = int(geom[0])
    return bool(int(scene.geom_node[g]) in nodes or int(scene.model.geom_bodyid[g]) in bodies
                or g in geoms)


RAY_HIDDEN = 5
"""The geom group `_rays_among` moves the geoms no ray can meet to."""


@contextmanager
def _rays_among(scene: SceneModel, data: mujoco.MjData, ends: np.ndarray
                ) -> Iterator[np.ndarray | None]:
    """Inside: the geom groups (`mj_ray`'s `geomgroup`) with the geoms whose bounding
    spheres lie wholly outside the box around `ends` left out; the model's groups as
    they were after. `visible` asks about segments between those points: what a ray
    meets before its point lies in the box, so the answers are the same, and a ray tests
    the geoms of a room, not of the home. None (every geom) where the model uses
    `RAY_HIDDEN` itself."""
    m = scene.model
    if np.any(m.geom_group == RAY_HIDDEN):
        yield None
        return
    lo, hi = ends.min(axis=0), ends.max(axis=0)
    radius = m.geom_rbound[:, None]
    out = np.any((data.geom_xpos - radius > hi) | (data.geom_xpos + radius < lo), axis=1)
    out &= m.geom_rbound > 0  # 0: a plane, unbounded
    saved = m.geom_group.copy()
    m.geom_group[out] = RAY_HIDDEN
    try:
        yield np.array([g != RAY_HIDDEN for g in range(6)], np.uint8)
    finally:
        m.geom_group[:] = saved


def _arm_bodies(scene: SceneModel, side: str) -> frozenset[int]:
    """The bodies of a hand and what hangs from it (fingers, thumb): where the hand's
    site must show for the hand to count as seen."""
    m = scene.model
    root = int(m.site_bodyid[scene.hand_sites[side]])
    out = {root}
    for b in range(m.nbody):
        p = b
        while p > 0 and p not in out:
            p = int(m.body_parentid[p])
        if p in out:
            out.add(b)
    return frozenset(out)


def _score(scene: SceneModel, data: mujoco.MjData, cam: CameraSpec, it: Interaction,
           targets: list[np.ndarray], arm: frozenset[int], part: int | None = None,
           groups: np.ndarray | None = None) -> tuple[float, bool]:
    """How well a camera position sees the object (2 per share of points seen; of its
    geom `part` only, when given) and the hand (1 when seen) at the effect, nearer cameras
    winning ties; and whether it sees the hand (its site on `arm`, `_arm_bodies`). A ray
    stopped by where the object goes (a bookshelf's side) does not see it."""
    first = it.nodes[:1]  # what it puts on or in hides it, as anything else would
    owners, geoms = (first, frozenset()) if part is None else ((), frozenset({part}))
    seen = sum(visible(scene, data, cam.pos, p, owners, geoms=geoms, groups=groups)
               for p in targets)
    obj = seen / len(targets) if targets else 0.0
    hand = data.site_xpos[scene.hand_sites[it.side]]
    hand_seen = visible(scene, data, cam.pos, hand, first, arm, groups=groups)
    dist = float(np.linalg.norm(hand - cam.pos))
    return 2.0 * obj + float(hand_seen) - 0.05 * dist, hand_seen


def _aim(cam: CameraSpec, points: np.ndarray, aspect: float, shot: int,
         step: int, margin: float = MARGIN) -> CameraSpec:
    """`cam` turned to the middle of `points` with the narrowest field of view that
    holds them all (times `margin`)."""
    center = 0.5 * (points.min(axis=0) + points.max(axis=0))
    xa, ya = look_at(cam.pos, center)
    fwd = np.cross(ya, xa)
    rel = points - cam.pos
    z = np.maximum(rel @ fwd, 0.05)
    tan_y = float(np.max(np.abs(rel @ ya) / z))
    tan_x = float(np.max(np.abs(rel @ xa) / z)) / aspect
    fovy = math.degrees(2 * math.atan(margin * max(tan_x, tan_y)))
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
