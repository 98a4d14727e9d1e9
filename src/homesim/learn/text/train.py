"""Training: MLE with teacher forcing, then self-critical policy gradient.

Policy gradient (Rennie et al.'s self-critical form, as in the paper): for each description
sample a program and decode the greedy one; the loss is -(r(sample) - r(greedy)) times the
sample's log-probability, with r = LCS(steps) [+ `TrainConfig.sim_weight` (0.1) if it executes
in the example's home].
"""

from __future__ import annotations

import copy
import random
from collections.abc import Callable
from dataclasses import dataclass

import torch

from homesim.learn.data import Example
from homesim.learn.execution import executable
from homesim.learn.text import decode
from homesim.learn.text.text2prog import Text2Prog
from homesim.program.metrics import lcs_steps
from homesim.program.model import Program

Progress = Callable[[int, int, float], None]
"""Called after each batch with (batches done, batches in all, running loss)."""
EpochHook = Callable[[int], None]
"""Called after each epoch with its 0-based number (e.g. to keep the best weights)."""


@dataclass
class TrainConfig:
    """How to train; saved in the checkpoint's meta."""

    epochs: int = 10
    batch_size: int = 32
    lr: float = 2e-3
    seed: int = 0
    clip: float = 5.0
    sim_weight: float = 0.1
    """The policy-gradient reward's bonus when the program executes (`reward`)."""


def _targets(t2p: Text2Prog, examples: list[Example]) -> torch.Tensor:
    seqs = [t2p.steps.encode(e.program) or [] for e in examples]
    width = max(len(s) for s in seqs)
    out = torch.full((len(seqs), width), -100, dtype=torch.long)
    for i, s in enumerate(seqs):
        out[i, :len(s)] = torch.tensor(s)
    return out.to(t2p.device)


def _batches(examples: list[Example], size: int, rng: random.Random) -> list[list[Example]]:
    order = list(examples)
    rng.shuffle(order)
    return [order[i:i + size] for i in range(0, len(order), size)]


def train_mle(t2p: Text2Prog, train: list[Example], config: TrainConfig,
              progress: Progress | None = None, after_epoch: EpochHook | None = None
              ) -> list[float]:
    """Teacher-forced cross-entropy; returns the mean loss of each epoch."""
    usable = [e for e in train if t2p.steps.encode(e.program) is not None]
    rng = random.Random(config.seed)
    torch.manual_seed(config.seed)
    opt = torch.optim.Adam(t2p.model.parameters(), lr=config.lr)
    history = []
    total = config.epochs * -(-len(usable) // config.batch_size)
    done = 0
    for _ in range(config.epochs):
        t2p.model.train()
        losses = []
        for chunk in _batches(usable, config.batch_size, rng):
            words, mask = t2p.batch(chunk)
            loss = t2p.model(words, mask, _targets(t2p, chunk))
            _update(opt, t2p, loss, config.clip)
            losses.append(loss.item())
            done += 1
            if progress:
                progress(done, total, sum(losses) / len(losses))
        history.append(sum(losses) / len(losses))
        if after_epoch:
            after_epoch(len(history) - 1)
    return history


def _update(opt: torch.optim.Optimizer, t2p: Text2Prog, loss: torch.Tensor,
            clip: float) -> None:
    """One optimiser step on `loss`, with the gradient norm clipped to `clip`."""
    opt.zero_grad()
    loss.backward()
    torch.nn.utils.clip_grad_norm_(t2p.model.parameters(), clip)
    opt.step()


def reward(pred: Program, example: Example, use_sim: bool,
           sim_weight: float = TrainConfig.sim_weight) -> float:
    """LCS of steps with the truth, plus `sim_weight` when `use_sim` and the program
    executes."""
    r = lcs_steps(pred, example.program)
    if use_sim and executable(pred, example):
        r += sim_weight
    return r


def train_pg(t2p: Text2Prog, train: list[Example], config: TrainConfig, use_sim: bool,
             progress: Progress | None = None, after_epoch: EpochHook | None = None
             ) -> list[float]:
    """Self-critical policy gradient from the current weights; returns mean sample reward
    of each epoch."""
    rng = random.Random(config.seed)
    torch.manual_seed(config.seed)  # dropout draws from the global RNG: not from what ran before
    gen = torch.Generator(device=t2p.device).manual_seed(config.seed)
    opt = torch.optim.Adam(t2p.model.parameters(), lr=config.lr)
    history = []
    total = config.epochs * -(-len(train) // config.batch_size)
    done = 0
    for _ in range(config.epochs):
        rewards = []
        for chunk in _batches(train, config.batch_size, rng):
            words, mask = t2p.batch(chunk)
            t2p.model.eval()
            with torch.no_grad():
                base_ids = decode.greedy(t2p.model, words, mask)
            t2p.model.train()
            ids, logp = decode.sample(t2p.model, words, mask, gen)
            r_s = torch.tensor([reward(t2p.steps.decode(p), e, use_sim, config.sim_weight)
                                for p, e in zip(ids, chunk, strict=True)], device=t2p.device)
            r_g = torch.tensor([reward(t2p.steps.decode(p), e, use_sim, config.sim_weight)
                                for p, e in zip(base_ids, chunk, strict=True)],
                               device=t2p.device)
            loss = -((r_s - r_g) * logp).mean()
            _update(opt, t2p, loss, config.clip)
            rewards.extend(r_s.tolist())
            done += 1
            if progress:
                progress(done, total, sum(rewards) / len(rewards))
        history.append(sum(rewards) / len(rewards))
        if after_epoch:
            after_epoch(len(history) - 1)
    return history


class BestOnDev:
    """An epoch hook that keeps the weights scoring best on the dev split.

    The score is the mean reward of greedy programs: steps LCS, plus the simulator bonus
    when `use_sim` (the quantity the model is trained for).
    """

    def __init__(self, t2p: Text2Prog, dev: list[Example], use_sim: bool = False,
                 sim_weight: float = TrainConfig.sim_weight):
        self.t2p, self.dev, self.use_sim, self.sim_weight = t2p, dev, use_sim, sim_weight
        self.best = float("-inf")
        self.epoch: int | None = None
        self.scores: list[float] = []
        self._state: dict | None = None

    def __call__(self, epoch: int) -> None:
        preds = self.t2p.predict(self.dev)
        value = sum(reward(p, e, self.use_sim, self.sim_weight)
                    for p, e in zip(preds, self.dev, strict=True))
        value /= max(1, len(self.dev))
        self.scores.append(value)
        if value > self.best:
            self.best, self.epoch = value, epoch
            self._state = copy.deepcopy(self.t2p.model.state_dict())

    def restore(self) -> None:
        """Load the best weights back into the model (if any epoch was scored)."""
        if self._state is not None:
            self.t2p.model.load_state_dict(self._state)
