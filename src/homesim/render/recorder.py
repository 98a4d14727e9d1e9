"""Play a `Timeline` through the renderer and produce each frame's ground truth.

For every frame: apply the scene state (agent qpos, objects, hinges, lamps, screens),
let the `Director` pick a camera, draw colour and ids+depth, map geoms to graph ids
and classes, and compute the exact flow to the next frame. Frames are yielded as
`FrameTruth` in order; writing them is the writer's job.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from homesim.render.animate import Timeline
from homesim.render.cameras import aimed
from homesim.render.director import Director
from homesim.render.flow import intrinsics, optical_flow, project, world_to_cam
from homesim.render.gl import mujoco
from homesim.render.renderer import Renderer
from homesim.render.scene import BACKGROUND, SceneModel
from homesim.render.shots import shot_frames


@dataclass
class FrameTruth:
    """Everything recorded for one frame (arrays are H x W unless noted)."""

    index: int
    camera: int  # index into scene.cameras
    rgb: np.ndarray  # (H, W, 3) uint8
    depth: np.ndarray  # float32 metres along the view axis; 0 where nothing is seen
    class_seg: np.ndarray  # uint16 class index (0 background)
    instance_seg: np.ndarray  # int32 graph node id (0 background)
    flow: np.ndarray | None  # (H, W, 2) float32 pixels to the next frame (u, v)
    flow_valid: np.ndarray | None  # bool: the point is seen in front of the next camera
    intrinsics: np.ndarray  # (3, 3)
    world_to_cam: np.ndarray  # (4, 4) OpenCV convention
    joints3d: np.ndarray  # (J, 3) world metres
    joints2d: np.ndarray  # (J, 2) pixels
    joints_visible: np.ndarray  # (J,) bool: in the image and not hidden
    cut: bool  # True when the camera changes between this frame and the next


VIEW_CAP = 0.04
"""Agent share of the image at which a view scores best; larger shares (close-ups that
cut the agent off) score less, down to 0 at VIEW_CAP + 0.2."""


def _size_score(share: float) -> float:
    if share <= VIEW_CAP:
        return share / VIEW_CAP
    return max(0.0, 1.0 - (share - VIEW_CAP) / 0.2)


FOCUS_BONUS = 0.5
"""Score added when the object the step acts on is in view too."""
NEAR = 1.0
"""Metres: what stands nearer than this to a room camera (a wall edge or a door beside
it), other than the agent and the object acted on, blocks its view..."""
BLOCK_PENALTY = 2.0
"""... and costs this much score per share of the image it covers."""


def camera_intrinsics(scene: SceneModel, cam: int, width: int, height: int) -> np.ndarray:
    """The pinhole matrix of a camera as it is now (a room camera zooms when aimed)."""
    return intrinsics(width, height, float(scene.model.cam_fovy[cam]))


def view_score(renderer: Renderer, data: mujoco.MjData, scene: SceneModel, cam: int,
               focus: int = -1) -> float:
    """How well a camera shows the agent (visible pixels, capped; joints in frame) and
    the object it acts on (`focus`, a node id; -1 for none), less what blocks the view
    near the camera (`BLOCK_PENALTY`)."""
    probe = renderer.probe_view(data, cam, (scene.character_id, focus), near=NEAR)
    share, seen = probe.shares
    if share <= 0.0:
        return 0.0
    w2c = world_to_cam(data.cam_xpos[cam], data.cam_xmat[cam])
    w, h = renderer.width, renderer.height
    uv, z = project(data.site_xpos[scene.joint_sites], camera_intrinsics(scene, cam, w, h), w2c)
    inside = (z > 0) & (uv[:, 0] >= 0) & (uv[:, 0] < w) & (uv[:, 1] >= 0) & (uv[:, 1] < h)
    return _score(share, float(inside.mean()), seen > 0, probe.near)


def _score(share: float, inside: float, focus_seen: bool, near: float) -> float:
    """A view's score from the agent's share of it, the share of its joints inside it,
    whether the step's object shows, and the share of it near the camera."""
    return (_size_score(share) + inside + (FOCUS_BONUS if focus_seen else 0.0)
            - BLOCK_PENALTY * near)


def aimed_score(state: SceneState, renderer: Renderer, scene: SceneModel, cam: int,
                focus: int = -1) -> float:
    """`view_score` of a camera once aimed at the agent (a probed camera is aimed: the one
    chosen films from there)."""
    state.aim(cam)
    return view_score(renderer, state.data, scene, cam, focus)


