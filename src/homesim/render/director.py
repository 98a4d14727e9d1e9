"""Camera switching: keep a camera while it sees the agent, then cut to the best one.

Visibility comes from segmentation: the share of pixels whose geom belongs to the
agent. Candidates are probed at a small resolution to keep switching cheap.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from homesim.render.layout import room_of_point

if TYPE_CHECKING:
    from homesim.render.scene import SceneModel

KEEP_SCORE = 1.3
"""Least view score (see `recorder.view_score`: capped agent pixels + share of joints in
the image) for the current camera to be kept."""
MAX_RANGE = 7.0
"""Metres: beyond this the current camera is left for a closer one."""
MIN_HOLD = 15
"""Frames a camera is kept at least (no flicker between two views)."""
RETRY = 10
"""Frames to wait before probing again when no camera was better than the current one."""


@dataclass
class Director:
    """Chooses a camera per frame; `probe(camera_index)` scores how well it shows the
    agent (0: not at all)."""

    scene: SceneModel
    current: int = -1
    held: int = 0
    since_probe: int = 0

    def candidates(self, agent_xy: np.ndarray) -> list[int]:
        """The room cameras of the agent's room (all room cameras if it has none)."""
        room = room_of_point(self.scene.layout, agent_xy)
        cams = [i for i in self.room_cameras() if self.scene.cameras[i].room_id == room]
        return cams or self.room_cameras()

    def room_cameras(self) -> list[int]:
        """Indices of the fixed cameras (not close-ups of interactions)."""
        return [i for i, c in enumerate(self.scene.cameras) if c.shot < 0]

    def force(self, camera: int) -> int:
        """Film this frame with a given camera (a close-up of an interaction)."""
        if camera != self.current:
            self.current, self.held = camera, 0
        self.since_probe = 0
        return camera

    def choose(self, agent_pos: np.ndarray, score_now: float | None, probe) -> int:
        """The camera for this frame. `score_now`: the current camera's last view score."""
        self.held += 1
        self.since_probe += 1
        on_shot = self.current >= 0 and self.scene.cameras[self.current].shot >= 0
        if self.current >= 0 and score_now is not None and not on_shot:
            cam = self.scene.cameras[self.current]
            in_range = np.linalg.norm(cam.pos - agent_pos) <= MAX_RANGE
            if score_now > 0 and (self.held < MIN_HOLD or self.since_probe < RETRY
                                  or (score_now >= KEEP_SCORE and in_range)):
                return self.current
        self.since_probe = 0
        best, best_share = self._best(self.candidates(agent_pos[:2]), agent_pos, probe)
        if best_share <= 0.0:  # e.g. in a doorway: look from every room
            best, best_share = self._best(self.room_cameras(), agent_pos, probe)
        if best != self.current:
            self.current, self.held = best, 0
        return self.current

    def _best(self, cams, agent_pos: np.ndarray, probe) -> tuple[int, float]:
        best, best_score, best_share = 0, -np.inf, 0.0
        for i in cams:
            share = probe(i)
            dist = float(np.linalg.norm(self.scene.cameras[i].pos - agent_pos))
            score = share - 0.001 * dist  # prefer the closer of two equal views
            if score > best_score:
                best, best_score, best_share = i, score, share
        return best, best_share
