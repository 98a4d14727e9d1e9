"""Cameras: 8 per room, high in the corners and on the edges, looking in.

Each seed moves every camera a little, turns it and changes its field of view, so the
same program renders from different viewpoints per seed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from homesim.render.layout import Layout

CAMERA_HEIGHT = 2.15
"""Metres above the floor (ceilings are at 2.5 m)."""
INSET = 0.3
"""Metres from the room's floor edge."""


@dataclass(frozen=True)
class CameraSpec:
    """One fixed camera: world position, unit axes (MuJoCo: looks along -z) and fovy."""

    name: str
    room_id: int
    pos: np.ndarray
    xaxis: np.ndarray  # image right
    yaxis: np.ndarray  # image up
    fovy: float  # degrees
    shot: int = -1  # a close-up of this interaction (`Timeline.interactions` index); -1: none
    step: int = -1  # the program step that interaction belongs to (-1: a room camera)

    @property
    def forward(self) -> np.ndarray:
        return np.cross(self.yaxis, self.xaxis)


def look_at(pos: np.ndarray, target: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Camera x (right) and y (up) axes for a camera at `pos` looking at `target`."""
    f = target - pos
    f = f / np.linalg.norm(f)
    x = np.cross(f, [0.0, 0.0, 1.0])
    if np.linalg.norm(x) < 1e-6:  # looking straight down
        x = np.array([1.0, 0.0, 0.0])
    x = x / np.linalg.norm(x)
    y = np.cross(x, f)
    return x, y


def room_cameras(layout: Layout, seed: int = 0) -> list[CameraSpec]:
    """8 cameras per room (4 corners, 4 edge middles), randomised by `seed`."""
    rng = np.random.default_rng(seed)
    blockers = [b for p in layout.parts
                if p.class_name not in ("floor", "ceiling", "wall", "doorjamb") for b in p.boxes]
    # Every blocker at once (one array op per camera, not one per blocker).
    centers = np.array([b.center for b in blockers]).reshape(-1, 3)
    reach = np.array([b.half + 0.1 for b in blockers]).reshape(-1, 3)
    cams: list[CameraSpec] = []
    for rid in sorted(layout.room_floors):
        box = layout.room_floors[rid]
        lo, hi = box.lo[:2] + INSET, box.hi[:2] - INSET
        mid = (lo + hi) / 2
        spots = [(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1]),
                 (mid[0], lo[1]), (hi[0], mid[1]), (mid[0], hi[1]), (lo[0], mid[1])]
        for k, (x, y) in enumerate(spots):
            jitter = rng.uniform(-0.15, 0.15, size=2)
            pos = np.array([x + jitter[0], y + jitter[1],
                            CAMERA_HEIGHT + rng.uniform(-0.15, 0.1)])
            pos[:2] = np.clip(pos[:2], lo, hi)
            target = np.array([mid[0], mid[1], 0.7]) + np.r_[rng.uniform(-0.6, 0.6, 2),
                                                             rng.uniform(-0.2, 0.3)]
            if np.any(np.all(np.abs(pos - centers) < reach, axis=1)):
                continue  # inside furniture: this camera would see nothing
            xa, ya = look_at(pos, target)
            fovy = float(rng.uniform(55.0, 75.0))
            cams.append(CameraSpec(f"cam{rid}_{k}", rid, pos, xa, ya, fovy))
    return cams


AIM_HEIGHT = 0.15
"""Metres above the agent's pelvis that a room camera aims at (mid-torso)."""
FRAMED_HEIGHT = 3.6
"""Metres: an aimed room camera zooms so that its view spans this much at the agent
(about twice a person's height: the agent and what it is near stay in the picture)."""
MIN_AIMED_FOVY = 35.0
"""Degrees: the narrowest a room camera zooms in (a far agent)."""


def aimed(pos: np.ndarray, agent: np.ndarray, fovy: float) -> tuple[np.ndarray, float]:
    """A room camera at `pos` turned toward the agent (pelvis at `agent`) and zoomed in on
    it: the MuJoCo camera quaternion (w, x, y, z) and field of view (degrees, no wider
    than the camera's own `fovy`)."""
    target = agent + np.array([0.0, 0.0, AIM_HEIGHT])
    xaxis, yaxis = look_at(pos, target)
    rotation = np.column_stack([xaxis, yaxis, np.cross(xaxis, yaxis)])
    quat = _quaternion(rotation)
    distance = float(np.linalg.norm(target - pos))
    zoom = float(np.degrees(2.0 * np.arctan2(FRAMED_HEIGHT / 2.0, distance)))
    return quat, float(np.clip(zoom, min(MIN_AIMED_FOVY, fovy), fovy))


def _quaternion(rotation: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a 3x3 rotation matrix."""
    from homesim.render.gl import mujoco

    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.ascontiguousarray(rotation, dtype=float).ravel())
    return quat
