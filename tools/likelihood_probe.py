"""The MLE model's likelihood of each candidate as reranker features, measured on dev
(docs/learn.md, "Measured on dev and once on test, not kept"): the cross-validated and
dev figures of `tools/rerank_dev.py` with and without three more features per candidate;
with --test, the one test measurement made after that choice.

    python tools/likelihood_probe.py [--seeds 5] [--split stratified] [--test]

The features (`homesim.learn.likelihood`) are the teacher-forced log-likelihood of the
candidate's steps (its end included) under an MLE model given the description: the total,
the mean per step, and the share of its steps the model cannot emit. A training query is
scored by a model trained without its fold (and every copy of the fold's programs;
leave-activities-out: without the fold's activities), so that no query's likelihood comes
from a model that read its program; dev by a model trained on all of training
(`CrossFitted`, as `Reranker.fit(..., likelihood=True)` fits them).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import torch

from homesim.learn.experiment import HOLDOUT, RunSpec, load_run_splits
from homesim.learn.likelihood import CrossFitted
from homesim.learn.rerank import Bank, Query, Reranker, _labelled, _with_likelihoods, fit_trees
from homesim.learn.summary import summarize, summarize_gap
from homesim.program.metrics import normalized_lcs, step_tokens
from rerank_dev import BASELINE, cross_validated, top_lcs, training_queries

Group = tuple[np.ndarray, np.ndarray]


def measure(split: str, seed: int, vectors: Path) -> tuple[float, float, float, float]:
    """(CV, dev) without and with the likelihood features, for one run."""
    splits = load_run_splits(RunSpec("real", split, seed), vectors)
    bank = Bank(splits.train)
    fitted = CrossFitted.fit(splits.train, HOLDOUT[split], seed)
    base: list[Group] = []
    extended: list[Group] = []
    folds: list[int] = []
    for i, example, allowed, fold in training_queries(bank, split):
        query = Query(bank, example, allowed)
        if query.candidates:
            features, targets = _labelled(query)
            base.append((features, targets))
            extended.append((_with_likelihoods(features, query, fitted.for_training_query(i)),
                             targets))
            folds.append(fold)
    everything = np.ones(len(splits.train), bool)
    dev = [Query(bank, e, everything) for e in splits.dev]
    base_dev = [_labelled(q) for q in dev]
    extended_dev = [(_with_likelihoods(f, q, fitted.full), t)
                    for q, (f, t) in zip(dev, base_dev, strict=True)]
    return (cross_validated(base, folds), float(np.mean(top_lcs(fit_trees(base), base_dev))),
            cross_validated(extended, folds),
            float(np.mean(top_lcs(fit_trees(extended), extended_dev))))


def on_test(split: str, seeds: int, vectors: Path) -> None:
    """The one test measurement: `Reranker.fit(..., likelihood=True).predict` (executability
    checked, as the table's row) against the split's baseline, over the seeds, summarised
    as the table summarises a gap (`learn.summary`)."""
    baseline = BASELINE[split][1]
    ours: list[list[dict]] = []
    theirs: list[list[dict]] = []
    for seed in range(seeds):
        splits = load_run_splits(RunSpec("real", split, seed), vectors)
        model = Reranker.fit(splits.train, HOLDOUT[split], likelihood=True, seed=seed)
        for programs, out in ((model.predict(splits.test), ours),
                              (baseline(splits.train, splits.test), theirs)):
            out.append([{"steps": normalized_lcs(step_tokens(p), step_tokens(e.program))}
                        for p, e in zip(programs, splits.test, strict=True)])
        print(f"{split} seed {seed}: test {np.mean([r['steps'] for r in ours[-1]]):.4f}, "
              f"{BASELINE[split][0]} {np.mean([r['steps'] for r in theirs[-1]]):.4f}", flush=True)
    row, gap = summarize(ours, "steps"), summarize_gap(ours, theirs, "steps")
    print(f"{split} test: {row['mean']:.4f} ± {row['sd']:.4f} [{row['lo']:.4f}, "
          f"{row['hi']:.4f}]; gap to {BASELINE[split][0]} {gap['mean']:+.4f} ± {gap['sd']:.4f} "
          f"[{gap['lo']:+.4f}, {gap['hi']:+.4f}]")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--split", default="stratified",
                        choices=("stratified", "leave-activities-out"))
    parser.add_argument("--vectors", type=Path, default=Path("out/learn/real/vectors.npz"))
    parser.add_argument("--test", action="store_true",
                        help="Measure on test instead (once, after the choice on dev).")
    args = parser.parse_args()
    torch.set_num_threads(1)  # as `homesim learn` (the thread count changes float sums)
    torch.use_deterministic_algorithms(True)
    if args.test:
        on_test(args.split, args.seeds, args.vectors)
        return
    rows = []
    for seed in range(args.seeds):
        rows.append(measure(args.split, seed, args.vectors))
        cv, dev, cv_l, dev_l = rows[-1]
        print(f"{args.split} seed {seed}: CV / dev {cv:.4f} / {dev:.4f} -> with the "
              f"likelihood {cv_l:.4f} / {dev_l:.4f}", flush=True)
    cv, dev, cv_l, dev_l = np.mean(rows, axis=0)
    print(f"{args.split} mean: CV / dev {cv:.4f} / {dev:.4f} -> with the likelihood "
          f"{cv_l:.4f} / {dev_l:.4f}")


if __name__ == "__main__":
    main()