def focus_per_frame(timeline: Timeline) -> list[int]:
    """The node each frame's step acts on (-1 before the first and for none)."""
    out = [-1] * len(timeline)
    for (a, b), node in zip(timeline.step_frames, timeline.focus, strict=False):
        out[a:b + 1] = [node] * (b + 1 - a)
    return out


class SceneState:
    """Applies one frame of a timeline to the model and data; with `aim_cameras`, a room
    camera is turned toward the agent and zoomed in on it whenever it is probed or
    chosen (`aim`), and holds that view until the next time (`cameras.aimed`)."""

    def __init__(self, scene: SceneModel, timeline: Timeline, aim_cameras: bool = True):
        self.scene, self.tl = scene, timeline
        self._aimable = {i: (c.pos, c.fovy) for i, c in enumerate(scene.cameras)
                         if aim_cameras and c.shot < 0}
        self._agent = scene.model.body("agent").id
        self.data = mujoco.MjData(scene.model)
        m = scene.model
        self._emission = {n: 1.0 for n in scene.lamp_mat}
        self._light_ids = dict(scene.lamp_light)
        self._mocap = m.nmocap > 0
        del m

    def aim(self, cam: int) -> None:
        """Turn room camera `cam` toward the agent as posed now and zoom in on it (a no-op
        for close-ups and without `aim_cameras`)."""
        if cam not in self._aimable:
            return
        m, d = self.scene.model, self.data
        pos, fovy = self._aimable[cam]
        m.cam_quat[cam], m.cam_fovy[cam] = aimed(pos, d.xpos[self._agent], fovy)
        mujoco.mj_camlight(m, d)

    def apply(self, i: int) -> mujoco.MjData:
        m, d, tl = self.scene.model, self.data, self.tl
        d.qpos[:] = tl.qpos[i]
        if self._mocap:
            d.mocap_pos[:] = tl.mocap[i]
        lit = tl.lamps[i]
        lights: dict[int, bool] = {}  # a room's light is on when any of its lamps is
        for n, mat in self.scene.lamp_mat.items():
            on = n in lit
            m.mat_emission[mat] = 0.9 if on else 0.0
            lid = self._light_ids.get(n, -1)
            if lid >= 0:
                lights[lid] = lights.get(lid, False) or on
        for lid, on in lights.items():
            m.light_active[lid] = on
        screen_off, screen_on = self.scene.screen_mats
        for n, g in self.scene.screen_geom.items():
            m.geom_matid[g] = screen_on if n in tl.screens[i] else screen_off
        mujoco.mj_kinematics(m, d)
        mujoco.mj_camlight(m, d)
        return d


def record(scene: SceneModel, timeline: Timeline, renderer: Renderer,
           fixed_camera: int | None = None, flow: bool = True) -> Iterator[FrameTruth]:
    """Yield each frame's ground truth, in order; without `flow`, `FrameTruth.flow` and
    `flow_valid` are None (not computed)."""
    state = SceneState(scene, timeline, aim_cameras=fixed_camera is None)
    director = Director(scene)
    char = scene.character_id
    body = scene.model.body("agent").id
    w, h = renderer.width, renderer.height
    focus = focus_per_frame(timeline)
    shots = shot_frames(scene, timeline)
    node_lut = np.concatenate([[BACKGROUND], scene.geom_node]).astype(np.int32)
    class_lut = np.concatenate([[0], scene.geom_class]).astype(np.uint16)
    visible = None
    pending = None  # frame t waiting for t+1's poses to finish its flow
    for i in range(len(timeline)):
        d = state.apply(i)
        agent = d.xpos[body].copy()
        if fixed_camera is not None:
            cam = fixed_camera
        elif shots[i] >= 0:  # a close-up of the interaction under way
            cam = director.force(shots[i])
        else:
            cam = director.choose(agent, visible, lambda c, d=d, f=focus[i]: aimed_score(
                state, renderer, scene, c, f))
        k = camera_intrinsics(scene, cam, w, h)
        rgb = renderer.rgb(d, cam)
        ids, depth = renderer.ids_depth(d, cam)
        seen = ids >= 0
        instance = node_lut[ids + 1]  # one gather per map: id -1 (nothing) -> slot 0
        share = float(np.count_nonzero(instance == char)) / instance.size
        w2c = world_to_cam(d.cam_xpos[cam], d.cam_xmat[cam])
        poses = (d.geom_xpos.copy(), d.geom_xmat.copy()) if flow else None
        if pending is not None:
            yield _finish(pending, cam, k, w2c, poses)
        joints = d.site_xpos[scene.joint_sites].copy()
        uv, z = project(joints, k, w2c)
        iu = np.clip(np.round(uv).astype(int), 0, [w - 1, h - 1])
        inside = (uv[:, 0] >= -0.5) & (uv[:, 0] < w - 0.5) & (uv[:, 1] >= -0.5) \
            & (uv[:, 1] < h - 0.5) & (z > 0)
        unhidden = z <= depth[iu[:, 1], iu[:, 0]] + 0.15  # joints sit inside the limbs
        visible = 0.0 if share == 0 else _frame_score(share, inside, instance, depth, seen,
                                                      char, focus[i])
        depth[~seen] = 0.0
        truth = FrameTruth(
            i, cam, rgb, depth, class_lut[ids + 1], instance, None, None, k, w2c, joints,
            uv, inside & unhidden, False)
        pending = (truth, ids, poses)
    if pending is not None:
        truth = pending[0]
        last = _finish(pending, truth.camera, truth.intrinsics, truth.world_to_cam, pending[2])
        if last.flow_valid is not None:
            last.flow_valid[:] = False  # no next frame to flow to
        yield last


