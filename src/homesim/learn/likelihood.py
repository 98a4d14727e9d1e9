"""The MLE model's likelihood of candidate programs, as features for the reranker.

For a description and candidate programs, `likelihoods` gives three columns (`FEATURES`):
the teacher-forced log-likelihood of each candidate's steps and its end under a `Text2Prog`
model reading the description, its mean per step, and the share of its steps outside the
model's step vocabulary (each counted at `UNKNOWN_LOGP`).

The reranker's trees learn from training queries, so their likelihoods must come from
models that never read the query's program: `CrossFitted` trains one model per fold of the
training set (`folds`: round robin, or by activity when the split hides whole activities),
each without its fold's programs and every copy of them, and one model on all of training
for new descriptions. docs/learn.md gives what the features gained (on dev, not on test:
``tools/likelihood_probe.py``) and so why the table's reranker does not use them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from homesim.learn.data import Example
from homesim.program.metrics import step_tokens
from homesim.program.model import Program

if TYPE_CHECKING:
    from homesim.learn.text2prog import Text2Prog

FOLDS = 5
UNKNOWN_LOGP = -12.0
"""Log-probability counted for a step the model cannot emit."""
FEATURES = ("log-likelihood", "mean log-likelihood", "unknown steps")


def folds(train: list[Example], holdout: str) -> list[int]:
    """The fold of each training example: round robin, or by activity when `holdout` is
    "activity" (a fold then holds whole activities)."""
    if holdout == "activity":
        activities = sorted({e.activity for e in train})
        return [activities.index(e.activity) % FOLDS for e in train]
    return [i % FOLDS for i in range(len(train))]


def trained(examples: list[Example], seed: int) -> Text2Prog:
    """A fresh MLE model trained on `examples` with the table's epochs, batch and learning
    rate (`experiment.RunSpec`'s; no dev selection), in eval mode."""
    from homesim.learn.experiment import RunSpec
    from homesim.learn.text2prog import Text2Prog
    from homesim.learn.train import TrainConfig, train_mle

    t2p = Text2Prog.create(examples, seed)
    train_mle(t2p, examples, TrainConfig(RunSpec.mle_epochs, RunSpec.batch_size,
                                         RunSpec.mle_lr, seed))
    t2p.model.eval()
    return t2p


def likelihoods(t2p: Text2Prog, example: Example, programs: list[Program]) -> np.ndarray:
    """(programs, 3) `FEATURES` of each program for the example's title and description."""
    import torch
    import torch.nn.functional as F

    from homesim.learn.vocab import END, step_key

    model = t2p.model
    ids = [[t2p.steps.index.get(step_key(s)) for s in p.steps] + [END] for p in programs]
    total, unknown = np.zeros(len(ids)), np.zeros(len(ids))
    with torch.no_grad():
        words, mask = t2p.batch([example])
        state = model.encode(words.expand(len(ids), -1), mask.expand(len(ids), -1))
        steps = model.step_embeddings()
        prev = None
        for t in range(max(len(i) for i in ids)):
            logits, state = model.decode_step(state, prev, steps)
            logp = F.log_softmax(logits, 1).cpu().numpy()
            gold = [i[t] if t < len(i) else END for i in ids]
            for b, g in enumerate(gold):
                if t < len(ids[b]):
                    total[b] += UNKNOWN_LOGP if g is None else logp[b, g]
                    unknown[b] += g is None
            prev = torch.tensor([END if g is None else g for g in gold], device=logits.device)
    lengths = np.array([len(i) for i in ids], dtype=float)
    return np.stack([total, total / lengths, unknown / lengths], 1)


@dataclass
class CrossFitted:
    """Models for the likelihoods: `models[k]` for training queries of fold `k` (trained
    without that fold), `full` for every other description."""

    folds: list[int]
    models: dict[int, Text2Prog]
    full: Text2Prog

    @classmethod
    def fit(cls, train: list[Example], holdout: str, seed: int = 0) -> CrossFitted:
        """Fold models and the full model for `train`, hiding what `holdout` hides."""
        assigned = folds(train, holdout)
        models = {k: trained(_without_fold(train, assigned, k), seed)
                  for k in sorted(set(assigned))}
        return cls(assigned, models, trained(train, seed))

    def for_training_query(self, index: int) -> Text2Prog:
        """The model that scores training example `index` as a query."""
        return self.models[self.folds[index]]


def _without_fold(train: list[Example], assigned: list[int], k: int) -> list[Example]:
    """Training without fold `k`'s examples, the copies of their programs and (when folds
    hold whole activities) their activities."""
    held = [e for e, f in zip(train, assigned, strict=True) if f == k]
    programs = {tuple(step_tokens(e.program)) for e in held}
    return [e for e, f in zip(train, assigned, strict=True)
            if f != k and tuple(step_tokens(e.program)) not in programs]
