"""Step recognition in 2-second clips (the paper's Table 2, left): TRN over frame features.

Glossary:
    clip: `FRAMES` frames spread evenly over a 2-second window (every frame at 4
        frames/s), labelled with the step shown at its middle frame: its *action* and its
        *step* (action and object classes, instance numbers dropped, as the paper's
        action-object-object).
    descriptor: one vector per frame: the feature of a frame encoder trained here
        (`framecnn`) on RGB, on the predicted class map (`segment`) or on the
        ground-truth class map (the oracle). The TRN models differ only in it.
    TRN: temporal relation network (Zhou et al.): for k = 2..`ClipConfig.max_scale` (up to
        4-frame relations), `ClipConfig.subsets` ordered k-frame subsets of the clip's
        frames, spread over all of them, are concatenated and passed through an MLP g_k;
        the mean over subsets, summed over scales, is the clip feature.
    single frame: the clip feature is the middle frame's encoding (the baseline).
    end to end: with `ClipConfig.backbone`, the clip model holds the frame encoder itself
        (a `framecnn.FrameCNN`, started from the frame stage's trained weights) and reads
        the frames or class maps, fine-tuning the encoder with the TRN on the clips'
        labels, as TRN is trained (its backbone fine-tuned end to end); without it the
        descriptors are fixed features computed once.
Two linear heads read the clip feature (class-weighted cross-entropy on both). A clip's
step is the one whose log-probability plus its action's (the action head's) is highest:
the action head learns from every clip of an action, so it steers the step head among the
~200 steps, most of them rare (validation steps on the development plan: predicted maps
1.5 -> 2.1 %, true maps 5.6 -> 6.4 %; docs/learn.md). Scores are
mean per-class accuracy (recall averaged over the test classes; a class never seen in
training scores 0).
"""

from __future__ import annotations

import random
from collections import Counter, defaultdict
from dataclasses import asdict, dataclass
from itertools import combinations
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from homesim.learn.video.fit import FitResult, batches, fit
from homesim.learn.video.framecnn import FrameCNN, FrameCNNConfig, class_weights

FRAMES = 8
"""Frames sampled evenly from a clip."""
KINDS = ("trn", "single")
CLIP_SECONDS = 2.0
TRAIN_HOP = 1.0
"""Seconds between the starts of training clips (overlapping: twice the clips; the
default of `VideoRunConfig.train_hop`)."""


@dataclass
class ClipConfig:
    """A clip model; saved with its checkpoint."""

    kind: str  # "trn" | "single"
    input: str  # the descriptor: "rgb" | "seg" | "oracle"
    n_inputs: int  # descriptor width
    n_actions: int
    n_steps: int
    feature: int = 128
    epochs: int = 20
    batch_size: int = 64
    lr: float = 1e-3
    seed: int = 0
    max_scale: int = 4
    """The TRN's largest subset of frames (scales 2..max_scale: up to 4-frame relations)."""
    subsets: int = 4
    """Ordered frame subsets per scale (evenly spread over all of them)."""
    hidden: int = 256
    """Width of the relation MLPs' hidden layer."""
    dropout: float = 0.3
    backbone: dict | None = None
    """A `FrameCNNConfig` as a dict: the clip model reads frames or maps through this
    frame encoder and trains it too (end to end); None: it reads fixed descriptors."""

    def to_dict(self) -> dict:
        return asdict(self)


def _subsets(k: int, subsets: int) -> list[tuple[int, ...]]:
    every = list(combinations(range(FRAMES), k))
    picks = np.linspace(0, len(every) - 1, subsets).round().astype(int)
    return [every[i] for i in sorted(set(picks.tolist()))]


