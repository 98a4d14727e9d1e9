"""The writer's choice measured on the development test splits only (seeds 0-4; the locked
seeds from 100 are refused): what docs/learn.md's "Second change" table reports.

    python tools/writer_choice_dev.py stratified:0 stratified:1 leave-activities-out:0
        [--vectors out/learn/real/vectors.npz] [--models DIR]

For each split:seed, with the reranker fitted on that run's training split (cached as a
pickle in `--models`, so a second call only predicts), prints the writer's steps LCS minus
the title-medoid, the title-median and NN (description) on whole descriptions, and minus
the title-median and NN (title) given the title alone: with the choice of this code
("now") and with the choice before commit 5290169 ("before": a bare title's typical
program only when the trees rank it first; a program that runs nowhere cut to the steps
that run), from the same fitted model.
"""

from __future__ import annotations

import argparse
import pickle
from collections.abc import Callable
from pathlib import Path

import numpy as np

from homesim.learn.data import Example
from homesim.learn.eval import baselines
from homesim.learn.eval.experiment import HOLDOUT, RunSpec, load_run_splits
from homesim.learn.eval.scores import lcs_scores
from homesim.learn.eval.splits import check_unlocked
from homesim.learn.eval.titles import title_only
from homesim.learn.execution import executable
from homesim.learn.rerank.reranker import Reranker, runnable_part
from homesim.learn.rerank.support import support_level
from homesim.program.model import Program


def choice_before(model: Reranker, example: Example, runs: Callable[[Program], bool]
                  ) -> Program:
    """What `Reranker.choose` wrote before commit 5290169, for comparison."""
    query, programs = model.ranked(example)
    bare = support_level(example, model.config.support_edges) == 0
    if (bare and query.typical >= 0 and programs[0] is query.candidates[query.typical].program
            and runs(programs[0])):
        return programs[0]
    chosen = next((p for p in programs[:model.config.check_executable] if runs(p)), None)
    if chosen is None:
        chosen = runnable_part(programs[0], runs)
    return next((p for p in model.edits(query, chosen)
                 if p.steps != chosen.steps and runs(p)), chosen)


def fitted(split: str, seed: int, train: list[Example], models: Path) -> Reranker:
    path = models / f"reranker-{split}-{seed}.pkl"
    if path.is_file():
        return pickle.loads(path.read_bytes())
    model = Reranker.fit(train, HOLDOUT[split])
    models.mkdir(parents=True, exist_ok=True)
    path.write_bytes(pickle.dumps(model))
    return model


def report(split: str, seed: int, vectors: Path, models: Path) -> str:
    check_unlocked(seed, final=False)
    splits = load_run_splits(RunSpec("real", split, seed, 2000, 12), vectors)
    test, train = splits.test, splits.train
    model = fitted(split, seed, train, models)

    def lcs(programs: list[Program]) -> np.ndarray:
        return np.array([lcs_scores(p, e.program)[2] for p, e in zip(programs, test,
                                                                      strict=True)])

    base = {"medoid": lcs(baselines.title_medoid(train, test)),
            "median": lcs(baselines.title_median(train, test)),
            "NN(desc)": lcs(baselines.nn_description(train, test)),
            "NN(title)": lcs(baselines.nn_title(train, test))}
    titles = [title_only(e) for e in test]
    runs = [lambda p, e=e: executable(p, e) for e in test]
    before = [choice_before(model, e, r) for e, r in zip(test, runs, strict=True)]
    before_title = [choice_before(model, t, r) for t, r in zip(titles, runs, strict=True)]
    rows = {"now": (lcs(model.predict(test)), lcs(model.predict(titles))),
            "before": (lcs(before), lcs(before_title))}
    parts = [f"{split}:{seed} ({len(test)} programs)"]
    for name, (desc, title) in rows.items():
        gaps = [f"desc-{b} {desc.mean() - base[b].mean():+.4f}"
                for b in ("medoid", "median", "NN(desc)")]
        gaps += [f"title-{b} {title.mean() - base[b].mean():+.4f}"
                 for b in ("median", "NN(title)")]
        parts.append(f"{name}: " + ", ".join(gaps))
    return " | ".join(parts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="split:seed, e.g. stratified:0")
    parser.add_argument("--vectors", type=Path, default=Path("out/learn/real/vectors.npz"))
    parser.add_argument("--models", type=Path, default=Path("out/writer_choice_dev"))
    args = parser.parse_args()
    for run in args.runs:
        split, seed = run.split(":")
        print(report(split, int(seed), args.vectors, args.models), flush=True)


if __name__ == "__main__":
    main()
