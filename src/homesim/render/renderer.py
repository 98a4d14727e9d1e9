"""`Renderer`: the offscreen GL context, drawing RGB + metric depth and geom ids.

Two draws per frame: one in colour, and one in MuJoCo's segmentation mode from which
`mjr_readPixels` reads both the geom ids and the depth buffer (so depth and ids agree
pixel for pixel). Use it as a context manager so the GL
context is freed: ``with Renderer(scene, 640, 480) as r: ...``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from homesim.errors import HomesimError
from homesim.render.gl import BACKEND, mujoco, thread_context
from homesim.render.scene import SceneModel

HIDDEN_GROUP = 5
"""Geom group of the geoms a camera cannot see (not drawn)."""
MAX_LIGHTS = 7
"""Lights a draw uses besides the headlight: MuJoCo's OpenGL renderer lights with at most
eight. Each camera keeps those of its own room first, then the nearest."""


@dataclass(frozen=True)
class Probe:
    """A small view drawn to choose a camera: the share of it each node asked about
    covers, and the share of it near the camera that none of them covers."""

    shares: list[float]
    near: float


class Renderer:
    """Draws a `SceneModel` from its fixed cameras at one resolution.

    `shadows`: the light of the camera's room casts shadows in colour draws. One more
    pass over the scene per frame: about twice the colour draw's time with OSMesa
    (llvmpipe), little on a GPU; by default on with EGL only."""

    def __init__(self, scene: SceneModel, width: int, height: int,
                 shadows: bool | None = None):
        model = scene.model
        if width > model.vis.global_.offwidth or height > model.vis.global_.offheight:
            raise HomesimError(f"{width}x{height} is larger than the scene was built for "
                               f"({model.vis.global_.offwidth}x{model.vis.global_.offheight})")
        self.scene, self.width, self.height = scene, width, height
        try:
            self._gl = thread_context()
        except Exception as e:
            raise HomesimError(f"cannot create an OpenGL context with MUJOCO_GL={BACKEND} "
                               f"({e}); on Debian install libosmesa6") from None
        self._con = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_100)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, self._con)
        self._con.readDepthMap = mujoco.mjtDepthMap.mjDEPTH_ZEROFAR  # reversed Z
        self._scn = mujoco.MjvScene(model, maxgeom=model.ngeom + 200)
        self._opt = mujoco.MjvOption()
        self._cam = mujoco.MjvCamera()
        self._cam.type = mujoco.mjtCamera.mjCAMERA_FIXED
        self._rect = mujoco.MjrRect(0, 0, width, height)
        self._rgb = np.empty((height, width, 3), np.uint8)
        self._depth = np.empty((height, width), np.float32)
        self._seg4: np.ndarray | None = None
        self._drawn = model.geom_group.copy()  # the geom groups of the last draw
        self._culled_for: dict[int, bytes] = {}  # camera -> the pose it was culled for
        self._moving = np.flatnonzero(model.geom_bodyid != 0)  # agent, doors, held objects
        self._groups = self._cull_groups()
        self._placed: set[bytes] = set()  # camera positions given by `camera_moved`
        self._seen: dict[bytes, np.ndarray] = {}  # camera pose, bodies moved -> still geoms
        self._opaque = _opaque(model)  # may hide what is behind
        self._agent = model.body_rootid == model.body("agent").id  # bodies that always move
        self._node_geoms: dict[int, np.ndarray] = {}  # node id -> its geoms
        self._opt.geomgroup[HIDDEN_GROUP] = 0
        # The light of the room a camera is in casts shadows in its colour draws.
        self._shadow_light = {c: scene.room_light.get(spec.room_id, -1)
                              for c, spec in enumerate(scene.cameras)}
        self._shadow_now: int | None = None
        self._light_masks = {c: self._lights_for(spec.room_id, spec.pos)
                             for c, spec in enumerate(scene.cameras)}
        self.shadows = BACKEND == "egl" if shadows is None else shadows
        extent = model.stat.extent
        self.znear = float(model.vis.map.znear * extent)
        self.zfar = float(model.vis.map.zfar * extent)

    def __enter__(self) -> Renderer:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Free the GL resources and restore the model's geom groups (safe to call twice).
        The thread's GL context stays for the next renderer (`gl.thread_context`)."""
        if getattr(self, "_gl", None) is not None:
            self.scene.model.geom_group[:] = self._groups[-1]
            self._gl.make_current()
            self._con.free()
            self._gl = None

    def probe(self, data: mujoco.MjData, camera_id: int, node_id: int,
              size: tuple[int, int] = (80, 60)) -> float:
        """Share of a small (w, h) view covered by one graph node (cheap visibility)."""
        return self.probe_nodes(data, camera_id, (node_id,), size)[0]

    def probe_nodes(self, data: mujoco.MjData, camera_id: int, node_ids: tuple[int, ...],
                    size: tuple[int, int] = (80, 60)) -> list[float]:
        """Shares of a small (w, h) view covered by each of some graph nodes."""
        return self.probe_view(data, camera_id, node_ids, size).shares

    def probe_view(self, data: mujoco.MjData, camera_id: int, node_ids: tuple[int, ...],
                   size: tuple[int, int] = (80, 60), near: float = 0.0) -> Probe:
        """A small (w, h) view: the share each of some graph nodes covers, and the share
        nearer than `near` metres that none of them covers (what stands in front of the
        camera). Only what may show in those pixels is drawn (`_probe_groups`)."""
        w, h = min(size[0], self.width), min(size[1], self.height)  # inside the buffer
        rect = mujoco.MjrRect(0, 0, w, h)
        self._draw(data, camera_id, segment=True, rect=rect,
                   groups=self._probe_groups(data, camera_id, node_ids, near))
        buf = np.empty((h, w, 3), np.uint8)
        raw = np.empty((h, w), np.float32)
        mujoco.mjr_readPixels(buf, raw, rect, self._con)
        ids = self._decode(buf)
        seen = ids >= 0
        nodes = self.scene.geom_node[ids[seen]]
        close = (self._metric_depth(raw[::-1])[seen] < near) & ~np.isin(nodes, node_ids)
        return Probe([float(np.count_nonzero(nodes == n)) / ids.size for n in node_ids],
                     float(np.count_nonzero(close)) / ids.size)

    def _lights_for(self, room: int | None, pos: np.ndarray) -> np.ndarray | None:
        """Which lights a camera in `room` at `pos` may use (None: all, when few)."""
        m = self.scene.model
        if m.nlight <= MAX_LIGHTS:
            return None
        order = sorted(range(m.nlight), key=lambda i: (
            self.scene.light_room.get(i) != room, float(np.linalg.norm(m.light_pos[i] - pos))))
        mask = np.zeros(m.nlight, bool)
        mask[order[:MAX_LIGHTS]] = True
        return mask

    def _cull_groups(self) -> dict[int, np.ndarray]:
        """Per camera, the geom groups that hide static geoms outside its view (-1: the
        model's own groups). MuJoCo draws every geom it is given; a room camera sees a
        fraction of a home, so this saves most of each draw. Hidden geoms cannot show in
        the image, so colour, depth and segmentation are the same as without culling."""
        m = self.scene.model
        data = mujoco.MjData(m)
        mujoco.mj_kinematics(m, data)
        mujoco.mj_camlight(m, data)  # camera poses
        self._rest = data.xpos.copy(), data.xmat.copy()  # where every body starts
        groups = {-1: m.geom_group.copy()}
        for cam in range(m.ncam):
            groups[cam] = self._cull(data, cam, groups[-1])
            self._culled_for[cam] = self._pose(data, cam)
        return groups

    def _pose(self, data: mujoco.MjData, cam: int) -> bytes:
        """A camera's position, orientation and field of view, as a key."""
        return (data.cam_xpos[cam].tobytes() + data.cam_xmat[cam].tobytes()
                + self.scene.model.cam_fovy[cam:cam + 1].tobytes())

    def _cull(self, data: mujoco.MjData, cam: int, own: np.ndarray) -> np.ndarray:
        """Camera `cam`'s geom groups (posed as in `data`): static geoms whose bounding
        sphere lies outside its view moved to `HIDDEN_GROUP`."""
        m = self.scene.model
        hidden = (m.geom_bodyid == 0) & self._outside(data, cam, slice(None))
        return np.where(hidden, HIDDEN_GROUP, own).astype(np.int32)

    def _outside(self, data: mujoco.MjData, cam: int, geoms: slice | np.ndarray
                 ) -> np.ndarray:
        """Which of `geoms` have their bounding sphere wholly outside camera `cam`'s view."""
        m = self.scene.model
        centers, radii = data.geom_xpos[geoms], m.geom_rbound[geoms]
        axes = data.cam_xmat[cam].reshape(3, 3)  # columns: right, up, backward
        rel = (centers - data.cam_xpos[cam]) @ axes
        depth = -rel[:, 2]
        ty = float(np.tan(np.radians(m.cam_fovy[cam]) / 2))
        tx = ty * self.width / self.height
        # Distance of each bounding sphere's centre outside the four side planes.
        out_x = (np.abs(rel[:, 0]) - tx * depth) / np.sqrt(1 + tx * tx)
        out_y = (np.abs(rel[:, 1]) - ty * depth) / np.sqrt(1 + ty * ty)
        return (out_x > radii) | (out_y > radii) | (depth < -radii)

    def _culled(self, data: mujoco.MjData, cam: int) -> np.ndarray:
        """Camera `cam`'s geom groups with the static geoms outside its view, as posed now,
        hidden (culled again when a room camera was aimed anew)."""
        if self._culled_for.get(cam) != self._pose(data, cam):
            self._recull(data, cam)
        return self._groups.get(cam, self._groups[-1])

    def _frame_groups(self, data: mujoco.MjData, cam: int) -> np.ndarray:
        """The geom groups of a full-size draw from camera `cam` as posed now: static geoms
        outside its view hidden and, without shadows, also the moving ones (the agent,
        doors, objects carried) outside its view and the static geoms that do not show
        from this pose (`_seen_still`; not for a position the caller moved a camera to,
        `camera_moved`: drawn from once, the search would not repay itself). Hidden geoms
        cannot show: the image is the same, the draw cheaper (MuJoCo draws every geom it
        is given). With shadows they could cast one into the view, so they stay."""
        groups = self._culled(data, cam)
        if self.shadows:
            return groups
        groups = groups.copy()
        moving = self._moving
        groups[moving[self._outside(data, cam, moving)]] = HIDDEN_GROUP
        if data.cam_xpos[cam].tobytes() in self._placed:
            return groups
        moved = self._moved(data)
        still = self._opaque & ~moved[self.scene.model.geom_bodyid]
        unseen = still & (groups != HIDDEN_GROUP)
        unseen[self._seen_still(data, cam, groups, still, moved)] = False
        groups[unseen] = HIDDEN_GROUP
        return groups

    def _moved(self, data: mujoco.MjData) -> np.ndarray:
        """(nbody,) which bodies are not where the model puts them (the agent always):
        an object carried or put elsewhere, a door opened."""
        xpos, xmat = self._rest
        moved = np.any(data.xpos != xpos, axis=1) | np.any(data.xmat != xmat, axis=1)
        return moved | self._agent

    def _seen_still(self, data: mujoco.MjData, cam: int, groups: np.ndarray,
                    still: np.ndarray, moved: np.ndarray) -> np.ndarray:
        """The `still` geoms (opaque, of bodies that are where the model puts them) that
        show from camera `cam`'s pose at full size (ids), found by one segmentation draw
        of those alone the first time the pose is drawn from with the same bodies moved
        (a room camera holds its view for a shot). Exact: a still geom that shows in no
        pixel of that draw is behind other still geoms in every pixel, and what moves can
        only cover more; transparent geoms and those of moved bodies are always drawn, so
        what stands behind glass or where a carried object was still shows."""
        key = self._pose(data, cam) + np.packbits(moved).tobytes()
        seen = self._seen.get(key)
        if seen is None:
            self._render(data, cam, True, self._rect,
                         np.where(still, groups, HIDDEN_GROUP).astype(np.int32))
            mujoco.mjr_readPixels(self._rgb, None, self._rect, self._con)
            ids = self._decode(self._rgb)
            seen = np.unique(ids[ids >= 0])
            self._seen[key] = seen
        return seen

    def _probe_groups(self, data: mujoco.MjData, cam: int, node_ids: tuple[int, ...],
                      near: float) -> np.ndarray:
        """The geom groups of a probe (`probe_view`): of the geoms in the view, only the
        nodes' asked about, those that could stand in front of them (their bounding
        spheres meet the cone from the camera to a node's bounding sphere, nearer than its
        far side) and those that may come nearer than `near` along the view axis. Exact
        for what a probe counts: a pixel of a node asked about, or nearer than `near`,
        shows the same geom as with every geom drawn."""
        groups = self._culled(data, cam).copy()
        moving = self._moving
        groups[moving[self._outside(data, cam, moving)]] = HIDDEN_GROUP
        eye = data.cam_xpos[cam]
        rel = data.geom_xpos - eye
        dist = np.linalg.norm(rel, axis=1)
        radii = self.scene.model.geom_rbound
        ahead = -(rel @ data.cam_xmat[cam].reshape(3, 3)[:, 2])  # depth along the view
        keep = ahead - radii < near
        for node in node_ids:
            geoms = self._geoms_of(node)
            if not len(geoms):
                continue
            keep[geoms] = True
            keep |= _in_cone(rel, dist, radii, *_sphere(data.geom_xpos[geoms] - eye,
                                                        radii[geoms]))
        groups[~keep] = HIDDEN_GROUP
        return groups

    def _geoms_of(self, node: int) -> np.ndarray:
        geoms = self._node_geoms.get(node)
        if geoms is None:
            geoms = self._node_geoms[node] = np.flatnonzero(self.scene.geom_node == node)
        return geoms

    def camera_moved(self, data: mujoco.MjData, camera_id: int) -> None:
        """The caller moved a camera (`data` posed with `mj_camlight` after): cull for
        where it is now. Each draw does this by itself when the camera is not where it was
        culled for (a room camera aimed anew); a position given here is taken for one a
        camera visits briefly (walls are not searched for what they hide from there)."""
        self._placed.add(data.cam_xpos[camera_id].tobytes())
        self._recull(data, camera_id)

    def _recull(self, data: mujoco.MjData, camera_id: int) -> None:
        self._groups[camera_id] = self._cull(data, camera_id, self._groups[-1])
        self._culled_for[camera_id] = self._pose(data, camera_id)

    def _draw(self, data: mujoco.MjData, camera_id: int, segment: bool,
              rect: mujoco.MjrRect | None = None, groups: np.ndarray | None = None) -> None:
        """Draw from a camera with the geoms of `groups` (default: `_frame_groups`)."""
        self._gl.make_current()
        # Renderers share the thread's GL context: draw into this one's framebuffer.
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, self._con)
        if groups is None:
            groups = self._frame_groups(data, camera_id)
        self._render(data, camera_id, segment, rect or self._rect, groups)

    def _render(self, data: mujoco.MjData, camera_id: int, segment: bool,
                rect: mujoco.MjrRect, groups: np.ndarray) -> None:
        # Set on every draw (a small copy): another renderer of the same model may have
        # changed the groups since.
        self.scene.model.geom_group[:] = groups
        self._drawn = groups
        self._cam.fixedcamid = camera_id
        m = self.scene.model
        mask = self._light_masks.get(camera_id)
        saved = None if mask is None else m.light_active.copy()
        if saved is not None:  # only the lights this camera uses (see MAX_LIGHTS)
            m.light_active[:] = saved & mask
        mujoco.mjv_updateScene(m, data, self._opt, None, self._cam,
                               mujoco.mjtCatBit.mjCAT_ALL, self._scn)
        if saved is not None:
            m.light_active[:] = saved
        self._scn.flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = segment
        self._scn.flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = segment
        mujoco.mjr_render(rect, self._scn, self._con)

    def _cast_shadows(self, camera_id: int) -> None:
        """Only the light of the camera's room casts shadows (one shadow pass a frame)."""
        light = self._shadow_light.get(camera_id, -1) if self.shadows else -1
        if light == self._shadow_now:
            return
        flags = self.scene.model.light_castshadow
        flags[:] = 0
        if light >= 0:
            flags[light] = 1
        self._shadow_now = light

    def rgb(self, data: mujoco.MjData, camera_id: int) -> np.ndarray:
        """(H, W, 3) uint8 colour image."""
        self._cast_shadows(camera_id)
        self._draw(data, camera_id, segment=False)
        mujoco.mjr_readPixels(self._rgb, None, self._rect, self._con)
        return self._rgb[::-1].copy()  # GL rows start at the bottom

    def ids_depth(self, data: mujoco.MjData, camera_id: int,
                  nodes: tuple[int, ...] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(H, W) int32 geom id per pixel (-1: none) and (H, W) float32 depth in metres
        along the camera's view axis. `nodes`: only the pixels that show these graph nodes
        matter (a view weighed by what it shows of them): only what could stand in front
        of them is drawn (`_probe_groups`), so other pixels may show nothing."""
        groups = None if nodes is None else self._probe_groups(data, camera_id, nodes, 0.0)
        self._draw(data, camera_id, segment=True, groups=groups)
        mujoco.mjr_readPixels(self._rgb, self._depth, self._rect, self._con)
        depth = self._metric_depth(self._depth[::-1])
        return self._decode(self._rgb), depth

    def _decode(self, buf: np.ndarray) -> np.ndarray:
        h, w = buf.shape[:2]
        if self._seg4 is None or self._seg4.shape[:2] != (h, w):
            self._seg4 = np.zeros((h, w, 4), np.uint8)
        self._seg4[..., :3] = buf[::-1]
        seg = self._seg4.view("<u4")[..., 0]  # segid + 1 (0: no geom), little-endian RGB
        lut = self._segid_lut()
        return lut[np.minimum(seg, len(lut) - 1)]

    def _segid_lut(self) -> np.ndarray:
        """segid + 1 -> geom id (-1: none) of the last draw. MuJoCo lists the geoms it
        draws in model order, a geom's segid its place in that list: the table is the
        geoms of the groups drawn, checked against the scene at three places (and read
        from the scene geom by geom should they differ)."""
        scn, n = self._scn, self._scn.ngeom
        drawn = np.flatnonzero(self._opt.geomgroup[np.clip(self._drawn, 0, 5)] != 0)
        lut = np.concatenate([[-1], drawn, [-1]]).astype(np.int32)
        geom = mujoco.mjtObj.mjOBJ_GEOM
        if len(drawn) == n and all(scn.geoms[i].segid == i and scn.geoms[i].objtype == geom
                                   and scn.geoms[i].objid == drawn[i]
                                   for i in {0, n // 2, n - 1} if n):
            return lut
        lut = np.full(n + 2, -1, np.int32)
        for i in range(n):
            g = scn.geoms[i]
            if g.segid >= 0 and g.objtype == geom:
                lut[g.segid + 1] = g.objid
        return lut

    def _metric_depth(self, raw: np.ndarray) -> np.ndarray:
        # MuJoCo draws with reversed Z: the buffer holds about near/z (1 at the near
        # plane, ~0 far away), so float32 keeps its precision; invert the projection.
        n, f = self.znear, self.zfar
        c = 0.5 * (f + n) / (f - n) - 0.5
        d = f * n / (f - n)
        return (np.float32(d) / (raw + np.float32(c))).astype(np.float32, copy=False)


def _opaque(model: mujoco.MjModel) -> np.ndarray:
    """(ngeom,) whether each geom is opaque (its colour's and its material's alpha 1)."""
    alpha = model.geom_rgba[:, 3].copy()
    has = model.geom_matid >= 0
    alpha[has] = np.minimum(alpha[has], model.mat_rgba[model.geom_matid[has], 3])
    return alpha >= 1.0


def _sphere(rel: np.ndarray, radii: np.ndarray) -> tuple[np.ndarray, float]:
    """A sphere around spheres (centres `rel`, `radii`): its centre and radius."""
    center = 0.5 * (rel.min(axis=0) + rel.max(axis=0))
    return center, float(np.max(np.linalg.norm(rel - center, axis=1) + radii))


def _in_cone(rel: np.ndarray, dist: np.ndarray, radii: np.ndarray, center: np.ndarray,
             radius: float) -> np.ndarray:
    """Which spheres (centres `rel` from the eye, `dist` their norms, `radii`) may stand
    between the eye and a point of the sphere (`center` from the eye, `radius`): they meet
    the cone of lines from the eye through it, nearer than its far side."""
    reach = float(np.linalg.norm(center))
    if reach <= radius:  # the eye is inside: every direction
        return dist - radii < reach + radius
    half = np.arcsin(radius / reach)
    inside = dist <= radii
    spread = np.arcsin(np.clip(radii / np.maximum(dist, 1e-12), 0.0, 1.0))
    cos = (rel @ center) / np.maximum(dist * reach, 1e-12)
    angle = np.arccos(np.clip(cos, -1.0, 1.0))
    return (inside | (angle <= half + spread)) & (dist - radii < reach + radius)