def _frame_score(share: float, inside: np.ndarray, instance: np.ndarray, depth: np.ndarray,
                 seen: np.ndarray, char: int, focus: int) -> float:
    """`view_score` of the frame just drawn, from its full-size maps."""
    shown = bool(np.any(instance == focus)) if focus >= 0 else False
    near = seen & (depth < NEAR) & (instance != char) & (instance != focus)
    return _score(share, float(inside.mean()), shown, float(np.count_nonzero(near)) / near.size)


def _finish(pending, cam1: int, k1: np.ndarray, w2c1: np.ndarray, poses1) -> FrameTruth:
    """Complete frame t with the flow to t+1 (camera `cam1`, geom poses `poses1`; None:
    no flow) and whether the view cuts after it."""
    truth, ids, poses0 = pending
    truth.cut = is_cut(truth.camera, truth.intrinsics, truth.world_to_cam, cam1, k1, w2c1)
    if poses0 is not None and poses1 is not None:
        truth.flow, truth.flow_valid = optical_flow(
            truth.depth, ids, truth.intrinsics, truth.world_to_cam, k1, w2c1, *poses0,
            *poses1)
        if truth.cut:  # across a cut (or a camera aimed anew) the flow is no correspondence
            truth.flow_valid[:] = False
    return truth


def is_cut(cam0: int, k0: np.ndarray, w2c0: np.ndarray,
           cam1: int, k1: np.ndarray, w2c1: np.ndarray) -> bool:
    """Whether the view changes between two frames: another camera, or the same one aimed
    or zoomed anew."""
    return cam0 != cam1 or not (np.array_equal(k0, k1) and np.array_equal(w2c0, w2c1))


def still_frames(scene: SceneModel, timeline: Timeline, renderer: Renderer,
                 frames: list[int]) -> list[tuple[int, np.ndarray]]:
    """RGB of chosen frames only, each from the camera that sees the agent best."""
    return list(iter_still_frames(scene, timeline, renderer, frames))


def iter_still_frames(scene: SceneModel, timeline: Timeline, renderer: Renderer,
                      frames: list[int]) -> Iterator[tuple[int, np.ndarray]]:
    """`still_frames` one at a time, so a caller can store each and drop it."""
    state = SceneState(scene, timeline)
    body = scene.model.body("agent").id
    focus = focus_per_frame(timeline)
    shots = shot_frames(scene, timeline)
    for i in frames:
        d = state.apply(i)
        director = Director(scene)  # a fresh choice per frame: no continuity needed
        cam = shots[i] if shots[i] >= 0 else director.choose(
            d.xpos[body].copy(), None,
            lambda c, f=focus[i]: aimed_score(state, renderer, scene, c, f))
        yield i, renderer.rgb(d, cam)


def shot_camera(scene: SceneModel, timeline: Timeline, frame: int) -> int | None:
    """The close-up camera that films `frame` (an interaction under way), if any."""
    cam = shot_frames(scene, timeline)[frame]
    return None if cam < 0 else cam
