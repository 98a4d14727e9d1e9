"""Static geoms a wall hides from an eye point, whatever the eye looks at.

A room camera stays where it is and only turns (and zooms) toward the agent; from its
place, most of a home's static geoms stand behind walls. MuJoCo draws every geom it is
given, and with llvmpipe a draw costs about the same per geom however little of it shows,
so the renderer leaves these out (`Renderer`), as it leaves out what lies outside the
view: the image is the same, the draw cheaper.

A geom is left out only when the box around it lies wholly in the shadow of one opaque
wall box seen from the eye: every corner of that box is behind the wall along the line
from the eye, by `DEPTH_MARGIN` at least, with the wall shrunk by `SIDE_MARGIN`. The
points behind a convex box along lines from one point form a convex set, so the whole
box is hidden, not only its corners: no pixel of it can show in any direction.
"""

from __future__ import annotations

import numpy as np

from homesim.render.gl import mujoco

OCCLUDERS = ("wall",)
"""Classes whose static, opaque boxes hide what is behind them (walls: they part rooms)."""
DEPTH_MARGIN = 0.01
"""Metres a hidden corner lies behind the wall at least (far above depth precision)."""
SIDE_MARGIN = 0.002
"""Metres the wall is shrunk by on each side for the test (beyond any rasterizer's
rounding of its outline)."""
NEAR_MARGIN = 0.1
"""Metres from the eye the wall must start at least (the near clipping plane is nearer)."""

_SIGNS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)


def occluder_geoms(model: mujoco.MjModel, geom_class: np.ndarray, classes: list[str]
                   ) -> np.ndarray:
    """Ids of the static, opaque box geoms of the classes in `OCCLUDERS`."""
    wanted = np.array([c in OCCLUDERS for c in classes])
    mat_alpha = np.ones(model.ngeom)
    has = model.geom_matid >= 0
    mat_alpha[has] = model.mat_rgba[model.geom_matid[has], 3]
    ok = ((model.geom_bodyid == 0) & (model.geom_type == mujoco.mjtGeom.mjGEOM_BOX)
          & wanted[geom_class] & (model.geom_rgba[:, 3] >= 1.0) & (mat_alpha >= 1.0))
    return np.flatnonzero(ok)


def target_geoms(model: mujoco.MjModel, occluders: np.ndarray) -> np.ndarray:
    """Ids of the static geoms that may be left out: all but planes and the occluders."""
    ok = (model.geom_bodyid == 0) & (model.geom_type != mujoco.mjtGeom.mjGEOM_PLANE)
    ok[occluders] = False
    return np.flatnonzero(ok)


def corners(model: mujoco.MjModel, data: mujoco.MjData, geoms: np.ndarray) -> np.ndarray:
    """(G, 8, 3) world corners of the boxes around geoms (their local bounding boxes, as
    posed)."""
    local = model.geom_aabb[geoms, None, :3] + _SIGNS * model.geom_aabb[geoms, None, 3:]
    rot = data.geom_xmat[geoms].reshape(-1, 3, 3)
    return data.geom_xpos[geoms, None, :] + np.einsum("gij,gkj->gki", rot, local)


BATCH = 8
"""Walls tested together, the widest (seen from the eye) first: what they hide is not
tested again against the next ones."""


def shadowed(model: mujoco.MjModel, data: mujoco.MjData, eye: np.ndarray,
             occluders: np.ndarray, targets: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """The ids of `targets` (their corners: `boxes`, as `corners` gives) hidden from
    `eye` behind one of `occluders` (module docstring)."""
    half = model.geom_size[occluders] - SIDE_MARGIN  # (W, 3)
    axes = data.geom_xmat[occluders].reshape(-1, 3, 3)  # columns: each wall's axes
    pos = data.geom_xpos[occluders]
    eyes = np.einsum("wi,wij->wj", eye - pos, axes)  # the eye in each wall's frame
    rim = np.linalg.norm(model.geom_size[occluders], axis=1)  # bounding sphere radius
    ahead = np.maximum(np.linalg.norm(eyes, axis=1), 1e-9)
    usable = np.flatnonzero(~np.all(np.abs(eyes) < half + NEAR_MARGIN, axis=1))
    usable = usable[np.argsort(-rim[usable] / ahead[usable], kind="stable")]
    to_center = boxes.mean(axis=1) - eye  # a box's centre is hidden when the box is
    reach = np.maximum(np.linalg.norm(to_center, axis=1), 1e-9)
    hidden = np.zeros(len(targets), bool)
    for k in range(0, len(usable), BATCH):
        w = usable[k:k + BATCH]
        open_ = np.flatnonzero(~hidden)
        # A quick necessary test first: the centre beyond the nearest point of the
        # wall's bounding sphere and inside its cone from the eye (unless in the sphere).
        cone = np.sqrt(np.clip(1.0 - (rim[w] / ahead[w]) ** 2, 0.0, 1.0))[:, None]
        toward = (pos[w] - eye) / ahead[w, None]
        near = reach[open_] >= (ahead[w] - rim[w])[:, None]
        aligned = ((toward @ to_center[open_].T >= cone * reach[open_])
                   | (ahead[w] <= rim[w])[:, None])
        pair_w, pair_t = np.nonzero(near & aligned)
        if not len(pair_w):
            continue
        wall, target = w[pair_w], open_[pair_t]
        points = np.einsum("pki,pij->pkj", boxes[target] - pos[wall, None], axes[wall])
        hidden[target[_behind(points, eyes[wall, None], half[wall, None])]] = True
    return targets[hidden]


def _behind(points: np.ndarray, eye: np.ndarray, half: np.ndarray) -> np.ndarray:
    """(P,) whether all 8 points of each pair (its wall's frame, (P, 8, 3)) are behind
    the wall of `half` sizes ((P, 1, 3)) seen from `eye` ((P, 1, 3), the same frame): the
    line from the eye enters the wall `NEAR_MARGIN` from the eye at least and
    `DEPTH_MARGIN` before the point at least."""
    d = points - eye
    # A line parallel to a face: a tiny step keeps it within (or without) that slab for
    # every t, as the exact division by zero would.
    d[np.abs(d) < 1e-12] = 1e-12
    inv = 1.0 / d
    t1, t2 = (-half - eye) * inv, (half - eye) * inv
    lo = np.minimum(t1, t2).max(axis=-1)
    hi = np.maximum(t1, t2).min(axis=-1)
    length = np.sqrt(np.einsum("pki,pki->pk", d, d))
    hit = (lo <= hi) & (lo * length >= NEAR_MARGIN) & ((1.0 - lo) * length >= DEPTH_MARGIN)
    return hit.all(axis=-1)