class ClipModel(nn.Module):
    """Frame encoder (an MLP over descriptors), temporal module (TRN or the middle frame)
    and two heads."""

    def __init__(self, cfg: ClipConfig):
        super().__init__()
        self.cfg = cfg
        f = cfg.feature
        self.backbone = FrameCNN(FrameCNNConfig(**cfg.backbone)) if cfg.backbone else None
        self.frames = nn.Sequential(nn.Linear(cfg.n_inputs, f), nn.ReLU())
        self.scales = list(range(2, cfg.max_scale + 1)) if cfg.kind == "trn" else []
        self.relations = nn.ModuleList(
            nn.Sequential(nn.Linear(k * f, cfg.hidden), nn.ReLU(), nn.Linear(cfg.hidden, f),
                          nn.ReLU())
            for k in self.scales)
        self.drop = nn.Dropout(cfg.dropout)
        self.action_head = nn.Linear(f, cfg.n_actions)
        self.step_head = nn.Linear(f, cfg.n_steps)

    def describe(self, clips: torch.Tensor) -> torch.Tensor:
        """(B, FRAMES, ...) inputs -> (B, FRAMES, width) descriptors: through the
        backbone when the model has one, else as given."""
        if self.backbone is None:
            return clips
        return self.backbone(clips.flatten(0, 1)).view(clips.shape[0], FRAMES, -1)

    def features(self, clips: torch.Tensor) -> torch.Tensor:
        """(B, FRAMES, width) descriptors (or frames or maps, with a backbone) -> (B,
        feature) clip features."""
        clips = self.describe(clips)
        if not self.scales:
            return self.frames(clips[:, FRAMES // 2])
        b = clips.shape[0]
        per_frame = self.frames(clips.flatten(0, 1)).view(b, FRAMES, -1)
        out = torch.zeros_like(per_frame[:, 0])
        for k, g in zip(self.scales, self.relations, strict=True):
            subs = _subsets(k, self.cfg.subsets)
            out = out + sum(g(per_frame[:, list(s)].flatten(1)) for s in subs) / len(subs)
        return out

    def forward(self, clips: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        h = self.drop(self.features(clips))
        return self.action_head(h), self.step_head(h)


def windows(length: int, fps: int, hop: float | None = None) -> list[tuple[int, int]]:
    """[a, b) frame windows of `CLIP_SECONDS` every `hop` s (default: back to back)."""
    size = max(1, round(CLIP_SECONDS * fps))
    step = max(1, round((hop or CLIP_SECONDS) * fps))
    return [(a, a + size) for a in range(0, length - size + 1, step)]


def clip_rows(a: int, b: int) -> np.ndarray:
    """The `FRAMES` frames of window [a, b), evenly spaced (relative rows)."""
    return np.linspace(a, b - 1, FRAMES).round().astype(np.int64)


def clip_inputs(features: np.ndarray, rows: np.ndarray) -> torch.Tensor:
    """The clips' inputs, (B, FRAMES, ...) for frame rows (B, FRAMES): float descriptors,
    or frames and class maps (uint8) as stored, for a model with a backbone."""
    x = np.asarray(features[rows])
    return torch.from_numpy(x if x.dtype == np.uint8 else x.astype(np.float32))


@dataclass
class ClipSet:
    """Clips: the store rows of their frames (N, FRAMES), the episode of each, and their
    action and step names."""

    rows: np.ndarray
    episodes: list[str]
    actions: list[str]
    steps: list[str]


def action_name(step: str) -> str:
    """``[Grab] <cup>`` -> ``Grab``."""
    return step.split("]")[0].strip("[")


def step_class(step_text: str) -> str:
    """``[Grab] <cup> (1)`` -> ``[Grab] <cup>``."""
    import re

    return re.sub(r"\s*\(\d+\)", "", step_text).strip()


def clip_set(episodes: list, step: np.ndarray, hop: float | None = None) -> ClipSet:
    """Every clip of the episodes (`store.StoredEpisode`) whose middle frame shows a step,
    every `hop` s (default back to back), labelled with that step."""
    rows, keys, actions, steps = [], [], [], []
    for ep in episodes:
        shown = step[ep.start:ep.start + ep.length]
        for a, b in windows(ep.length, ep.fps, hop):
            middle = int(shown[(a + b) // 2])
            if middle < 0:
                continue
            label = step_class(ep.steps[middle])
            rows.append(ep.start + clip_rows(a, b))
            keys.append(ep.key)
            actions.append(action_name(label))
            steps.append(label)
    stacked = np.stack(rows) if rows else np.zeros((0, FRAMES), np.int64)
    return ClipSet(stacked, keys, actions, steps)


@dataclass
class Labels:
    """Class names of the heads (from the training clips)."""

    actions: list[str]
    steps: list[str]

    @classmethod
    def build(cls, data: ClipSet) -> Labels:
        return cls(sorted(set(data.actions)), sorted(set(data.steps)))

    def step_actions(self) -> torch.Tensor:
        """Each step's action as an index into `actions`."""
        return torch.tensor([self.actions.index(action_name(s)) for s in self.steps])

    def ids(self, names: list[str], table: list[str]) -> np.ndarray:
        index = {n: i for i, n in enumerate(table)}
        return np.array([index.get(n, -100) for n in names], np.int64)


def train_clip_model(cfg: ClipConfig, features: np.ndarray, data: ClipSet, labels: Labels,
                     val: ClipSet | None = None, device: str = "cpu",
                     checkpoint: Path | None = None,
                     backbone_state: dict | None = None) -> tuple[ClipModel, FitResult]:
    """Class-weighted cross-entropy on both heads over the clips' descriptors (`features`:
    (store rows, width); with a backbone, the stored frames or maps, its weights started
    from `backbone_state`); with `val`, the epoch scoring best on it (mean of the two
    heads' mean per-class accuracy) is kept. Resumes from `checkpoint`."""
    torch.manual_seed(cfg.seed)
    model = ClipModel(cfg).to(device)
    if model.backbone is not None and backbone_state is not None:
        model.backbone.load_state_dict(backbone_state)
    y_a = labels.ids(data.actions, labels.actions)
    y_s = labels.ids(data.steps, labels.steps)
    w_a = class_weights(y_a, cfg.n_actions).to(device)
    w_s = class_weights(y_s, cfg.n_steps).to(device)

    def step(opt: torch.optim.Optimizer, rng: np.random.Generator) -> float:
        losses = []
        for batch in batches(len(y_s), cfg.batch_size, rng):
            la, ls = model(clip_inputs(features, data.rows[batch]).to(device))
            loss = (F.cross_entropy(la, torch.from_numpy(y_a[batch]).to(device), w_a,
                                    ignore_index=-100)
                    + F.cross_entropy(ls, torch.from_numpy(y_s[batch]).to(device), w_s,
                                      ignore_index=-100))
            opt.zero_grad()
            loss.backward()
            opt.step()
            losses.append(float(loss.detach()))
        return float(np.mean(losses)) if losses else 0.0

    score = None
    if val is not None and val.steps:
        def score() -> float:
            actions, steps = predict_clips(model, features, val, labels)
            return (mean_class_accuracy(actions, val.actions)
                    + mean_class_accuracy(steps, val.steps)) / 2
    result = fit(model, step, epochs=cfg.epochs, lr=cfg.lr, seed=cfg.seed, score=score,
                 checkpoint=checkpoint, config=cfg.to_dict())
    return model, result


@torch.no_grad()
def predict_clips(model: ClipModel, features: np.ndarray, data: ClipSet, labels: Labels,
                  batch_size: int = 512) -> tuple[list[str], list[str]]:
    """Predicted action and step names of every clip (a step scored with its action: see
    the module)."""
    model.eval()
    device = next(model.parameters()).device
    step_actions = labels.step_actions().to(device)
    actions: list[str] = []
    steps: list[str] = []
    for i in range(0, len(data.steps), batch_size):
        la, ls = model(clip_inputs(features, data.rows[i:i + batch_size]).to(device))
        joint = F.log_softmax(ls, 1) + F.log_softmax(la, 1)[:, step_actions]
        actions += [labels.actions[j] for j in la.argmax(1).tolist()]
        steps += [labels.steps[j] for j in joint.argmax(1).tolist()]
    return actions, steps


@torch.no_grad()
def clip_features(model: ClipModel, features: np.ndarray, rows: np.ndarray,
                  batch_size: int = 512) -> torch.Tensor:
    """(len(rows), feature) clip features (no dropout) of clips given by frame rows."""
    model.eval()
    device = next(model.parameters()).device
    out = [model.features(clip_inputs(features, rows[i:i + batch_size]).to(device)).cpu()
           for i in range(0, len(rows), batch_size)]
    return torch.cat(out) if out else torch.zeros(0, model.cfg.feature)


def random_retrieval(train: list[str], n: int, seed: int) -> list[str]:
    """The label of a random training clip for each of n test clips."""
    rng = random.Random(seed)
    return [rng.choice(train) for _ in range(n)]


def mean_class_accuracy(pred: list[str], truth: list[str]) -> float:
    """Recall of each true class, averaged over the classes (a percentage)."""
    hits: dict[str, int] = defaultdict(int)
    counts = Counter(truth)
    for p, t in zip(pred, truth, strict=True):
        hits[t] += p == t
    if not counts:
        return 0.0
    return 100.0 * sum(hits[c] / n for c, n in counts.items()) / len(counts)
