"""Step recognition in 2-second clips (the paper's Table 2, left): TRN over frame vectors.

Glossary:
    descriptor: one vector per frame. RGB: the feature of the frame CNN trained here
        (`homesim.learn.video.framecnn`, the backbone); *oracle perception*: the frame's
        ground-truth class pixel shares. Both models below are the same but for it, so
        the gap between them is how much of the task is perception.
    frame encoder: an MLP over a frame's descriptor.
    TRN: temporal relation network (Zhou et al.): for k = 2..`MAX_SCALE`, ordered subsets of
        k of the clip's `FRAMES` sampled frames are concatenated and passed through an MLP
        g_k; the mean over subsets, summed over scales, is the clip feature.
    single-frame: the clip feature is the middle frame's encoding (the baseline).
Two linear heads read the clip feature: the clip's action and its step (action and object
classes). Scores are mean per-class accuracy (recall averaged over the test classes;
classes never seen in training count with 0).
"""

from __future__ import annotations

import copy
import random
from collections import Counter, defaultdict
from collections.abc import Callable
from dataclasses import asdict, dataclass
from itertools import combinations
from typing import Protocol

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from homesim.learn.video.data import Episode

Descriptors = dict[str, np.ndarray]
"""Episode key -> (frames, width) float32: one vector per frame (CNN feature or shares)."""
FRAMES = 8
"""Frames sampled evenly from a clip."""
MAX_SCALE = 4
SUBSETS = 4
"""Ordered frame subsets per scale (evenly spread over all of them)."""
KINDS = ("trn", "single")
INPUTS = ("rgb", "oracle")


@dataclass
class ClipConfig:
    """A clip model; saved with its checkpoint."""

    kind: str  # "trn" | "single"
    input: str  # "rgb" | "oracle"
    n_inputs: int  # descriptor width
    n_actions: int
    n_steps: int
    feature: int = 64
    epochs: int = 8
    batch_size: int = 32
    lr: float = 2e-3
    seed: int = 0

    def to_dict(self) -> dict:
        return asdict(self)


def _subsets(k: int) -> list[tuple[int, ...]]:
    every = list(combinations(range(FRAMES), k))
    picks = np.linspace(0, len(every) - 1, SUBSETS).round().astype(int)
    return [every[i] for i in sorted(set(picks.tolist()))]


INPUT_SCALE = {"rgb": 1.0, "oracle": 10.0}
"""Descriptors are multiplied by this (class pixel shares are small)."""


class FrameEncoder(nn.Module):
    """(N, n_inputs) frame descriptors -> (N, feature)."""

    def __init__(self, cfg: ClipConfig):
        super().__init__()
        self.scale = INPUT_SCALE[cfg.input]
        self.net = nn.Sequential(nn.Linear(cfg.n_inputs, 128), nn.ReLU(),
                                 nn.Linear(128, cfg.feature), nn.ReLU())

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.net(x * self.scale)


