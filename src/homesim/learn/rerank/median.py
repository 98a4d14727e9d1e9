"""Generalised median programs: the step sequence of highest weighted expected steps LCS to a
set of reference programs, found by greedy local search.

The medoid (the reference closest to the others) can only return a program someone wrote;
the median may also insert a step many references share or delete one few do. Under the
steps LCS divided by the longer sequence, that pays: on the stratified split's training
queries the median of the title's activity scores about .017 above its medoid
(docs/learn.md). LCS lengths are computed bit-parallel (one machine-word operation per
step of the candidate), and a search iteration scores all its moves at once from prefix and
suffix LCS tables (`Medians.move_scores`), so a search takes milliseconds.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from dataclasses import dataclass

import numpy as np

from homesim.program.metrics import step_tokens
from homesim.program.model import Program, Step


@dataclass(frozen=True)
class MedianConfig:
    """How far the median search looks (part of the reranker's `config.RerankConfig`)."""

    vocab: int = 10
    """Insertions try the steps of this many highest-weighted-support tokens."""
    iters: int = 12
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


def uniform_median(programs: Sequence[Program], start: Program,
                   config: MedianConfig = MedianConfig()) -> Program:
    """The median of `programs` weighted alike (a title's activity), searched from `start`
    (their medoid)."""
    return Medians(programs, np.ones(len(programs)), config).median(start)


class Medians:
    """Reference programs, weighted, against which sequences are scored and searched."""

    def __init__(self, references: Sequence[Program], weights: np.ndarray,
                 config: MedianConfig = MedianConfig()) -> None:
        self.config = config
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
        self.vocab = [int(c) for c in order[:config.vocab] if support[c] > 0]
        fits = all(len(r) < 64 for r in refs)
        self._tables = _Tables(refs) if fits and refs else None

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
        """Greedy local search from `start`: at each of up to `config.iters` moves, the
        single-step deletion or insertion (of a `vocab` step, anywhere) that raises
        `expected_lcs` most; stops when none does. Ties go to the first move tried."""
        if not self.weights:
            return start
        current = self.encode(start)
        best = self.expected_lcs(current)
        for _ in range(self.config.iters):
            scores = self.move_scores(current)
            if not len(scores) or float(np.max(scores)) <= best + 1e-12:
                break
            k = int(np.argmax(scores))
            current, best = self.move(current, k), float(scores[k])
        return self.decode(start, current)

    def move(self, current: list[int], k: int) -> list[int]:
        """`moves(current)[k]`, built alone."""
        deletions = len(current) if len(current) > 1 else 0
        if k < deletions:
            return current[:k] + current[k + 1:]
        symbol, i = divmod(k - deletions, len(current) + 1)
        return [*current[:i], self.vocab[symbol], *current[i:]]

    def moves(self, current: list[int]) -> list[list[int]]:
        """The search's moves from `current`, in order: each single-step deletion (when more
        than one step is left), then each `vocab` symbol inserted at each position."""
        moves = [current[:i] + current[i + 1:] for i in range(len(current))
                 ] if len(current) > 1 else []
        return moves + [[*current[:i], s, *current[i:]] for s in self.vocab
                        for i in range(len(current) + 1)]

    def move_scores(self, current: list[int]) -> np.ndarray:
        """`expected_lcs` of each of `moves(current)`, the same floats: all at once from
        prefix and suffix LCS tables (`_Tables`) when every reference fits a 64-bit row,
        else one by one."""
        if self._tables is None:
            return np.array([self.expected_lcs(m) for m in self.moves(current)])
        n = len(current)
        lengths, per_move = self._tables.move_lcs(current, self.vocab, deletions=n > 1)
        total = np.zeros(len(lengths))
        for r, weight in enumerate(self.weights):  # the order expected_lcs adds them in
            longer = np.maximum(lengths, self._tables.lengths[r])
            total += weight * (per_move[:, r] / longer)
        return total


class _Tables:
    """The references as 64-bit bit-parallel LCS rows, scoring every single-step move of a
    sequence at once: with P[i, r, j] = LCS(sequence[:i], ref_r[:j]) and S[i, r, j] =
    LCS(sequence[i:], ref_r[j:]) (the zero bits of the rows after each prefix, forwards and
    backwards), deleting step i gives max_j P[i, r, j] + S[i + 1, r, j], and inserting
    symbol s at i gives the larger of the whole LCS and 1 + P[i, r, k] + S[i, r, k + 1] over
    the positions k where ref_r holds s."""

    def __init__(self, refs: list[list[int]]) -> None:
        self.lengths = np.array([len(r) for r in refs], dtype=np.int64)
        width = int(self.lengths.max(initial=0))
        self.symbols = np.full((len(refs), max(width, 1)), -1, dtype=np.int64)
        for r, ref in enumerate(refs):
            self.symbols[r, :len(ref)] = ref
        self.full = np.array([(1 << len(r)) - 1 for r in refs], dtype=np.uint64)
        self.forward = [position_masks(r) for r in refs]
        self.backward = [position_masks(r[::-1]) for r in refs]
        self.bits = np.arange(self.symbols.shape[1], dtype=np.uint64)
        self._valid = np.arange(self.symbols.shape[1] + 1) <= self.lengths[:, None]

    def _masks(self, masks: list[dict[int, int]], symbol: int) -> np.ndarray:
        return np.array([m.get(symbol, 0) for m in masks], dtype=np.uint64)

    def _zeros(self, sequence: list[int], masks: list[dict[int, int]]) -> np.ndarray:
        """(len(sequence) + 1, refs, width + 1): zero bits among the lowest j of each
        reference's row after each prefix of `sequence`."""
        row = self.full.copy()
        rows = [row]
        for symbol in sequence:
            matched = row & self._masks(masks, symbol)
            row = ((row + matched) | (row - matched)) & self.full
            rows.append(row)
        ones = (np.stack(rows)[:, :, None] >> self.bits) & np.uint64(1)
        zeros = np.cumsum(1 - ones.astype(np.int64), axis=2)
        return np.concatenate([np.zeros((*zeros.shape[:2], 1), np.int64), zeros], axis=2)

    def move_lcs(self, sequence: list[int], vocab: list[int], deletions: bool
                 ) -> tuple[np.ndarray, np.ndarray]:
        """(moves,) lengths and (moves, refs) LCS lengths of `Medians.moves`, in its order."""
        n, width = len(sequence), self.symbols.shape[1]
        prefix = self._zeros(sequence, self.forward)
        back = self._zeros(sequence[::-1], self.backward)
        # suffix[i, r, j] = back[n - i, r, length_r - j] (j beyond length_r: masked below)
        flip = np.clip(self.lengths[:, None] - np.arange(width + 1), 0, None)
        suffix = np.take_along_axis(back[::-1], np.broadcast_to(flip, (n + 1, *flip.shape)),
                                    axis=2)
        lost = np.iinfo(np.int64).min // 4
        whole = prefix[n, np.arange(len(self.lengths)), self.lengths]
        out, lengths = [], []
        if deletions:
            split = np.where(self._valid, prefix[:-1] + suffix[1:], lost)
            out.append(split.max(axis=2))
            lengths += [n - 1] * n
        matched = prefix[:, :, :width] + suffix[:, :, 1:]
        for symbol in vocab:
            here = np.where(self.symbols == symbol, matched, lost).max(axis=2)
            out.append(np.maximum(whole, 1 + here))
            lengths += [n + 1] * (n + 1)
        if not out:
            return np.zeros(0, np.int64), np.zeros((0, len(self.lengths)), np.int64)
        return np.array(lengths, dtype=np.int64), np.concatenate(out)
