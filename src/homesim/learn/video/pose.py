"""The pose network of the perception rows: RGB frames -> the agent's 2-D joints, trained
here on the training frames' ground-truth joints (`joints2d`, `joints_visible` of each
episode, in the store as ``joints.npy``).

Why: the class maps, true or predicted, show the agent as a blob of ~20 pixels, and the
clip models then confuse Walk with Run and miss Sit and StandUp; the ground-truth joints
beside the maps add ~17 points of action accuracy on validation (docs/learn.md). This
network is the perceived stand-in for those joints.

The network: the segmentation network's body (`segment.SegNet`: strided encoder, dilated
context, a skip at half size) with one heatmap per joint at half the frame size; a
joint's place is the heatmap's expected cell (a soft-argmax: differentiable, finer than a
cell), its visibility (in the frame and not hidden behind something) a logistic read of
the heatmap's peak and mean. Loss: L1 distance in half-size cells over the joints inside
the frame, hidden ones too (their place follows from the body's), plus the visibility's
cross-entropy. Scored by the mean error of visible joints in frame pixels and PCK (the
share within a fifth of the body's height).

`pose_descriptor` turns joints (true or predicted) into what a clip model reads per
frame: each joint relative to the body's centre in body heights, its visibility, the
centre's place and the height.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from homesim.learn.video.fit import FitResult, fit, frame_epoch, over_frames
from homesim.learn.video.segment import SegConfig, SegNet

PCK_SHARE = 0.2
"""A predicted joint is correct within this share of the body's height (PCK)."""


@dataclass
class PoseConfig:
    """The pose network; saved with its checkpoint."""

    joints: int
    width: int = 16  # channels of the half-size features (as `SegConfig.width`)
    epochs: int = 6  # validation PCK on the development plan: 51.7 % after 4, 54.9 % after 6
    batch_size: int = 64
    lr: float = 2e-3
    seed: int = 0
    frames_per_epoch: int = 40000  # training frames drawn each epoch (all if fewer)

    def to_dict(self) -> dict:
        return asdict(self)


class PoseNet(nn.Module):
    """(N, 3, H, W) uint8 -> (N, joints, 3): x and y as shares of the frame's width and
    height, and the visibility's logit."""

    def __init__(self, cfg: PoseConfig):
        super().__init__()
        self.cfg = cfg
        self.heatmaps = SegNet(SegConfig(num_classes=cfg.joints, width=cfg.width))
        self.visible = nn.Conv1d(cfg.joints, cfg.joints, 2, groups=cfg.joints)

    def forward(self, frames: torch.Tensor) -> torch.Tensor:
        logits = self.heatmaps(frames)  # (N, J, h, w)
        n, j, h, w = logits.shape
        p = F.softmax(logits.flatten(2), 2).view(n, j, h, w)
        xs = (torch.arange(w, device=p.device, dtype=p.dtype) + 0.5) / w
        ys = (torch.arange(h, device=p.device, dtype=p.dtype) + 0.5) / h
        x = (p.sum(2) * xs).sum(2)
        y = (p.sum(3) * ys).sum(2)
        flat = logits.flatten(2)
        peaks = torch.stack([flat.amax(2), flat.mean(2)], 2)  # (N, J, 2)
        vis = self.visible(peaks).squeeze(2)
        return torch.stack([x, y, vis], 2)


def pose_loss(pred: torch.Tensor, truth: torch.Tensor, map_size: tuple[int, int]
              ) -> torch.Tensor:
    """L1 distance in half-size cells over the joints of `truth` ((N, J, 3): x, y shares,
    visible 0/1) inside the frame, plus the visibility's binary cross-entropy."""
    w, h = map_size
    xy = truth[..., :2]
    inside = ((xy >= 0) & (xy <= 1)).all(-1).to(pred.dtype)
    scale = torch.tensor([w, h], dtype=pred.dtype, device=pred.device)
    dist = ((pred[..., :2] - xy).abs() * scale).sum(-1)
    place = (dist * inside).sum() / inside.sum().clamp(min=1.0)
    return place + F.binary_cross_entropy_with_logits(pred[..., 2], truth[..., 2])


