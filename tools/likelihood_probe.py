"""The MLE model's likelihood of each candidate as reranker features, measured without test
(docs/learn.md, "Tried for the reranker"): the cross-validated and dev figures of
`tools/rerank_dev.py` with and without three more features per candidate.

    python tools/likelihood_probe.py [--seeds 5] [--split stratified]

The features are the teacher-forced log-likelihood of the candidate's steps (its end
included) under the run's MLE model given the description: the total, the mean per step,
and the share of its steps outside the model's step vocabulary (each such step counts
`OOV_LOGP`). A training query is scored by a model trained without its fold (and without
every copy of the fold's programs; leave-activities-out: without the fold's activities),
so that no query's likelihood comes from a model that read its program; dev by a model
trained on all of training. Models: `Text2Prog`, `MLE_EPOCHS` epochs, the run's seed.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F

from homesim.learn.data import Example
from homesim.learn.experiment import RunSpec, load_run_splits
from homesim.learn.rerank import Bank, Query, _labelled, fit_trees
from homesim.learn.text2prog import Text2Prog
from homesim.learn.train import TrainConfig, train_mle
from homesim.learn.vocab import END, step_key
from homesim.program.metrics import step_tokens
from homesim.program.model import Program
from rerank_dev import FOLDS, cross_validated, top_lcs, training_queries

OOV_LOGP = -12.0
MLE_EPOCHS = 12

Group = tuple[np.ndarray, np.ndarray]


def trained(examples: list[Example], seed: int) -> Text2Prog:
    """A fresh MLE model trained on `examples` (the table's learning rate and batch)."""
    t2p = Text2Prog.create(examples, seed)
    train_mle(t2p, examples, TrainConfig(MLE_EPOCHS, 32, 4e-3, seed))
    t2p.model.eval()
    return t2p


@torch.no_grad()
def likelihoods(t2p: Text2Prog, example: Example, programs: list[Program]) -> np.ndarray:
    """(programs, 3): total log-likelihood, its mean per step, share of unknown steps."""
    model = t2p.model
    words, mask = t2p.batch([example])
    n = len(programs)
    state = model.encode(words.expand(n, -1), mask.expand(n, -1))
    steps = model.step_embeddings()
    ids = [[t2p.steps.index.get(step_key(s)) for s in p.steps] + [END] for p in programs]
    total, unknown = np.zeros(n), np.zeros(n)
    prev = None
    for t in range(max(len(i) for i in ids)):
        logits, state = model.decode_step(state, prev, steps)
        logp = F.log_softmax(logits, 1)
        gold = [i[t] if t < len(i) else END for i in ids]
        for b, g in enumerate(gold):
            if t < len(ids[b]):
                total[b] += OOV_LOGP if g is None else float(logp[b, g])
                unknown[b] += g is None
        prev = torch.tensor([END if g is None else g for g in gold], device=logits.device)
    lengths = np.array([len(i) for i in ids], dtype=float)
    return np.stack([total, total / lengths, unknown / lengths], 1)


def with_likelihoods(query: Query, t2p: Text2Prog) -> Group:
    """The query's feature rows with the likelihood features appended, and its targets."""
    features, targets = _labelled(query)
    extra = likelihoods(t2p, query.example, [c.program for c in query.candidates])
    return np.hstack([features, extra]), targets


def fold_models(bank: Bank, split: str, seed: int) -> dict[int, Text2Prog]:
    """Fold -> a model trained without the fold's programs (and their copies), and for
    leave-activities-out without the fold's activities."""
    rows = training_queries(bank, split)
    models = {}
    for k in range(FOLDS):
        held = [e for _, e, _, fold in rows if fold == k]
        programs = {tuple(step_tokens(e.program)) for e in held}
        activities = {e.activity for e in held} if split != "stratified" else set()
        keep = [e for e in bank.train if tuple(step_tokens(e.program)) not in programs
                and e.activity not in activities]
        models[k] = trained(keep, seed)
    return models


def measure(split: str, seed: int, vectors: Path) -> tuple[float, float, float, float]:
    """(CV, dev) without and with the likelihood features, for one run."""
    splits = load_run_splits(RunSpec("real", split, seed), vectors)
    bank = Bank(splits.train)
    models, full = fold_models(bank, split, seed), trained(splits.train, seed)
    base: list[Group] = []
    extended: list[Group] = []
    folds: list[int] = []
    for _, example, allowed, fold in training_queries(bank, split):
        query = Query(bank, example, allowed)
        if query.candidates:
            base.append(_labelled(query))
            extended.append(with_likelihoods(query, models[fold]))
            folds.append(fold)
    everything = np.ones(len(splits.train), bool)
    dev_queries = [Query(bank, e, everything) for e in splits.dev]
    base_dev = [_labelled(q) for q in dev_queries]
    extended_dev = [with_likelihoods(q, full) for q in dev_queries]
    return (cross_validated(base, folds), float(np.mean(top_lcs(fit_trees(base), base_dev))),
            cross_validated(extended, folds),
            float(np.mean(top_lcs(fit_trees(extended), extended_dev))))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--split", default="stratified",
                        choices=("stratified", "leave-activities-out"))
    parser.add_argument("--vectors", type=Path, default=Path("out/learn/real/vectors.npz"))
    args = parser.parse_args()
    torch.set_num_threads(1)  # as `homesim learn` (the thread count changes float sums)
    torch.use_deterministic_algorithms(True)
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
