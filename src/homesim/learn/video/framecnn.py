"""The frame encoders of the clip models: small CNNs trained here on single frames.

The paper's TRN reads the features of a backbone trained beforehand (BN-Inception on RGB,
or on DilatedNet's segmentation); homesim ships no pretrained weights, so each backbone is
trained here, once (not per seed: a fixed backbone, as the paper's), on the training
frames that show a step, with an action head and a step head (class-weighted
cross-entropy, so the loss matches the metric, mean per-class accuracy), keeping the
epoch that scores best on the validation frames. Two inputs:

    rgb: the (3, H, W) frame; four 3x3 convolutions (three strided), then the spatial
        mean, or the means of a grid of cells (`FrameCNNConfig.grid_w`, `grid_h`) (~8
        MFLOP a 64x48 frame).
    map: a (H/2, W/2) class map (ground truth, or `segment`'s prediction): each class id
        becomes a learned 16-d vector (a 1x1 convolution of the one-hot map), then three
        3x3 convolutions (two strided) and the spatial mean. The map's layout (what is next
        to what, where the agent is) reaches the feature, not only how much of each class
        is seen.

Each backbone's 64-d feature of every frame is then computed once (`frame_features`) and read
by the clip models (`clips`) of every seed.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from homesim.learn.video.fit import FitResult, fit, frame_epoch

INPUTS = ("rgb", "map")
IGNORE = -100


@dataclass
class FrameCNNConfig:
    """A frame encoder; saved with its checkpoint."""

    n_actions: int
    n_steps: int
    input: str = "rgb"  # one of INPUTS
    num_classes: int = 0  # map inputs: class ids below this
    feature: int = 64
    epochs: int = 6
    batch_size: int = 64
    lr: float = 2e-3
    seed: int = 0
    frames_per_epoch: int = 60000  # training frames drawn each epoch (all if fewer)
    dropout: float = 0.3
    """Dropout on the feature before the heads."""
    grid_w: int = 1
    grid_h: int = 1
    """The last convolution's output is averaged over a grid_w x grid_h grid of cells
    (1 x 1: the spatial mean), whose means all reach the feature: with more than one
    cell, where things are in the frame (the agent's place and height) is kept."""

    def to_dict(self) -> dict:
        return asdict(self)


class FrameCNN(nn.Module):
    """(N, 3, H, W) uint8 frames or (N, h, w) uint8 class maps -> (N, feature)."""

    def __init__(self, cfg: FrameCNNConfig):
        super().__init__()
        self.cfg = cfg
        plan: tuple[tuple[int, int, int], ...]
        if cfg.input == "map":
            self.embed: nn.Embedding | None = nn.Embedding(cfg.num_classes, 16)
            plan = ((16, 32, 2), (32, 64, 2), (64, 64, 1))
        else:
            self.embed = None
            plan = ((3, 16, 2), (16, 32, 2), (32, 64, 2), (64, 64, 1))
        layers: list[nn.Module] = []
        for a, b, stride in plan:
            layers += [nn.Conv2d(a, b, 3, stride=stride, padding=1), nn.BatchNorm2d(b),
                       nn.ReLU()]
        cells = cfg.grid_h * cfg.grid_w
        self.net = nn.Sequential(*layers, nn.AdaptiveAvgPool2d((cfg.grid_h, cfg.grid_w)),
                                 nn.Flatten(), nn.Linear(64 * cells, cfg.feature), nn.ReLU())
        self.action_head = nn.Linear(cfg.feature, cfg.n_actions)
        self.step_head = nn.Linear(cfg.feature, cfg.n_steps)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        if self.embed is not None:
            x = self.embed(x.long().clamp(max=self.cfg.num_classes - 1)).permute(0, 3, 1, 2)
        else:
            x = x.float() / 255.0 - 0.5
        return self.net(x)

    def heads(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        h = F.dropout(self.forward(x), self.cfg.dropout, self.training)
        return self.action_head(h), self.step_head(h)


def class_weights(ids: np.ndarray, n: int) -> torch.Tensor:
    """(n,) inverse class frequencies normalised to mean 1 over the classes present (the
    loss then matches mean per-class accuracy rather than favouring walking)."""
    counts = np.bincount(ids[ids >= 0], minlength=n).astype(np.float64)
    w = np.where(counts > 0, 1.0 / np.maximum(counts, 1), 0.0)
    return torch.tensor(w * (counts > 0).sum() / max(w.sum(), 1e-9), dtype=torch.float32)


@dataclass
class FrameLabels:
    """Per-row class ids of the two heads (`IGNORE` for none)."""

    actions: np.ndarray
    steps: np.ndarray


def mean_class_accuracy_ids(pred: np.ndarray, truth: np.ndarray) -> float:
    """Recall of each true class, averaged over the classes present (%)."""
    keep = truth >= 0
    pred, truth = pred[keep], truth[keep]
    if not len(truth):
        return 0.0
    classes, inverse = np.unique(truth, return_inverse=True)
    hits = np.bincount(inverse, weights=(pred == truth).astype(float), minlength=len(classes))
    return 100.0 * float(np.mean(hits / np.bincount(inverse, minlength=len(classes))))


def _inputs(data: np.ndarray, idx: np.ndarray) -> torch.Tensor:
    return torch.from_numpy(np.asarray(data[np.sort(idx)]))


def train_frame_cnn(cfg: FrameCNNConfig, data: np.ndarray, labels: FrameLabels,
                    train_rows: np.ndarray, val_rows: np.ndarray | None, device: str = "cpu",
                    checkpoint: Path | None = None) -> tuple[FrameCNN, FitResult]:
    """Class-weighted cross-entropy on both heads over `train_rows` of `data` (frames or
    maps, memory-mapped), `frames_per_epoch` drawn each epoch; the epoch scoring best on
    `val_rows` (mean of the two heads' mean per-class accuracy) is kept. Resumes from
    `checkpoint`."""
    torch.manual_seed(cfg.seed)
    model = FrameCNN(cfg).to(device)
    rows = train_rows[labels.steps[train_rows] >= 0]
    w_a = class_weights(labels.actions[rows], cfg.n_actions).to(device)
    w_s = class_weights(labels.steps[rows], cfg.n_steps).to(device)

    def batch_loss(idx: np.ndarray) -> torch.Tensor:
        la, ls = model.heads(_inputs(data, idx).to(device))
        ya = torch.from_numpy(labels.actions[idx]).long().to(device)
        ys = torch.from_numpy(labels.steps[idx]).long().to(device)
        return (F.cross_entropy(la, ya, w_a, ignore_index=IGNORE)
                + F.cross_entropy(ls, ys, w_s, ignore_index=IGNORE))

    def step(opt: torch.optim.Optimizer, rng: np.random.Generator) -> float:
        return frame_epoch(opt, rng, rows, cfg.frames_per_epoch, cfg.batch_size, batch_loss)

    score = None
    if val_rows is not None and len(val_rows):
        shown = val_rows[labels.steps[val_rows] >= 0][:20000]

        def score() -> float:
            pa, ps = predict_frames(model, data, shown)
            return (mean_class_accuracy_ids(pa, labels.actions[shown])
                    + mean_class_accuracy_ids(ps, labels.steps[shown])) / 2
    result = fit(model, step, epochs=cfg.epochs, lr=cfg.lr, seed=cfg.seed, score=score,
                 checkpoint=checkpoint, config=cfg.to_dict())
    return model, result


@torch.no_grad()
def predict_frames(model: FrameCNN, data: np.ndarray, rows: np.ndarray,
                   batch_size: int = 512) -> tuple[np.ndarray, np.ndarray]:
    """The two heads' predicted class ids of `rows`."""
    model.eval()
    device = next(model.parameters()).device
    pa, ps = [], []
    for i in range(0, len(rows), batch_size):
        la, ls = model.heads(_inputs(data, rows[i:i + batch_size]).to(device))
        pa.append(la.argmax(1).cpu().numpy())
        ps.append(ls.argmax(1).cpu().numpy())
    empty = np.zeros(0, np.int64)
    return (np.concatenate(pa) if pa else empty), (np.concatenate(ps) if ps else empty)


@torch.no_grad()
def frame_features(model: FrameCNN, data: np.ndarray, batch_size: int = 512) -> np.ndarray:
    """(N, feature) float16: the feature of every row of `data`."""
    model.eval()
    device = next(model.parameters()).device
    out = np.zeros((len(data), model.cfg.feature), np.float16)
    for i in range(0, len(data), batch_size):
        x = torch.from_numpy(np.array(data[i:i + batch_size])).to(device)
        out[i:i + batch_size] = model(x).cpu().numpy()
    return out