class ClipModel(nn.Module):
    """Frame encoder, temporal module (TRN or single frame) and two heads."""

    def __init__(self, cfg: ClipConfig):
        super().__init__()
        self.cfg = cfg
        self.frames = FrameEncoder(cfg)
        f = cfg.feature
        self.scales = list(range(2, MAX_SCALE + 1)) if cfg.kind == "trn" else []
        self.relations = nn.ModuleList(
            nn.Sequential(nn.Linear(k * f, 128), nn.ReLU(), nn.Linear(128, f), nn.ReLU())
            for k in self.scales)
        self.drop = nn.Dropout(0.3)
        self.action_head = nn.Linear(f, cfg.n_actions)
        self.step_head = nn.Linear(f, cfg.n_steps)

    def features(self, clips: torch.Tensor) -> torch.Tensor:
        """(B, FRAMES, width) descriptors -> (B, feature) clip features."""
        if not self.scales:
            return self.frames(clips[:, FRAMES // 2])
        b = clips.shape[0]
        per_frame = self.frames(clips.flatten(0, 1)).view(b, FRAMES, -1)
        out = torch.zeros_like(per_frame[:, 0])
        for k, g in zip(self.scales, self.relations, strict=True):
            subs = _subsets(k)
            out = out + sum(g(per_frame[:, list(s)].flatten(1)) for s in subs) / len(subs)
        return out

    def forward(self, clips: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        h = self.drop(self.features(clips))
        return self.action_head(h), self.step_head(h)


@dataclass
class ClipSet:
    """Clips as tensors: inputs (N, FRAMES, descriptor width), their action and step
    texts."""

    inputs: torch.Tensor
    actions: list[str]
    steps: list[str]


def clip_inputs(vectors: np.ndarray, a: int, b: int) -> np.ndarray:
    """(`FRAMES`, width): the descriptors of `FRAMES` evenly spaced frames of [a, b)."""
    return vectors[np.linspace(a, b - 1, FRAMES).round().astype(int)]


TRAIN_HOP = 1.0
"""Seconds between the starts of training clips (overlapping: twice the clips)."""


def clip_set(episodes: list[Episode], descriptors: Descriptors, hop: float | None = None
             ) -> ClipSet:
    """Every labelled clip of the episodes (every `hop` s; default non-overlapping)."""
    inputs, actions, steps = [], [], []
    for ep in episodes:
        for a, b, label in ep.clips(hop=hop):
            inputs.append(clip_inputs(descriptors[ep.key], a, b))
            actions.append(label.split("]")[0].strip("["))
            steps.append(label)
    width = next(iter(descriptors.values())).shape[1] if descriptors else 0
    stacked = np.stack(inputs) if inputs else np.zeros((0, FRAMES, width), np.float32)
    return ClipSet(torch.from_numpy(stacked.astype(np.float32)), actions, steps)


@dataclass
class Labels:
    """Class names of the heads (from the training clips)."""

    actions: list[str]
    steps: list[str]

    @classmethod
    def build(cls, data: ClipSet) -> Labels:
        return cls(sorted(set(data.actions)), sorted(set(data.steps)))

    def ids(self, names: list[str], table: list[str]) -> torch.Tensor:
        index = {n: i for i, n in enumerate(table)}
        return torch.tensor([index.get(n, -100) for n in names])


def class_weights(ids: torch.Tensor, n: int) -> torch.Tensor:
    """(n,) inverse class frequencies normalised to mean 1 over the classes present: the
    loss then matches the metric (mean per-class accuracy) rather than favouring walking."""
    counts = torch.bincount(ids[ids >= 0], minlength=n).float()
    weights = torch.where(counts > 0, 1.0 / counts.clamp(min=1), torch.zeros_like(counts))
    return weights * (counts > 0).sum() / weights.sum().clamp(min=1e-9)


def clip_score(model: ClipModel, data: ClipSet, labels: Labels) -> float:
    """Mean of the action and step mean per-class accuracies (%): what chooses the epoch."""
    actions, steps = predict_clips(model, data, labels)
    return (mean_class_accuracy(actions, data.actions)
            + mean_class_accuracy(steps, data.steps)) / 2


@dataclass
class ClipTraining:
    """A trained clip model, the epoch kept and each epoch's validation score."""

    model: ClipModel
    best_epoch: int | None
    val_scores: list[float]


def train_clip_model(cfg: ClipConfig, data: ClipSet, labels: Labels, val: ClipSet | None = None,
                     device: str = "cpu") -> ClipTraining:
    """Class-weighted cross-entropy on both heads (`fit_two_heads`); with `val`, the weights
    of the epoch scoring best on it (`clip_score`) are kept. Same seed, same weights."""
    torch.manual_seed(cfg.seed)
    model = ClipModel(cfg).to(device)
    score = (lambda: clip_score(model, val, labels)) if val is not None and val.steps else None
    best_epoch, scores = fit_two_heads(
        model, model, data.inputs, labels.ids(data.actions, labels.actions),
        labels.ids(data.steps, labels.steps), cfg, score, device)
    return ClipTraining(model.eval(), best_epoch, scores)


class TrainingConfig(Protocol):
    """What `fit_two_heads` reads of a model's config (`ClipConfig`, `FrameCNNConfig`)."""

    n_actions: int
    n_steps: int
    epochs: int
    batch_size: int
    lr: float
    seed: int


def fit_two_heads(model: nn.Module, heads: Callable[[torch.Tensor], tuple[torch.Tensor, ...]],
                  inputs: torch.Tensor, y_a: torch.Tensor, y_s: torch.Tensor, cfg: TrainingConfig,
                  score: Callable[[], float] | None, device: str, min_batch: int = 1
                  ) -> tuple[int | None, list[float]]:
    """Train `model` (already seeded and on `device`) with Adam on the action and step
    heads' class-weighted cross-entropy (`class_weights`; label -100 is ignored), in
    shuffled batches of ``cfg.batch_size`` (smaller than `min_batch` skipped) for
    ``cfg.epochs`` epochs. With `score`, the weights of the best-scoring epoch are loaded
    back. Returns that epoch (None without `score`) and each epoch's score."""
    opt = torch.optim.Adam(model.parameters(), lr=cfg.lr)
    w_a = class_weights(y_a, cfg.n_actions).to(device)
    w_s = class_weights(y_s, cfg.n_steps).to(device)
    rng = random.Random(cfg.seed)
    order = list(range(len(y_s)))
    scores: list[float] = []
    best: tuple[float, int, dict] | None = None
    for epoch in range(cfg.epochs):
        model.train()
        rng.shuffle(order)
        for i in range(0, len(order), cfg.batch_size):
            batch = torch.tensor(order[i:i + cfg.batch_size])
            if len(batch) < min_batch:
                continue
            logit_a, logit_s = heads(inputs[batch].to(device))
            loss = (F.cross_entropy(logit_a, y_a[batch].to(device), w_a, ignore_index=-100)
                    + F.cross_entropy(logit_s, y_s[batch].to(device), w_s, ignore_index=-100))
            opt.zero_grad()
            loss.backward()
            opt.step()
        if score is not None:
            scores.append(score())
            if best is None or scores[-1] > best[0]:
                best = (scores[-1], epoch, copy.deepcopy(model.state_dict()))
    if best is not None:
        model.load_state_dict(best[2])
    return (best[1] if best else None), scores


@torch.no_grad()
def predict_clips(model: ClipModel, data: ClipSet, labels: Labels,
                  batch_size: int = 128) -> tuple[list[str], list[str]]:
    """Predicted action and step names of every clip."""
    model.eval()
    device = next(model.parameters()).device
    actions: list[str] = []
    steps: list[str] = []
    for i in range(0, len(data.steps), batch_size):
        logit_a, logit_s = model(data.inputs[i:i + batch_size].to(device))
        actions += [labels.actions[j] for j in logit_a.argmax(1).tolist()]
        steps += [labels.steps[j] for j in logit_s.argmax(1).tolist()]
    return actions, steps


@torch.no_grad()
def clip_features(model: ClipModel, inputs: torch.Tensor) -> torch.Tensor:
    """(N, feature) clip features (no dropout)."""
    model.eval()
    device = next(model.parameters()).device
    if len(inputs) == 0:
        return torch.zeros(0, model.cfg.feature)
    return model.features(inputs.to(device)).cpu()


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
