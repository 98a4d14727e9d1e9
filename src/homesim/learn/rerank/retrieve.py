"""Retrieve-and-edit: the training program with the highest expected LCS, pruned.

For a description x, every training example j gets a weight
w_j = softmax_j(sim(x, j) / tau), where sim mixes the MiniLM cosine of the descriptions
and of the titles (``mix`` * description + (1 - ``mix``) * title). The prediction is the
training program c maximising the expected steps LCS sum_j w_j LCS(c, program_j) (minimum
Bayes risk over the neighbours: tau -> 0 is nearest-neighbour retrieval, uniform weights
within an activity the title-medoid). It is then edited: a step that fewer than
``support`` of the weighted neighbours contain, and whose objects the text does not name,
is dropped. tau, mix and support are chosen on the dev split (`RetrieveEdit.fit`), from
the grid of `RetrieveConfig`.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass, field

import numpy as np

from homesim.learn.data import Example
from homesim.learn.embeddings import example_vectors
from homesim.program.metrics import normalized_lcs, step_tokens
from homesim.program.model import Program


@dataclass(frozen=True)
class RetrieveConfig:
    """The dev grid of `RetrieveEdit.fit`: every (tau, mix, support) is tried."""

    taus: tuple[float, ...] = (0.03, 0.05, 0.1)
    mixes: tuple[float, ...] = (0.3, 0.5, 0.7)
    supports: tuple[float, ...] = (0.0, 0.2, 0.3, 0.4, 0.5)


@dataclass
class RetrieveEdit:
    """A fitted retrieve-and-edit predictor over a training set (module docstring): the
    (tau, mix, support) chosen, and the grid they were chosen from."""

    train: list[Example]
    tau: float = 0.05
    mix: float = 0.5
    support: float = 0.3
    config: RetrieveConfig = field(default_factory=RetrieveConfig)
    _lcs: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self._tokens = [step_tokens(e.program) for e in self.train]
        n = len(self.train)
        self._lcs = np.eye(n)
        for i, j in itertools.combinations(range(n), 2):
            self._lcs[i, j] = self._lcs[j, i] = normalized_lcs(self._tokens[i], self._tokens[j])
        self._desc, self._title = example_vectors(self.train)
        self._presence: dict[tuple, np.ndarray] = {}

    @classmethod
    def fit(cls, train: list[Example], dev: list[Example],
            config: RetrieveConfig | None = None) -> RetrieveEdit:
        """The model with the (tau, mix, support) of the grid (`config`, default
        `RetrieveConfig()`) scoring best on `dev`."""
        grid = config or RetrieveConfig()
        model = cls(train, config=grid)
        best = (-1.0, model.tau, model.mix, model.support)
        for tau, mix, support in itertools.product(grid.taus, grid.mixes, grid.supports):
            model.tau, model.mix, model.support = tau, mix, support
            value = float(np.mean([normalized_lcs(step_tokens(p), step_tokens(e.program))
                                   for p, e in zip(model.predict(dev), dev, strict=True)]))
            best = max(best, (value, tau, mix, support), key=lambda b: b[0])
        _, model.tau, model.mix, model.support = best
        return model

    def weights(self, examples: list[Example]) -> np.ndarray:
        """(examples, train) neighbour weights."""
        desc, title = example_vectors(examples)
        sims = self.mix * (desc @ self._desc.T) + (1 - self.mix) * (title @ self._title.T)
        w = np.exp((sims - sims.max(1, keepdims=True)) / self.tau)
        return w / w.sum(1, keepdims=True)

    def predict(self, examples: list[Example]) -> list[Program]:
        """One edited program per example."""
        if not examples:
            return []
        weights = self.weights(examples)
        best = (weights @ self._lcs).argmax(1)  # expected LCS of each training program
        return [self._edit(self.train[int(c)].program, w, e)
                for c, w, e in zip(best, weights, examples, strict=True)]

    def _edit(self, program: Program, w: np.ndarray, example: Example) -> Program:
        """Drop the steps few neighbours have and the text does not name."""
        if self.support <= 0:
            return program
        words = set(re.findall(r"[a-z]+", example.text.lower()))
        kept = []
        for step, token in zip(program.steps, step_tokens(program), strict=True):
            share = float(w @ self._has(token))
            named = any(set(ref.name.split("_")) <= words for ref in step.args)
            if share >= self.support or named:
                kept.append(step)
        return Program(tuple(kept)) if kept else program


    def _has(self, token: tuple) -> np.ndarray:
        """(train,) 1 where the training program contains the step token."""
        if token not in self._presence:
            self._presence[token] = np.array([token in t for t in self._tokens], dtype=float)
        return self._presence[token]

