"""The segmentation network of the perception rows (the paper's DilatedNet, small): RGB
frames -> a class map at half the frame size, trained here on the training frames'
ground-truth class maps.

The network: a strided encoder to a quarter of the frame, two dilated convolutions for
context (dilation 2 and 4, as DilatedNet widens its view without losing resolution), and
one upsampling step (nearest) joined with the half-size features (a skip connection) to per-pixel
class logits at half size (the map size of `homesim.learn.video.store`). Classes are
every class of the training maps (``num_classes``; the background is class 0); loss is
per-pixel cross-entropy. Scored by pixel accuracy and mean IoU over the classes present
in the scored frames' truth.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from homesim.learn.video.fit import FitResult, fit, frame_epoch, over_frames


@dataclass
class SegConfig:
    """The segmentation network; saved with its checkpoint."""

    num_classes: int
    width: int = 16  # channels of the half-size features
    epochs: int = 4
    batch_size: int = 64
    lr: float = 2e-3
    seed: int = 0
    frames_per_epoch: int = 40000  # training frames drawn each epoch (all if fewer)

    def to_dict(self) -> dict:
        return asdict(self)


def _conv(a: int, b: int, stride: int = 1, dilation: int = 1) -> nn.Sequential:
    return nn.Sequential(nn.Conv2d(a, b, 3, stride, padding=dilation, dilation=dilation),
                         nn.BatchNorm2d(b), nn.ReLU())


def _double(x: torch.Tensor) -> torch.Tensor:
    """Nearest upsampling by 2 as a broadcast: its gradient is a plain sum, deterministic
    on CUDA (bilinear interpolation's is not)."""
    n, c, h, w = x.shape
    return x[:, :, :, None, :, None].expand(n, c, h, 2, w, 2).reshape(n, c, 2 * h, 2 * w)


class SegNet(nn.Module):
    """(N, 3, H, W) uint8 -> (N, classes, H/2, W/2) logits (~20 MFLOP a 64x48 frame)."""

    def __init__(self, cfg: SegConfig):
        super().__init__()
        self.cfg = cfg
        w = cfg.width
        self.fine = nn.Sequential(_conv(3, 16, 2), _conv(16, w))  # (N, w, H/2, W/2)
        self.quarter = nn.Sequential(_conv(w, 2 * w, 2), _conv(2 * w, 2 * w, dilation=2),
                                     _conv(2 * w, 2 * w, dilation=4))  # (N, 2w, H/4, W/4)
        self.join = nn.Sequential(nn.Conv2d(3 * w, w, 1), nn.ReLU(), _conv(w, w))
        self.out = nn.Conv2d(w, cfg.num_classes, 1)

    def forward(self, frames: torch.Tensor) -> torch.Tensor:
        half = self.fine(frames.float() / 255.0 - 0.5)
        up = _double(self.quarter(half))[..., :half.shape[2], :half.shape[3]]
        return self.out(self.join(torch.cat([half, up], 1)))


def pixel_loss(logits: torch.Tensor, truth: torch.Tensor) -> torch.Tensor:
    """Per-pixel cross-entropy, (N, C, h, w) logits against (N, h, w) class ids, written
    with a one-hot product: the same value as `F.cross_entropy`, and deterministic on CUDA
    too (its 2-d form is not, and the CLI asks torch for deterministic algorithms)."""
    one_hot = F.one_hot(truth, logits.shape[1]).permute(0, 3, 1, 2).to(logits.dtype)
    return -(F.log_softmax(logits, 1) * one_hot).sum(1).mean()


def train_segnet(cfg: SegConfig, frames: np.ndarray, maps: np.ndarray, train_rows: np.ndarray,
                 val_rows: np.ndarray | None, device: str = "cpu",
                 checkpoint: Path | None = None) -> tuple[SegNet, FitResult]:
    """Per-pixel cross-entropy on `train_rows` of `frames` (N, 3, H, W) and their `maps`
    (N, H/2, W/2) class ids, `frames_per_epoch` drawn each epoch; the epoch with the best
    validation mean IoU is kept. Resumes from `checkpoint`."""
    torch.manual_seed(cfg.seed)
    model = SegNet(cfg).to(device)

    def batch_loss(idx: np.ndarray) -> torch.Tensor:
        x = torch.from_numpy(np.asarray(frames[idx])).to(device)
        y = torch.from_numpy(np.asarray(maps[idx]).astype(np.int64)).to(device)
        return pixel_loss(model(x), y.clamp(max=cfg.num_classes - 1))

    def step(opt: torch.optim.Optimizer, rng: np.random.Generator) -> float:
        return frame_epoch(opt, rng, train_rows, cfg.frames_per_epoch, cfg.batch_size,
                           batch_loss)

    score = None
    if val_rows is not None and len(val_rows):
        def score() -> float:
            return segmentation_scores(model, frames, maps, val_rows[:8000])["miou"]
    result = fit(model, step, epochs=cfg.epochs, lr=cfg.lr, seed=cfg.seed, score=score,
                 checkpoint=checkpoint, config=cfg.to_dict())
    return model, result


@torch.no_grad()
def predict_maps(model: SegNet, frames: np.ndarray, rows: np.ndarray | None = None,
                 batch_size: int = 256) -> np.ndarray:
    """(len(rows), H/2, W/2) uint8: the predicted class of every pixel."""
    out = over_frames(model, frames, rows, batch_size,
                      lambda logits: logits.argmax(1).to(torch.uint8).cpu().numpy())
    h, w = frames.shape[2] // 2, frames.shape[3] // 2
    return np.concatenate(out) if out else np.zeros((0, h, w), np.uint8)


def confusion(pred: np.ndarray, truth: np.ndarray, n: int) -> np.ndarray:
    """(n, n) pixel counts: row the true class, column the predicted one."""
    t = np.minimum(truth.astype(np.int64).ravel(), n - 1)
    return np.bincount(t * n + pred.astype(np.int64).ravel(), minlength=n * n).reshape(n, n)


def scores_from_confusion(conf: np.ndarray) -> dict[str, float]:
    """Pixel accuracy and mean IoU (over the classes present in the truth), in %."""
    inter = np.diag(conf).astype(float)
    union = conf.sum(0) + conf.sum(1) - inter
    present = conf.sum(1) > 0
    iou = inter[present] / np.maximum(union[present], 1)
    return {"pixel_accuracy": 100.0 * inter.sum() / max(conf.sum(), 1),
            "miou": 100.0 * float(iou.mean()) if len(iou) else 0.0,
            "classes": int(present.sum())}


def segmentation_scores(model: SegNet, frames: np.ndarray, maps: np.ndarray,
                        rows: np.ndarray) -> dict[str, float]:
    """Pixel accuracy and mean IoU of the model on `rows`."""
    n = model.cfg.num_classes
    conf = np.zeros((n, n), np.int64)
    for i in range(0, len(rows), 2048):
        part = rows[i:i + 2048]
        conf += confusion(predict_maps(model, frames, part), np.asarray(maps[part]), n)
    return scores_from_confusion(conf)
