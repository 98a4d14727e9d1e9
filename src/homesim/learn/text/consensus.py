"""Seq2seq + retrieval consensus: minimum-Bayes-risk choice among sampled and retrieved programs.

For a description, the candidates are the seq2seq model's greedy program, ``samples``
programs sampled from it, and the ``neighbours`` training programs with the highest
retrieval weight (`retrieve.RetrieveEdit.weights`: MiniLM similarity of description and
title). The same samples and neighbours serve as pseudo-references, and the prediction is
the candidate with the highest expected steps LCS against them:

    score(c) = beta * mean_s LCS(c, sample_s) + (1 - beta) * sum_k w_k LCS(c, neighbour_k)

with w the retrieval weights of the neighbours (renormalised). Candidates that do not execute
in the example's home (`execution.executable`, checked best-first and only as far as
needed) are passed over while one that does remains, so the choice never trades
executability for LCS. beta is chosen on the dev split (from ``betas``; the three
settings are `ConsensusConfig`'s).
Sampling is seeded: same model, seed and data, same programs.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import torch

from homesim.learn.data import Example
from homesim.learn.execution import executable
from homesim.learn.rerank.retrieve import RetrieveEdit
from homesim.learn.text import decode
from homesim.learn.text.text2prog import Text2Prog
from homesim.program.metrics import normalized_lcs, step_tokens
from homesim.program.model import Program


@dataclass(frozen=True)
class ConsensusConfig:
    """How many candidates and pseudo-references, and the dev grid for beta."""

    samples: int = 20
    """Programs sampled from the seq2seq model."""
    neighbours: int = 10
    """Training programs of highest retrieval weight."""
    betas: tuple[float, ...] = (0.25, 0.5, 0.75)
    """The dev grid for beta (weight of the model's samples against the neighbours)."""


@dataclass
class Pool:
    """One example's candidates and pseudo-references."""

    candidates: list[Program]
    samples: list[list]
    neighbours: list[list]
    weights: np.ndarray
    example: Example
    _runs: dict[int, bool] = field(default_factory=dict)

    def __post_init__(self) -> None:
        tokens = [step_tokens(p) for p in self.candidates]
        self._own = np.array([np.mean([normalized_lcs(c, s) for s in self.samples])
                              for c in tokens])
        self._near = np.array([sum(w * normalized_lcs(c, n)
                                   for w, n in zip(self.weights, self.neighbours, strict=True))
                               for c in tokens])

    def runs(self, i: int) -> bool:
        """Whether candidate i executes in the example's home (checked once)."""
        if i not in self._runs:
            self._runs[i] = executable(self.candidates[i], self.example)
        return self._runs[i]

    def choose(self, beta: float) -> Program:
        """The executable candidate (the best, if none executes) with the best expected LCS."""
        score = beta * self._own + (1 - beta) * self._near
        order = np.argsort(-score, kind="stable")
        chosen = next((int(i) for i in order if self.runs(int(i))), int(order[0]))
        return self.candidates[chosen]


@dataclass
class Consensus:
    """A fitted consensus predictor (module docstring)."""

    t2p: Text2Prog
    retrieval: RetrieveEdit
    seed: int = 0
    beta: float = 0.5
    config: ConsensusConfig = field(default_factory=ConsensusConfig)

    @classmethod
    def fit(cls, t2p: Text2Prog, retrieval: RetrieveEdit, dev: list[Example],
            seed: int = 0, config: ConsensusConfig | None = None) -> Consensus:
        """The predictor with the beta of `config.betas` scoring best on `dev` (steps
        LCS)."""
        model = cls(t2p, retrieval, seed, config=config or ConsensusConfig())
        pools = model.pools(dev)
        truths = [step_tokens(e.program) for e in dev]

        def dev_score(beta: float) -> float:
            return float(np.mean([normalized_lcs(step_tokens(p.choose(beta)), t)
                                  for p, t in zip(pools, truths, strict=True)]))
        model.beta = max(model.config.betas, key=dev_score)
        return model

    @torch.no_grad()
    def pools(self, examples: list[Example]) -> list[Pool]:
        """Candidates and pseudo-references of each example."""
        if not examples:
            return []
        model, steps = self.t2p.model, self.t2p.steps
        model.eval()
        words, mask = self.t2p.batch(examples)
        generator = torch.Generator(device=self.t2p.device).manual_seed(self.seed)
        greedy = decode.greedy(model, words, mask)
        sampled = [decode.sample(model, words, mask, generator)[0]
                   for _ in range(self.config.samples)]
        weights = self.retrieval.weights(examples)
        out = []
        for b, example in enumerate(examples):
            near = np.argsort(-weights[b], kind="stable")[:self.config.neighbours]
            w = weights[b][near] / weights[b][near].sum()
            samples = [steps.decode(s[b]) for s in sampled]
            neighbours = [self.retrieval.train[int(j)].program for j in near]
            candidates = _unique([steps.decode(greedy[b]), *samples, *neighbours])
            out.append(Pool(candidates, [step_tokens(p) for p in samples],
                            [step_tokens(p) for p in neighbours], w, example))
        return out

    def predict(self, examples: list[Example]) -> list[Program]:
        """One program per example."""
        return [pool.choose(self.beta) for pool in self.pools(examples)]


def _unique(programs: list[Program]) -> list[Program]:
    """The programs without repeats (by steps), in order."""
    seen: set[tuple] = set()
    out = []
    for p in programs:
        key = tuple(step_tokens(p))
        if key not in seen:
            seen.add(key)
            out.append(Program(p.steps))
    return out
