"""Resumable training: epochs of a model with a checkpoint after each, and the weights of
the epoch that scores best on validation kept.

A job stopped between two epochs (a sitting that ends, a kill) continues from the last
checkpoint when run again and ends with the same weights as a run never stopped: each
epoch draws its batch order and dropout from its own seed (``(seed, epoch)``), not from
what ran before it.
"""

from __future__ import annotations

import copy
import hashlib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import torch
from torch import nn

from homesim.errors import HomesimError

EpochStep = Callable[[torch.optim.Optimizer, np.random.Generator], float]
"""Trains one epoch with the optimiser and the epoch's generator; returns its mean loss."""


def epoch_seed(seed: int, epoch: int) -> int:
    """The seed of one epoch's batch order and dropout."""
    return int.from_bytes(hashlib.sha256(f"fit-{seed}-{epoch}".encode()).digest()[:4], "big")


@dataclass
class FitResult:
    """What `fit` did: the epoch kept (None without validation), each epoch's loss and
    validation score."""

    best_epoch: int | None
    losses: list[float] = field(default_factory=list)
    scores: list[float] = field(default_factory=list)


def _load(path: Path, config: dict[str, Any]) -> dict[str, Any] | None:
    if not path.is_file():
        return None
    try:
        state = torch.load(path, map_location="cpu", weights_only=False)
    except (OSError, RuntimeError, EOFError) as e:
        raise HomesimError(f"{path}: unreadable checkpoint ({e}); delete it to start over"
                           ) from None
    if state.get("config") != config:
        raise HomesimError(f"{path}: a checkpoint of other settings; delete it or use "
                           "another --out folder")
    return state


def _save(path: Path, state: dict[str, Any]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    torch.save(state, tmp)
    tmp.replace(path)


def fit(model: nn.Module, step: EpochStep, *, epochs: int, lr: float, seed: int,
        score: Callable[[], float] | None = None, checkpoint: Path | None = None,
        config: dict[str, Any] | None = None) -> FitResult:
    """Train `model` (on its device) for `epochs` with Adam at `lr`; after each epoch
    score it (higher is better) and save a checkpoint (weights, optimiser, losses, scores,
    the best weights) to `checkpoint`, which a later call with the same `config` resumes.
    The best epoch's weights are loaded back at the end."""
    opt = torch.optim.Adam(model.parameters(), lr=lr)
    result = FitResult(None)
    best: dict[str, Any] | None = None
    state = _load(checkpoint, config or {}) if checkpoint else None
    if state is not None:
        model.load_state_dict(state["model"])
        opt.load_state_dict(state["optimizer"])
        result = FitResult(state["best_epoch"], state["losses"], state["scores"])
        best = state["best"]
    for epoch in range(len(result.losses), epochs):
        model.train()
        torch.manual_seed(epoch_seed(seed, epoch))
        result.losses.append(step(opt, np.random.default_rng(epoch_seed(seed, epoch))))
        if score is not None:
            model.eval()
            result.scores.append(score())
            if result.best_epoch is None or result.scores[-1] > max(result.scores[:-1],
                                                                     default=-np.inf):
                result.best_epoch, best = epoch, copy.deepcopy(model.state_dict())
        if checkpoint is not None:
            _save(checkpoint, {"config": config or {}, "model": model.state_dict(),
                               "optimizer": opt.state_dict(), "losses": result.losses,
                               "scores": result.scores, "best_epoch": result.best_epoch,
                               "best": best})
    if best is not None:
        model.load_state_dict(best)
    model.eval()
    return result


def batches(n: int, size: int, rng: np.random.Generator, min_batch: int = 1
            ) -> list[np.ndarray]:
    """Shuffled index batches of `size` over `n` items (a last one smaller than
    `min_batch` is dropped)."""
    order = rng.permutation(n)
    return [order[i:i + size] for i in range(0, n, size) if len(order[i:i + size]) >= min_batch]


def frame_epoch(opt: torch.optim.Optimizer, rng: np.random.Generator, rows: np.ndarray,
                per_epoch: int, batch_size: int,
                batch_loss: Callable[[np.ndarray], torch.Tensor]) -> float:
    """One epoch of a frame model: `per_epoch` of `rows` drawn (all if fewer), shuffled
    into batches of `batch_size` (each sorted: memory-mapped reads in order), an optimiser
    step on `batch_loss(rows of the batch)` each; the mean loss."""
    drawn = rows if len(rows) <= per_epoch else np.sort(
        rng.choice(rows, per_epoch, replace=False))
    losses = []
    for batch in batches(len(drawn), batch_size, rng, min_batch=2):
        loss = batch_loss(np.sort(drawn[batch]))
        opt.zero_grad()
        loss.backward()
        opt.step()
        losses.append(float(loss.detach()))
    return float(np.mean(losses)) if losses else 0.0


@torch.no_grad()
def over_frames(model: nn.Module, frames: np.ndarray, rows: np.ndarray | None,
                batch_size: int, read: Callable[[torch.Tensor], np.ndarray]
                ) -> list[np.ndarray]:
    """`read(model(batch))` of each batch of `rows` of `frames` (every frame when None),
    in order, the model in eval mode on its device."""
    model.eval()
    device = next(model.parameters()).device
    rows = np.arange(len(frames)) if rows is None else rows
    return [read(model(torch.from_numpy(np.asarray(frames[rows[i:i + batch_size]]))
                       .to(device)))
            for i in range(0, len(rows), batch_size)]
