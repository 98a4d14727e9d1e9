"""The reranker measured without test: 5-fold cross-validation over its training queries and
the dev split, for every real-data run (docs/learn.md, "How it was chosen").

    python tools/rerank_dev.py [--seeds 5] [--vectors out/learn/real/vectors.npz]
                               [--split S] [--without-copies] [--tree-seeds K]
                               [--train-fraction F]

Prints, per split and seed, the mean steps LCS of the top-scoring candidate (no
executability check) in cross-validation (folds by program for the stratified split, by
activity for leave-activities-out, as the split hides them) and on dev, with the dev score
of the baseline the goal is set against on that split, then the means; also the
cross-validated gap to that baseline (computed for each training query from what it may
see), over all training queries and over those whose program has no copy in training, as
no test program has: the steadiest estimate of the test gap. `--tree-seeds K`
averages each over the trees' `random_state` 0..K-1 (it picks the samples held out for
early stopping, which alone moves dev by about .01; docs/learn.md) and prints dev's range.
`--train-fraction F` keeps a seeded random share F of each run's training programs (the
bank, the training queries and the baseline alike): a learning curve.
"""

from __future__ import annotations

import argparse
import random
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from homesim.learn.data import Example
from homesim.learn.eval import baselines
from homesim.learn.eval.experiment import HOLDOUT, RunSpec, load_run_splits
from homesim.learn.eval.splits import SPLITS
from homesim.learn.rerank.base import Bank, Query, labelled
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.editors import cross_deleted, cross_inserted, fit_editors
from homesim.learn.rerank.folds import Known, fold_knowledge, has_copy
from homesim.learn.rerank.folds import folds as fold_of_each
from homesim.learn.rerank.reranker import Reranker
from homesim.learn.rerank.trees import cross_fitted_best, design, fit_trees
from homesim.program.metrics import normalized_lcs, step_tokens
from homesim.program.model import Program

Group = tuple[np.ndarray, np.ndarray]
CONFIG = RerankConfig()
"""The settings measured: the reranker's defaults, as the table fits it."""


def top_lcs(trees, groups: list[Group]) -> list[float]:
    """The truth's steps LCS of each group's best-scoring candidate."""
    return [float(t[int(np.argmax(trees.predict(design(f))))]) for f, t in groups]


def cross_validated_each(groups: list[Group], folds: list[int], random_state: int = 0
                         ) -> np.ndarray:
    """Each group's top-candidate LCS, its fold scored by trees fitted on the others."""
    best = cross_fitted_best(groups, folds, CONFIG, random_state)
    return np.array([float(t[b]) for (_, t), b in zip(groups, best, strict=True)])


def edited_cross_validated(queries: list[Query], groups: list[Group], folds: list[int],
                           known: list[Known]) -> tuple[np.ndarray, np.ndarray]:
    """Each query's steps LCS after the inserter adds steps to its cross-validated choice
    (the reranker's trees at `random_state` 0), then after the deleter removes some, each
    editor of a fold fitted on the queries of the other folds without a copy in training,
    as `rerank.fit_editors` fits them (the deleter on programs the inserters of their own
    folds wrote)."""
    best = cross_fitted_best(groups, folds, CONFIG)
    learns = [not has_copy(q.bank, q.example) for q in queries]
    written = cross_inserted([(q, known[f], q.candidates[b], f, ok) for q, f, b, ok
                              in zip(queries, folds, best, learns, strict=True)], CONFIG)
    deleted = cross_deleted([(q, known[f], f, ok) for q, f, ok
                             in zip(queries, folds, learns, strict=True)], written, CONFIG)

    def scored(programs: list[Program]) -> np.ndarray:
        return np.array([normalized_lcs(step_tokens(p), step_tokens(q.example.program))
                         for p, q in zip(programs, queries, strict=True)])

    return scored(written), scored(deleted)


BASELINE = {"stratified": ("title-medoid", baselines.title_medoid),
            "leave-activities-out": ("NN (description)", baselines.nn_description)}
"""The baseline each split's goal is set against (`report.GOALS`)."""