def train_posenet(cfg: PoseConfig, frames: np.ndarray, joints: np.ndarray,
                  train_rows: np.ndarray, val_rows: np.ndarray | None, device: str = "cpu",
                  checkpoint: Path | None = None) -> tuple[PoseNet, FitResult]:
    """Train on `train_rows` of `frames` (N, 3, H, W) and their `joints` (N, J, 3),
    `frames_per_epoch` drawn each epoch; the epoch with the best validation PCK is kept.
    Resumes from `checkpoint`."""
    torch.manual_seed(cfg.seed)
    model = PoseNet(cfg).to(device)
    map_size = (frames.shape[3] // 2, frames.shape[2] // 2)

    def batch_loss(idx: np.ndarray) -> torch.Tensor:
        x = torch.from_numpy(np.asarray(frames[idx])).to(device)
        y = torch.from_numpy(np.asarray(joints[idx], np.float32)).to(device)
        return pose_loss(model(x), y, map_size)

    def step(opt: torch.optim.Optimizer, rng: np.random.Generator) -> float:
        return frame_epoch(opt, rng, train_rows, cfg.frames_per_epoch, cfg.batch_size,
                           batch_loss)

    score = None
    if val_rows is not None and len(val_rows):
        def score() -> float:
            return pose_scores(model, frames, joints, val_rows[:8000])["pck"]
    result = fit(model, step, epochs=cfg.epochs, lr=cfg.lr, seed=cfg.seed, score=score,
                 checkpoint=checkpoint, config=cfg.to_dict())
    return model, result


@torch.no_grad()
def predict_joints(model: PoseNet, frames: np.ndarray, rows: np.ndarray | None = None,
                   batch_size: int = 256) -> np.ndarray:
    """(len(rows), J, 3) float16: each joint's x and y shares and its visibility's
    probability."""
    def read(pred: torch.Tensor) -> np.ndarray:
        pred[..., 2] = torch.sigmoid(pred[..., 2])
        return pred.cpu().numpy().astype(np.float16)

    out = over_frames(model, frames, rows, batch_size, read)
    return np.concatenate(out) if out else np.zeros((0, model.cfg.joints, 3), np.float16)


def _heights(joints: np.ndarray) -> np.ndarray:
    """(N,) the vertical extent of each frame's visible joints (a share of the frame)."""
    seen = joints[..., 2] > 0.5
    y = joints[..., 1]
    top = np.where(seen, y, np.inf).min(1)
    bottom = np.where(seen, y, -np.inf).max(1)
    return np.where(seen.any(1), bottom - top, 0.0)


def pose_scores(model: PoseNet, frames: np.ndarray, joints: np.ndarray, rows: np.ndarray
                ) -> dict[str, float]:
    """On the visible joints of `rows`: mean error in frame pixels, PCK (%) within
    `PCK_SHARE` of the body's height, and visibility accuracy (%) over all joints."""
    truth = np.asarray(joints[rows], np.float32)
    pred = predict_joints(model, frames, rows).astype(np.float32)
    seen = truth[..., 2] > 0.5
    size = np.array([frames.shape[3], frames.shape[2]], np.float32)
    err = np.linalg.norm((pred[..., :2] - truth[..., :2]) * size, axis=-1)
    tol = (PCK_SHARE * _heights(truth) * frames.shape[2])[:, None]
    vis_ok = (pred[..., 2] > 0.5) == seen
    return {"error_px": float(err[seen].mean()) if seen.any() else 0.0,
            "pck": 100.0 * float((err <= tol)[seen].mean()) if seen.any() else 0.0,
            "visibility": 100.0 * float(vis_ok.mean()) if vis_ok.size else 0.0}


def pose_descriptor(joints: np.ndarray) -> np.ndarray:
    """(N, J, 3) joints (x, y shares; visibility or its probability) -> (N, 3J + 3)
    float32: each joint's place relative to the joints' centre in body heights (the
    vertical extent of all joints, hidden ones too: the network places those as well),
    the visibilities, the centre and the height."""
    j = np.asarray(joints, np.float32)
    centre = j[..., :2].mean(1)
    height = (j[..., 1].max(1) - j[..., 1].min(1))[:, None]
    rel = (j[..., :2] - centre[:, None]) / np.maximum(height, 0.02)[..., None]
    return np.concatenate([rel.reshape(len(j), -1), j[..., 2], centre, height], 1)
