"""The RGB frame encoder of the clip models: a small CNN trained here on single frames.

The paper's TRN reads features of a backbone trained beforehand; homesim ships no
pretrained weights, so the backbone is trained first, here: a strided CNN over one frame
(`VideoFormat` size) with an action head and a step head, class-weighted cross-entropy on
frames labelled with the step they show, keeping the epoch that scores best on the
validation frames. Its feature of every frame of every episode is then computed once and
the clip models (TRN, single frame) and the video -> program encoder read those vectors,
as the oracle-perception models read the class pixel shares (`homesim.learn.video.clips`).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from homesim.learn.video.clips import Descriptors, fit_two_heads, mean_class_accuracy
from homesim.learn.video.data import Episode, step_class


@dataclass
class FrameCNNConfig:
    """The frame CNN; saved with its checkpoint."""

    n_actions: int
    n_steps: int
    feature: int = 64
    epochs: int = 8
    batch_size: int = 64
    lr: float = 2e-3
    seed: int = 0

    def to_dict(self) -> dict:
        return asdict(self)


class FrameCNN(nn.Module):
    """(N, 3, h, w) uint8 frames -> (N, feature): four strided 3x3 convolutions, then the
    spatial mean (~8 MFLOP a 64x48 frame)."""

    def __init__(self, cfg: FrameCNNConfig):
        super().__init__()
        self.cfg = cfg
        layers: list[nn.Module] = []
        for a, b, stride in ((3, 16, 2), (16, 32, 2), (32, 64, 2), (64, 64, 1)):
            layers += [nn.Conv2d(a, b, 3, stride=stride, padding=1), nn.BatchNorm2d(b),
                       nn.ReLU()]
        self.net = nn.Sequential(*layers, nn.AdaptiveAvgPool2d(1), nn.Flatten(),
                                 nn.Linear(64, cfg.feature), nn.ReLU())
        self.action_head = nn.Linear(cfg.feature, cfg.n_actions)
        self.step_head = nn.Linear(cfg.feature, cfg.n_steps)

    def forward(self, frames: torch.Tensor) -> torch.Tensor:
        return self.net(frames.float() / 255.0 - 0.5)

    def heads(self, frames: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        h = F.dropout(self.forward(frames), 0.3, self.training)
        return self.action_head(h), self.step_head(h)


@dataclass
class FrameSet:
    """Labelled frames: (N, 3, h, w) uint8 and their action and step class ids."""

    frames: torch.Tensor
    actions: torch.Tensor
    steps: torch.Tensor


def frame_set(episodes: list[Episode], actions: list[str], steps: list[str]) -> FrameSet:
    """Every frame that shows a step, labelled by the heads' class lists (-100: a class
    the heads do not have)."""
    a_index = {n: i for i, n in enumerate(actions)}
    s_index = {n: i for i, n in enumerate(steps)}
    frames, ya, ys = [], [], []
    for ep in episodes:
        labels = [step_class(t) for t in ep.step_texts]
        shown = np.nonzero(ep.step >= 0)[0]
        frames.append(ep.frames[shown])
        for i in shown.tolist():
            label = labels[ep.step[i]]
            ya.append(a_index.get(label.split("]")[0].strip("["), -100))
            ys.append(s_index.get(label, -100))
    stacked = np.concatenate(frames) if frames else np.zeros((0, 3, 1, 1), np.uint8)
    return FrameSet(torch.from_numpy(stacked), torch.tensor(ya, dtype=torch.long),
                    torch.tensor(ys, dtype=torch.long))


@torch.no_grad()
def _frame_score(model: FrameCNN, data: FrameSet, device: str) -> float:
    """Mean of the action and step mean per-class accuracy (%) over labelled frames."""
    model.eval()
    pa, ps = [], []
    for i in range(0, len(data.frames), 512):
        la, ls = model.heads(data.frames[i:i + 512].to(device))
        pa += la.argmax(1).tolist()
        ps += ls.argmax(1).tolist()
    return (mean_class_accuracy([str(p) for p in pa], [str(t) for t in data.actions.tolist()])
            + mean_class_accuracy([str(p) for p in ps], [str(t) for t in data.steps.tolist()])
            ) / 2


def train_frame_cnn(cfg: FrameCNNConfig, train: FrameSet, val: FrameSet | None,
                    device: str = "cpu") -> tuple[FrameCNN, int | None, list[float]]:
    """Class-weighted cross-entropy on both heads (`fit_two_heads`; batch norm needs
    batches of two); with `val`, the best epoch's weights. Returns the model, the epoch
    kept and each epoch's validation score."""
    torch.manual_seed(cfg.seed)
    model = FrameCNN(cfg).to(device)
    score = (lambda: _frame_score(model, val, device)) if val is not None and len(val.frames) \
        else None
    best_epoch, scores = fit_two_heads(model, model.heads, train.frames, train.actions,
                                       train.steps, cfg, score, device, min_batch=2)
    return model.eval(), best_epoch, scores


@torch.no_grad()
def frame_features(model: FrameCNN, episodes: list[Episode], batch_size: int = 512
                   ) -> Descriptors:
    """The CNN feature of every frame of every episode."""
    model.eval()
    device = next(model.parameters()).device
    out: Descriptors = {}
    for ep in episodes:
        parts = [model(torch.from_numpy(ep.frames[i:i + batch_size]).to(device)).cpu()
                 for i in range(0, len(ep.frames), batch_size)]
        out[ep.key] = (torch.cat(parts) if parts else torch.zeros(0, model.cfg.feature)
                       ).numpy()
    return out