def training_queries(bank: Bank, split: str, without_copies: bool = False
                     ) -> list[tuple[int, Example, np.ndarray, int]]:
    """(index, example, what it may see of training, cross-validation fold) of each training
    query: folds by program for the stratified split, by activity for leave-activities-out,
    as the split hides them. `without_copies`: only the queries whose program has no copy
    elsewhere in training (as no test program of the stratified split has)."""
    assigned = fold_of_each(bank.train, HOLDOUT[split], CONFIG.folds)
    rows = [(i, e, ~bank.hidden(e, HOLDOUT[split]), assigned[i])
            for i, e in enumerate(bank.train)]
    if without_copies:
        rows = [r for r in rows if not has_copy(bank, r[1])]
    return rows


def baseline_on_query(query: Query, split: str) -> float:
    """The steps LCS of the split's baseline for a training query, from what it may see:
    the medoid of its activity's programs (stratified; NaN if it may see none of them) or
    the program of the nearest description (leave-activities-out). The same choices as
    `baselines.title_medoid` and `baselines.nn_description` (checked on dev, where a query
    sees all of training), from the bank's stored LCS instead of recomputing them."""
    bank, truth = query.bank, step_tokens(query.example.program)
    if split == "stratified":
        same = query.activity_programs()
        if not len(same):
            return float("nan")
        choice = bank.medoid(same)
    else:
        choice = int(np.argmax(np.where(query.allowed, bank.desc @ query.desc, -np.inf)))
    return normalized_lcs(bank.tokens[choice], truth)


@dataclass
class Measured:
    """One run's figures, one entry per tree seed where a list."""

    cv: list[float]
    dev: list[float]
    baseline_dev: float
    cv_gap: list[float]
    """Cross-validated gap to the baseline on the training queries."""
    cv_alone: list[float]
    """The cross-validated score over the queries whose program has no copy in training,
    as test's (where the baseline has one)."""
    baseline_alone: float
    """The baseline's score over the same queries."""
    inserted_alone: float
    """`cv_alone` with the inserter's steps added (trees' random_state 0)."""
    inserted_dev: float
    """The dev score with them (same)."""
    deleted_alone: float
    """`inserted_alone` after the deleter's deletions (the reranker as the table scores it,
    less the executability check)."""
    deleted_dev: float
    """The dev score of the reranker as fitted: with them where `fit_editors` kept its
    deleter (the cross-validated deletions raised the training queries' LCS), else the
    inserted steps' score."""
    deleter_kept: float
    """1 when `fit_editors` kept the deleter, else 0 (over seeds: the share)."""

    @property
    def cv_gap_alone(self) -> list[float]:
        """The cross-validated gap to the baseline over those queries."""
        return [c - self.baseline_alone for c in self.cv_alone]


def subsample(train: list[Example], fraction: float, seed: int) -> list[Example]:
    """A random share `fraction` of `train` (seeded by `seed`), in its order."""
    if fraction >= 1:
        return train
    kept = random.Random(seed).sample(range(len(train)), round(fraction * len(train)))
    return [train[i] for i in sorted(kept)]


