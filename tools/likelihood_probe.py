"""The MLE model's likelihood of each candidate as reranker features: an experiment that
did not pay off on test, kept here, out of the library (docs/learn.md, "Measured on dev
and once on test, not kept"). Prints the cross-validated and dev figures of
`tools/rerank_dev.py` with and without three more features per candidate; with --test,
the one test measurement made after that choice.

    python tools/likelihood_probe.py [--seeds 5] [--split stratified] [--test]

The features (`likelihoods`) are the teacher-forced log-likelihood of the candidate's steps
(its end included) under an MLE model given the description: the total, the mean per step,
and the share of its steps the model cannot emit (each counted at `UNKNOWN_LOGP`). A
training query is scored by a model trained without its fold (and every copy of the fold's
programs; leave-activities-out: without the fold's activities), so that no query's
likelihood comes from a model that read its program; dev and test by a model trained on
all of training (`CrossFitted`).
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F

from homesim.learn.data import Example
from homesim.learn.eval.experiment import HOLDOUT, RunSpec, load_run_splits
from homesim.learn.eval.summary import summarize, summarize_gap
from homesim.learn.rerank.base import Bank, Query, labelled
from homesim.learn.rerank.editors import fit_editors
from homesim.learn.rerank.folds import folds
from homesim.learn.rerank.reranker import Reranker
from homesim.learn.rerank.trees import design, fit_trees
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.text.train import TrainConfig, train_mle
from homesim.learn.vocabularies import END, step_key
from homesim.program.metrics import normalized_lcs, step_tokens
from homesim.program.model import Program
from rerank_dev import BASELINE, CONFIG, cross_validated_each, top_lcs, training_queries

Group = tuple[np.ndarray, np.ndarray]
UNKNOWN_LOGP = -12.0
"""Log-probability counted for a step the model cannot emit."""
FEATURES = ("log-likelihood", "mean log-likelihood", "unknown steps")


def trained(examples: list[Example], seed: int) -> Text2Prog:
    """A fresh MLE model trained on `examples` with the table's epochs, batch and learning
    rate (`RunSpec`'s; no dev selection), in eval mode."""
    t2p = Text2Prog.create(examples, seed)
    train_mle(t2p, examples, TrainConfig(RunSpec.mle_epochs, RunSpec.batch_size,
                                         RunSpec.mle_lr, seed))
    t2p.model.eval()
    return t2p


def likelihoods(t2p: Text2Prog, example: Example, programs: list[Program]) -> np.ndarray:
    """(programs, 3) `FEATURES` of each program for the example's title and description."""
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
        assigned = folds(train, holdout, CONFIG.folds)
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


def with_likelihoods(features: np.ndarray, query: Query, t2p: Text2Prog) -> np.ndarray:
    """The query's feature rows with `FEATURES` under `t2p` appended."""
    programs = [c.program for c in query.candidates]
    return np.hstack([features, likelihoods(t2p, query.example, programs)])


@dataclass
class LikelihoodReranker(Reranker):
    """The reranker whose trees also read each candidate's likelihood under `fitted.full`."""

    fitted: CrossFitted | None = None

    @classmethod
    def fit_with_likelihood(cls, train: list[Example], holdout: str, seed: int = 0
                            ) -> LikelihoodReranker:
        """`Reranker.fit`, each training query's features with the likelihoods of the model
        trained without its fold (models trained with `seed`)."""
        bank = Bank(train, CONFIG)
        fitted = CrossFitted.fit(train, holdout, seed)
        groups, queries = [], []
        for i, example in enumerate(train):
            query = Query(bank, example, ~bank.hidden(example, holdout))
            if query.candidates:
                features, targets = labelled(query)
                groups.append((with_likelihoods(features, query,
                                                fitted.for_training_query(i)), targets))
                queries.append((i, query))
        inserter, deleter = fit_editors(bank, holdout, queries, groups, True)
        return cls(bank, fit_trees(groups, CONFIG), inserter, deleter, fitted)

    def scores(self, query: Query) -> np.ndarray:
        assert self.fitted is not None
        features = with_likelihoods(query.features(), query, self.fitted.full)
        return np.asarray(self.trees.predict(design(features)))


def measure(split: str, seed: int, vectors: Path) -> tuple[float, float, float, float]:
    """(CV, dev) without and with the likelihood features, for one run."""
    splits = load_run_splits(RunSpec("real", split, seed), vectors)
    bank = Bank(splits.train, CONFIG)
    fitted = CrossFitted.fit(splits.train, HOLDOUT[split], seed)
    base: list[Group] = []
    extended: list[Group] = []
    fold_of: list[int] = []
    for i, example, allowed, fold in training_queries(bank, split):
        query = Query(bank, example, allowed)
        if query.candidates:
            features, targets = labelled(query)
            base.append((features, targets))
            extended.append((with_likelihoods(features, query, fitted.for_training_query(i)),
                             targets))
            fold_of.append(fold)
    everything = np.ones(len(splits.train), bool)
    dev = [Query(bank, e, everything) for e in splits.dev]
    base_dev = [labelled(q) for q in dev]
    extended_dev = [(with_likelihoods(f, q, fitted.full), t)
                    for q, (f, t) in zip(dev, base_dev, strict=True)]
    return (float(cross_validated_each(base, fold_of).mean()),
            float(np.mean(top_lcs(fit_trees(base, CONFIG), base_dev))),
            float(cross_validated_each(extended, fold_of).mean()),
            float(np.mean(top_lcs(fit_trees(extended, CONFIG), extended_dev))))


def on_test(split: str, seeds: int, vectors: Path) -> None:
    """The one test measurement: `LikelihoodReranker.predict` (executability checked, as the
    table's row) against the split's baseline, over the seeds, summarised as the table
    summarises a gap (`homesim.learn.eval.summary`)."""
    baseline = BASELINE[split][1]
    ours: list[list[dict]] = []
    theirs: list[list[dict]] = []
    for seed in range(seeds):
        splits = load_run_splits(RunSpec("real", split, seed), vectors)
        model = LikelihoodReranker.fit_with_likelihood(splits.train, HOLDOUT[split], seed)
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
