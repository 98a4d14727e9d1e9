"""What the hands touch: the classes of a class map round the agent's wrists.

Why: a step is an action and its objects, and the object a step acts on is the one at the
hand. A map's pooled feature tells a clip model what the frame holds, not what is held;
the class shares in a small window round each wrist do. On the development plan's
validation clips (docs/learn.md, "Perceiving the body") they raise steps accuracy from 1.7
to 3.4 % over the predicted maps and joints, and from 7.0 to 11.5 % over the ground-truth
ones.

`hand_context` reads a class map (true or predicted) and joints (true or predicted, as
`pose.pose_descriptor` takes them) and gives, per frame, each class's share of the cells
in both wrists' windows, the agent's own class left out (the hand itself).
"""

from __future__ import annotations

import numpy as np

from homesim.render.agent import JOINTS

WRISTS = (JOINTS.index("l_wrist"), JOINTS.index("r_wrist"))
"""The joints whose surroundings `hand_context` reads (indices into the store's joints)."""
HAND_RADIUS = 2
"""Cells each side of a wrist's cell: a 5 x 5 window of the half-size map (10 x 10 frame
pixels at 64 x 48, about half the body's height there)."""


def hand_context(maps: np.ndarray, joints: np.ndarray, n_classes: int,
                 own_class: int | None = None, radius: int = HAND_RADIUS,
                 chunk: int = 50000) -> np.ndarray:
    """(N, n_classes) float32: each class's share of the map cells within `radius` of the
    wrists of `joints` ((N, J, 3+): x, y as shares of the frame) in `maps` ((N, H, W)
    class indices); `own_class` (the agent) counts as nothing. Windows at the map's edge
    repeat its edge cells."""
    n, h, w = maps.shape
    dy, dx = (d.ravel() for d in np.mgrid[-radius:radius + 1, -radius:radius + 1])
    out = np.zeros((n, n_classes), np.float32)
    for start in range(0, n, chunk):
        cells = np.asarray(maps[start:start + chunk])
        shares = np.asarray(joints[start:start + chunk, :, :2], np.float32)
        frames = np.arange(len(cells))[:, None]
        for wrist in WRISTS:
            col = np.clip((shares[:, wrist, 0] * w).astype(int), 0, w - 1)
            row = np.clip((shares[:, wrist, 1] * h).astype(int), 0, h - 1)
            ys = np.clip(row[:, None] + dy, 0, h - 1)
            xs = np.clip(col[:, None] + dx, 0, w - 1)
            seen = cells[frames, ys, xs].astype(np.int64) + frames * n_classes
            counts = np.bincount(seen.ravel(), minlength=len(cells) * n_classes)
            out[start:start + len(cells)] += counts.reshape(-1, n_classes)
    if own_class is not None:
        out[:, own_class] = 0
    return out / (len(WRISTS) * len(dy))


def with_hands(features: np.ndarray, hands: np.ndarray, train_rows: np.ndarray
               ) -> np.ndarray:
    """(N, width + classes) float16: the features and the square roots of `hands`' shares,
    the whole block scaled so that its spread over `train_rows` is the features' (one
    scale for the block: a rare class's column stays small rather than blown up)."""
    block = np.sqrt(np.asarray(hands, np.float32))
    spread = float(np.asarray(features[train_rows], np.float32).std())
    scale = spread / (float(block[train_rows].std()) + 1e-6)
    return np.concatenate([np.asarray(features, np.float32), block * scale],
                          1).astype(np.float16)