def measure(split: str, seed: int, vectors: Path, without_copies: bool = False,
            tree_seeds: int = 1, train_fraction: float = 1.0) -> Measured:
    """Cross-validated (on `training_queries`) and dev steps LCS of one run for each of the
    trees' `random_state` 0..`tree_seeds`-1, the baseline's dev score, and the
    cross-validated gap to the baseline; training cut to `train_fraction` (`subsample`)."""
    splits = load_run_splits(RunSpec("real", split, seed), vectors)
    train = subsample(splits.train, train_fraction, seed)
    bank = Bank(train, CONFIG)
    groups, folds, base, alone, queries, indexed = [], [], [], [], [], []
    for i, example, allowed, fold in training_queries(bank, split, without_copies):
        query = Query(bank, example, allowed)
        if query.candidates:
            groups.append(labelled(query))
            folds.append(fold)
            base.append(baseline_on_query(query, split))
            alone.append(not has_copy(bank, example))
            queries.append(query)
            indexed.append((i, query))
    everything = np.ones(len(train), bool)
    dev_queries = [Query(bank, e, everything) for e in splits.dev]
    dev = [labelled(q) for q in dev_queries]
    known = fold_knowledge(train, HOLDOUT[split], CONFIG)[1]
    inserted, deleted = edited_cross_validated(queries, groups, folds, known)
    model = Reranker(bank, fit_trees(groups, CONFIG), *fit_editors(bank, HOLDOUT[split], indexed,
                                                           groups, True))
    dev_inserted, dev_deleted = [], []
    for q, (f, _) in zip(dev_queries, dev, strict=True):
        chosen = q.candidates[int(np.argmax(model.trees.predict(design(f))))].program
        edits = model.edits(q, chosen)
        truth = step_tokens(q.example.program)
        dev_deleted.append(normalized_lcs(step_tokens(edits[0]), truth))
        dev_inserted.append(normalized_lcs(step_tokens(edits[-1]), truth))
    baseline = BASELINE[split][1](train, splits.dev)
    baseline_dev = np.mean([normalized_lcs(step_tokens(p), step_tokens(e.program))
                            for p, e in zip(baseline, splits.dev, strict=True)])
    each = [cross_validated_each(groups, folds, r) for r in range(tree_seeds)]
    base_lcs = np.array(base)
    scored_alone = np.array(alone) & ~np.isnan(base_lcs)
    return Measured([float(e.mean()) for e in each],
                    [float(np.mean(top_lcs(fit_trees(groups, CONFIG, r), dev)))
                     for r in range(tree_seeds)],
                    float(baseline_dev), [float(np.nanmean(e - base_lcs)) for e in each],
                    [float(e[scored_alone].mean()) for e in each],
                    float(base_lcs[scored_alone].mean()), float(inserted[scored_alone].mean()),
                    float(np.mean(dev_inserted)), float(deleted[scored_alone].mean()),
                    float(np.mean(dev_deleted)), float(model.deleter is not None))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--vectors", type=Path, default=Path("out/learn/real/vectors.npz"))
    parser.add_argument("--split", choices=SPLITS, action="append",
                        help="Only this split (repeatable; default: both).")
    parser.add_argument("--without-copies", action="store_true",
                        help="Fit and cross-validate on only the training queries whose "
                             "program has no copy elsewhere in training.")
    parser.add_argument("--tree-seeds", type=int, default=1,
                        help="Average over the trees' random_state 0..K-1 (default 1: the "
                             "reranker's own, 0).")
    parser.add_argument("--train-fraction", type=float, default=1.0,
                        help="Keep this seeded random share of the training programs "
                             "(default 1: all).")
    args = parser.parse_args()
    for split in args.split or SPLITS:
        rows = []
        for seed in range(args.seeds):
            rows.append(measure(split, seed, args.vectors, args.without_copies,
                                args.tree_seeds, args.train_fraction))
            print(f"{split} seed {seed}: {_line(rows[-1], split)}", flush=True)
        print(f"{split} mean: {_line(mean_of(rows), split)}")


def mean_of(rows: list[Measured]) -> Measured:
    """The seeds' means, field by field (per tree seed where a list)."""
    def lists(name: str) -> list[float]:
        return [float(v) for v in np.mean([getattr(r, name) for r in rows], axis=0)]

    def floats(name: str) -> float:
        return float(np.mean([getattr(r, name) for r in rows]))

    return Measured(lists("cv"), lists("dev"), floats("baseline_dev"), lists("cv_gap"),
                    lists("cv_alone"), floats("baseline_alone"), floats("inserted_alone"),
                    floats("inserted_dev"), floats("deleted_alone"), floats("deleted_dev"),
                    floats("deleter_kept"))


def _line(m: Measured, split: str) -> str:
    """Means over tree seeds (dev's range when several)."""
    spread = f" [tree seeds {min(m.dev):.4f}-{max(m.dev):.4f}]" if len(m.dev) > 1 else ""
    name = BASELINE[split][0]
    return (f"cross-validated {np.mean(m.cv):.4f} (gap to {name} {np.mean(m.cv_gap):+.4f}, "
            f"without copies {np.mean(m.cv_gap_alone):+.4f}: {np.mean(m.cv_alone):.4f} "
            f"against {m.baseline_alone:.4f}), dev {np.mean(m.dev):.4f}"
            f"{spread} ({name} {m.baseline_dev:.4f}); with the inserted steps: without "
            f"copies {m.inserted_alone:.4f} (gap {m.inserted_alone - m.baseline_alone:+.4f}), "
            f"dev {m.inserted_dev:.4f}; and then the deleted ones: without copies "
            f"{m.deleted_alone:.4f} (gap {m.deleted_alone - m.baseline_alone:+.4f}), "
            f"dev {m.deleted_dev:.4f} (deleter kept in {m.deleter_kept:.0%} of the fits)")


if __name__ == "__main__":
    main()
