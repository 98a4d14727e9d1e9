"""The reranker's editors fitted from its training queries: which to keep, and their
cross-fitted edits.

`fit_editors` learns the `insertion.Inserter` and the `deletion.Deleter` from the training
queries without a copy in training, each with its cross-fitted choice and what it may read
without its fold (`folds.Known`); the deleter is kept only when its cross-fitted deletions
(`cross_deleted`, of the programs `cross_inserted` wrote) raise those queries' mean steps
LCS. `tools/rerank_dev.py` measures the same edits.
"""

from __future__ import annotations

import numpy as np

from homesim.learn.rerank.base import Bank, Candidate, Query
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.deletion import Deleter
from homesim.learn.rerank.folds import Known, fold_knowledge, has_copy
from homesim.learn.rerank.insertion import Inserter
from homesim.learn.rerank.trees import cross_fitted_best
from homesim.program.metrics import lcs_steps
from homesim.program.model import Program


def fit_editors(bank: Bank, holdout: str, queries: list[tuple[int, Query]],
                groups: list[tuple[np.ndarray, np.ndarray]], delete: bool = False,
                best: np.ndarray | None = None) -> tuple[Inserter | None, Deleter | None]:
    """The `insertion.Inserter` and `deletion.Deleter` learned from the training queries
    (`queries`: (index in training, query), their `groups` in order) without a copy in
    training, each with its cross-fitted choice, what it may read of the folds it is not in
    (`folds.Known`), and for the deleter the steps inserted by an inserter fitted on
    those folds (`delete`; else None). `best`: each query's cross-fitted choice when
    already known (index among its candidates; default: `cross_fitted_best` of `groups`).
    The deleter is None too unless its deletions,
    cross-fitted (`cross_deleted`), raise those queries' mean steps LCS: on the stratified
    split they did at all five seeds, without their activity at three of five
    (docs/learn.md)."""
    config = bank.config
    fold_of, known = fold_knowledge(bank.train, holdout, config)
    query_folds = [int(fold_of[i]) for i, _ in queries]
    if best is None:
        best = cross_fitted_best(groups, query_folds, config)
    chosen = [(q, known[f], q.candidates[b], f) for (_, q), f, b
              in zip(queries, query_folds, best, strict=True)
              if b >= 0 and not has_copy(bank, q.example)]
    inserter = Inserter.fit([(q, k, c.tokens) for q, k, c, _ in chosen], config)
    if not delete:
        return inserter, None
    written = cross_inserted([(q, k, c, f, True) for q, k, c, f in chosen], config)
    deleted = cross_deleted([(q, k, f, True) for q, k, _, f in chosen], written, config)
    if not raises_lcs([q for q, *_ in chosen], written, deleted):
        return inserter, None
    by_fold = sorted(range(len(chosen)), key=lambda i: chosen[i][3])
    return inserter, Deleter.fit([(chosen[i][0], chosen[i][1], written[i]) for i in by_fold],
                                 config)


def cross_deleted(chosen: list[tuple[Query, Known, int, bool]], written: list[Program],
                  config: RerankConfig) -> list[Program]:
    """Each (training query, what it may read, its fold, whether editors learn from it)'s
    `written` program without the steps a `deletion.Deleter` deletes that was fitted on the
    written programs of the other folds' queries editors learn from (unchanged where there
    are none)."""
    deleted = list(written)
    for fold in range(config.folds):
        deleter = Deleter.fit([(q, k, p) for (q, k, f, learns), p
                               in zip(chosen, written, strict=True) if f != fold and learns],
                              config)
        if deleter is not None:
            for i, (q, k, f, _) in enumerate(chosen):
                if f == fold:
                    deleted[i] = deleter.delete(q, written[i], k)
    return deleted


def raises_lcs(queries: list[Query], before: list[Program], after: list[Program]) -> bool:
    """Whether `after` has a higher mean steps LCS to the queries' own programs."""
    def mean(programs: list[Program]) -> float:
        return float(np.mean([lcs_steps(p, q.example.program)
                              for p, q in zip(programs, queries, strict=True)]))

    return bool(queries) and mean(after) > mean(before)


def cross_inserted(chosen: list[tuple[Query, Known, Candidate, int, bool]],
                   config: RerankConfig) -> list[Program]:
    """Each (training query, what it may read, its cross-fitted choice, its fold, whether
    editors learn from it)'s choice with the steps inserted by an `insertion.Inserter`
    fitted on the queries of the other folds that editors learn from (the choice unchanged
    where there are none)."""
    written = [c.program for _, _, c, _, _ in chosen]
    for fold in range(config.folds):
        inserter = Inserter.fit([(q, k, c.tokens) for q, k, c, f, learns in chosen
                                 if f != fold and learns], config)
        if inserter is not None:
            for i, (q, k, c, f, _) in enumerate(chosen):
                if f == fold:
                    written[i] = inserter.insert(q, c.program, k)
    return written

