"""Camera models and exact optical flow from depth and each geom's motion.

Conventions (OpenCV): pixel (u, v) has its centre at integer coordinates, u right,
v down; the camera frame has x right, y down, z forward; ``world_to_cam`` maps world
points (metres, MuJoCo frame, z up) into it. MuJoCo cameras look along their -z with
y up, so their axes are (x, -y, -z) of ours.
"""

from __future__ import annotations

import math

import numpy as np

NEAR = 1e-3
"""Metres: a point closer to (or behind) the next camera than this has no valid flow."""


def intrinsics(width: int, height: int, fovy_deg: float) -> np.ndarray:
    """3x3 pinhole matrix for a MuJoCo camera (square pixels, centred principal point)."""
    f = 0.5 * height / math.tan(math.radians(fovy_deg) / 2)
    return np.array([[f, 0.0, width / 2 - 0.5], [0.0, f, height / 2 - 0.5], [0.0, 0.0, 1.0]])


def world_to_cam(cam_pos: np.ndarray, cam_xmat: np.ndarray) -> np.ndarray:
    """4x4 OpenCV extrinsics from a MuJoCo camera's position and 3x3 rotation matrix."""
    r_mj = np.asarray(cam_xmat, float).reshape(3, 3)  # columns: camera axes in world
    r_cv = r_mj * np.array([1.0, -1.0, -1.0])  # flip y and z axes (columns)
    out = np.eye(4)
    out[:3, :3] = r_cv.T
    out[:3, 3] = -r_cv.T @ np.asarray(cam_pos, float)
    return out


def project(points: np.ndarray, k: np.ndarray, w2c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pixels (N, 2) and depths (N,) of world points (N, 3)."""
    pc = points @ w2c[:3, :3].T + w2c[:3, 3]
    z = pc[:, 2]
    safe = np.where(np.abs(z) < 1e-9, 1e-9, z)
    uv = pc[:, :2] / safe[:, None] * [k[0, 0], k[1, 1]] + [k[0, 2], k[1, 2]]
    return uv, z


def backproject(depth: np.ndarray, k: np.ndarray, w2c: np.ndarray) -> np.ndarray:
    """World points (H, W, 3) of every pixel of a depth map (metres along the view axis)."""
    h, w = depth.shape
    u, v = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    z = depth.astype(np.float64)
    pc = np.stack([(u - k[0, 2]) * z / k[0, 0], (v - k[1, 2]) * z / k[1, 1], z], axis=-1)
    c2w_r = w2c[:3, :3].T
    return (pc - w2c[:3, 3]) @ c2w_r.T


def optical_flow(depth: np.ndarray, geom_ids: np.ndarray, k0: np.ndarray, w2c0: np.ndarray,
                 k1: np.ndarray, w2c1: np.ndarray, xpos0: np.ndarray, xmat0: np.ndarray,
                 xpos1: np.ndarray, xmat1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Forward flow (H, W, 2) in pixels from frame t to t+1, and its validity (H, W) bool.

    Each pixel's 3D point (from `depth` at t) is carried with the geom it lies on: into
    the geom's frame at t (`xpos0`, `xmat0`: (ngeom, 3), (ngeom, 9)), back out with its
    pose at t+1, then projected with the camera at t+1. Pixels on no geom (id -1) get 0.
    Only pixels that can move are computed: all of them when the camera moves, else
    those on geoms whose pose changed (the rest have exactly zero flow).

    A pixel's flow is valid when it lies on a geom and its point at t+1 is in front of
    the next camera (depth > `NEAR`) and projects inside the image (pixel centres at
    integers: -0.5 <= u < W - 0.5). Occlusion at t+1 is not checked.
    """
    h, w = depth.shape
    flow = np.zeros((h * w, 2), np.float32)
    ids = geom_ids.reshape(-1)
    valid = ids >= 0
    moved = np.any(xpos0 != xpos1, axis=1) | np.any(xmat0 != xmat1, axis=1)
    same_camera = np.array_equal(k0, k1) and np.array_equal(w2c0, w2c1)
    movable = np.concatenate([[False], moved if same_camera else np.ones_like(moved)])
    sel = np.flatnonzero(movable[ids + 1])
    if len(sel) == 0:
        return flow.reshape(h, w, 2), valid.reshape(h, w)
    u = (sel % w).astype(np.float64)
    v = (sel // w).astype(np.float64)
    z = depth.reshape(-1)[sel].astype(np.float64)
    pc = np.stack([(u - k0[0, 2]) * z / k0[0, 0], (v - k0[1, 2]) * z / k0[1, 1], z], axis=-1)
    pts = (pc - w2c0[:3, 3]) @ w2c0[:3, :3]  # camera -> world: R^T (p - t)
    g = ids[sel]
    gm = np.flatnonzero(moved[g])  # of those, the points whose geom moved
    if len(gm):
        gg = g[gm]
        r0 = xmat0.reshape(-1, 3, 3)[gg]
        r1 = xmat1.reshape(-1, 3, 3)[gg]
        local = np.einsum("nji,nj->ni", r0, pts[gm] - xpos0[gg])  # R0^T (p - x0)
        pts[gm] = np.einsum("nij,nj->ni", r1, local) + xpos1[gg]
    uv1, z1 = project(pts, k1, w2c1)
    flow[sel] = (uv1 - np.stack([u, v], axis=-1)).astype(np.float32)
    valid[sel] = (z1 > NEAR) & (uv1[:, 0] >= -0.5) & (uv1[:, 0] < w - 0.5) \
        & (uv1[:, 1] >= -0.5) & (uv1[:, 1] < h - 0.5)
    return flow.reshape(h, w, 2), valid.reshape(h, w)
