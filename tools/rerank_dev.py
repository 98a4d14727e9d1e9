"""The reranker measured without test: 5-fold cross-validation over its training queries and
the dev split, for every real-data run (docs/learn.md, "How it was chosen").

    python tools/rerank_dev.py [--seeds 5] [--vectors out/learn/real/vectors.npz]
                               [--split S] [--without-copies] [--tree-seeds K]

Prints, per split and seed, the mean steps LCS of the top-scoring candidate (no
executability check) in cross-validation (folds by program for the stratified split, by
activity for leave-activities-out, as the split hides them) and on dev, with the dev score
of the baseline the goal is set against on that split, then the means. `--tree-seeds K`
averages each over the trees' `random_state` 0..K-1 (it picks the samples held out for
early stopping, which alone moves dev by about .01; docs/learn.md) and prints dev's range.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from homesim.learn import baselines
from homesim.learn.data import Example
from homesim.learn.experiment import HOLDOUT, RunSpec, load_run_splits
from homesim.learn.likelihood import FOLDS
from homesim.learn.likelihood import folds as fold_of_each
from homesim.learn.rerank import Bank, Query, _labelled, design, fit_trees
from homesim.learn.splits import SPLITS
from homesim.program.metrics import normalized_lcs, step_tokens

Group = tuple[np.ndarray, np.ndarray]


def top_lcs(trees, groups: list[Group]) -> list[float]:
    """The truth's steps LCS of each group's best-scoring candidate."""
    return [float(t[int(np.argmax(trees.predict(design(f))))]) for f, t in groups]


def cross_validated(groups: list[Group], folds: list[int], random_state: int = 0) -> float:
    """Mean top-candidate LCS with each fold scored by trees fitted on the others."""
    out: list[float] = []
    for k in range(FOLDS):
        trees = fit_trees([g for g, f in zip(groups, folds, strict=True) if f != k],
                          random_state)
        out += top_lcs(trees, [g for g, f in zip(groups, folds, strict=True) if f == k])
    return float(np.mean(out))


BASELINE = {"stratified": ("title-medoid", baselines.title_medoid),
            "leave-activities-out": ("NN (description)", baselines.nn_description)}
"""The baseline each split's goal is set against (`report.GOALS`)."""


def training_queries(bank: Bank, split: str, without_copies: bool = False
                     ) -> list[tuple[int, Example, np.ndarray, int]]:
    """(index, example, what it may see of training, cross-validation fold) of each training
    query: folds by program for the stratified split, by activity for leave-activities-out,
    as the split hides them. `without_copies`: only the queries whose program has no copy
    elsewhere in training (as no test program of the stratified split has)."""
    assigned = fold_of_each(bank.train, HOLDOUT[split])
    rows = [(i, e, ~bank.hidden(e, HOLDOUT[split]), assigned[i])
            for i, e in enumerate(bank.train)]
    if without_copies:
        rows = [r for r in rows if bank.hidden(r[1], "program").sum() == 1]
    return rows


def measure(split: str, seed: int, vectors: Path, without_copies: bool = False,
            tree_seeds: int = 1) -> tuple[list[float], list[float], float]:
    """(cross-validated, dev) mean steps LCS of one run (fitted and cross-validated on
    `training_queries`) for each of the trees' `random_state` 0..`tree_seeds`-1, and the
    baseline's dev score."""
    splits = load_run_splits(RunSpec("real", split, seed), vectors)
    bank = Bank(splits.train)
    groups, folds = [], []
    for _, example, allowed, fold in training_queries(bank, split, without_copies):
        query = Query(bank, example, allowed)
        if query.candidates:
            groups.append(_labelled(query))
            folds.append(fold)
    everything = np.ones(len(splits.train), bool)
    dev = [_labelled(Query(bank, e, everything)) for e in splits.dev]
    baseline = BASELINE[split][1](splits.train, splits.dev)
    baseline_dev = np.mean([normalized_lcs(step_tokens(p), step_tokens(e.program))
                            for p, e in zip(baseline, splits.dev, strict=True)])
    return ([cross_validated(groups, folds, r) for r in range(tree_seeds)],
            [float(np.mean(top_lcs(fit_trees(groups, r), dev))) for r in range(tree_seeds)],
            float(baseline_dev))


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
    args = parser.parse_args()
    for split in args.split or SPLITS:
        rows = []
        for seed in range(args.seeds):
            rows.append(measure(split, seed, args.vectors, args.without_copies,
                                args.tree_seeds))
            print(f"{split} seed {seed}: {_line(*rows[-1], split)}", flush=True)
        cv, dev, base = (np.mean([r[k] for r in rows], axis=0) for k in range(3))
        print(f"{split} mean: {_line(list(cv), list(dev), float(base), split)}")


def _line(cv: list[float], dev: list[float], base: float, split: str) -> str:
    """Cross-validated and dev means over tree seeds (dev's range when several)."""
    spread = f" [tree seeds {min(dev):.4f}-{max(dev):.4f}]" if len(dev) > 1 else ""
    return (f"cross-validated {np.mean(cv):.4f}, dev {np.mean(dev):.4f}{spread} "
            f"({BASELINE[split][0]} {base:.4f})")


if __name__ == "__main__":
    main()
