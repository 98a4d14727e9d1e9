"""Cross-validation folds of the reranker's training queries, and what an editor fitted
without a query's fold may read for it.

The trees and the editors learn from training descriptions, each queried against the rest
of training; to see how a model does on a query it did not learn from, the queries are cut
into `config.RerankConfig.folds` folds (`folds`: round robin, or by activity when the split
hides whole activities) and each fold is scored by models fitted on the others. `Known` is what an
editor may read for a query besides the bank's neighbours: for a training query, a lexicon
fitted on and the programs of the other folds only (`fold_knowledge`), so that no count
moves with whether its own hidden program has a step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from homesim.learn.data import Example
from homesim.learn.rerank.base import Bank, Query
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.lexicon import ObjectLexicon


def folds(train: list[Example], holdout: str, n: int) -> list[int]:
    """The fold (of `n`) of each training example: round robin, or by activity when
    `holdout` is "activity" (a fold then holds whole activities)."""
    if holdout == "activity":
        activities = sorted({e.activity for e in train})
        return [activities.index(e.activity) % n for e in train]
    return [i % n for i in range(len(train))]


@dataclass(frozen=True)
class Known:
    """What an editor may read for a query besides the bank's neighbours: a lexicon, and the
    training programs whose steps it counts. For a test query, the bank's lexicon and every
    program; for a training query, those fitted on and made of the other cross-validation
    folds, so that no count moves with whether its own (hidden) program has a step."""

    lexicon: ObjectLexicon
    counted: np.ndarray
    """(train,) True for the programs counted."""

    @classmethod
    def everything(cls, query: Query) -> Known:
        """What a test query may read."""
        return cls(query.bank.lexicon, np.ones(len(query.bank.train), bool))


def fold_knowledge(train: list[Example], holdout: str, config: RerankConfig
                   ) -> tuple[np.ndarray, list[Known]]:
    """Each training example's cross-validation fold (`folds`), and for each fold
    what its training queries' editors may read: the lexicon fitted on, and the programs of,
    the other folds."""
    fold_of = np.array(folds(train, holdout, config.folds))
    return fold_of, [Known(ObjectLexicon.fit([e for e, f in zip(train, fold_of, strict=True)
                                               if f != k], config.lexicon), fold_of != k)
                     for k in range(config.folds)]


def has_copy(bank: Bank, example: Example) -> bool:
    """Whether another training example has the same steps as `example` (a training one).
    The editors learn only from training queries without one: a copy the query may not see
    would make a count move with whether its program has a step."""
    return int(bank.hidden(example, "program").sum()) > 1

