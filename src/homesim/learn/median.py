"""Generalised median programs: the step sequence of highest weighted expected steps LCS to a
set of reference programs, found by greedy local search.

The medoid (the reference closest to the others) can only return a program someone wrote;
the median may also insert a step many references share or delete one few do. Under the
steps LCS divided by the longer sequence, that pays: on the stratified split's training
queries the median of the title's activity scores about .017 above its medoid
(docs/learn.md). LCS lengths are computed bit-parallel (one machine-word operation per
step of the candidate), so a search scores thousands of candidate sequences in well under a
second.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence

import numpy as np

from homesim.program.metrics import step_tokens
from homesim.program.model import Program, Step

MEDIAN_VOCAB = 10
"""Insertions try the steps of this many highest-weighted-support tokens."""
MEDIAN_ITERS = 12
"""Improving moves made at most."""


def position_masks(sequence: Sequence[int]) -> dict[int, int]:
    """Symbol -> bitmask of the positions where `sequence` holds it."""
    masks: dict[int, int] = {}
    for i, symbol in enumerate(sequence):
        masks[symbol] = masks.get(symbol, 0) | (1 << i)
    return masks


def lcs_length(sequence: Sequence[int], masks: dict[int, int], length: int) -> int:
    """Length of the longest common subsequence of `sequence` and the sequence of `length`
    symbols whose `position_masks` are `masks` (bit-parallel, one pass over `sequence`)."""
    full = (1 << length) - 1
    row = full
    for symbol in sequence:
        matched = row & masks.get(symbol, 0)
        row = ((row + matched) | (row - matched)) & full
    return length - row.bit_count()


def uniform_median(programs: Sequence[Program], start: Program) -> Program:
    """The median of `programs` weighted alike (a title's activity), searched from `start`
    (their medoid)."""
    return Medians(programs, np.ones(len(programs))).median(start)


class Medians:
    """Reference programs, weighted, against which sequences are scored and searched."""

    def __init__(self, references: Sequence[Program], weights: np.ndarray) -> None:
        self.codes: dict[Hashable, int] = {}
        self.steps: list[Step] = []
        refs = [self.encode(p) for p in references]
        self.refs = [(position_masks(r), len(r)) for r in refs]
        total = float(np.sum(weights))
        self.weights = [float(w) / total for w in weights] if total > 0 else []
        support = np.zeros(len(self.steps))
        for r, w in zip(refs, self.weights, strict=True):
            support[sorted(set(r))] += w
        order = np.argsort(-support, kind="stable")
        self.vocab = [int(c) for c in order[:MEDIAN_VOCAB] if support[c] > 0]

    def encode(self, program: Program) -> list[int]:
        """The program's step tokens as symbols (new ones numbered in order of appearance)."""
        return [self._code(token, step)
                for token, step in zip(step_tokens(program), program.steps, strict=True)]

    def _code(self, token: Hashable, step: Step) -> int:
        if token not in self.codes:
            self.codes[token] = len(self.steps)
            self.steps.append(step)
        return self.codes[token]

    def symbol(self, step: Step) -> int:
        """One step as a symbol."""
        return self._code(step_tokens(Program((step,)))[0], step)

    def decode(self, program: Program, sequence: Sequence[int]) -> Program:
        """`program` with the steps of `sequence` (symbols of this object)."""
        return program.with_steps([self.steps[c] for c in sequence])

    def best_insertion(self, sequence: list[int], symbol: int) -> list[int]:
        """`sequence` with `symbol` inserted where `expected_lcs` is highest (ties:
        earliest)."""
        options = [[*sequence[:i], symbol, *sequence[i:]] for i in range(len(sequence) + 1)]
        return options[int(np.argmax([self.expected_lcs(o) for o in options]))]

    def expected_lcs(self, sequence: Sequence[int]) -> float:
        """Weighted mean of the steps LCS (over the longer length) to the references."""
        total = 0.0
        for (masks, length), weight in zip(self.refs, self.weights, strict=True):
            longer = max(len(sequence), length)
            total += weight * (lcs_length(sequence, masks, length) / longer if longer else 1.0)
        return total

    def median(self, start: Program) -> Program:
        """Greedy local search from `start`: at each of up to `MEDIAN_ITERS` moves, the
        single-step deletion or insertion (of a `vocab` step, anywhere) that raises
        `expected_lcs` most; stops when none does. Ties go to the first move tried."""
        if not self.weights:
            return start
        current = self.encode(start)
        best = self.expected_lcs(current)
        for _ in range(MEDIAN_ITERS):
            moves = [current[:i] + current[i + 1:] for i in range(len(current))
                     ] if len(current) > 1 else []
            moves += [[*current[:i], s, *current[i:]] for s in self.vocab
                      for i in range(len(current) + 1)]
            scores = [self.expected_lcs(m) for m in moves]
            if not scores or max(scores) <= best + 1e-12:
                break
            k = int(np.argmax(scores))
            current, best = moves[k], scores[k]
        return self.decode(start, current)
