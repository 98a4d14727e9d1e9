"""The reranker's scorer: gradient-boosted regression trees over a description's candidates.

The trees regress each candidate's steps LCS to the truth, centred within its description
(only the order within a description matters), on each feature (`base.FEATURES`) and on its
deviation from the description's mean (`design`), with the settings of
`config.RerankConfig.trees`. `cross_fitted_best` scores each fold of training queries with
trees fitted on the others (`folds`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from homesim.learn.rerank.config import RerankConfig

if TYPE_CHECKING:
    from sklearn.ensemble import HistGradientBoostingRegressor


def design(features: np.ndarray) -> np.ndarray:
    """The trees' input for one description's candidates: each feature's deviation from the
    candidates' mean, then the feature itself."""
    return np.hstack([features - features.mean(0), features])


def fit_trees(groups: list[tuple[np.ndarray, np.ndarray]], config: RerankConfig,
              random_state: int | None = None) -> HistGradientBoostingRegressor:
    """Trees regressing targets centred within each group on `design` (`config.trees`).

    `random_state` (default `config.trees`'s) only picks the 10% of samples scikit-learn holds out
    for early stopping (on from 10 000 samples; it has not stopped before `max_iter` in the
    real runs), yet that moves the dev score by about .01 (docs/learn.md):
    `tools/rerank_dev.py --tree-seeds` averages over it."""
    # deferred: scikit-learn takes seconds to import
    from sklearn.ensemble import HistGradientBoostingRegressor

    x = np.vstack([design(f) for f, _ in groups])
    y = np.concatenate([t - t.mean() for _, t in groups])
    trees = config.trees
    settings = trees if random_state is None else {**trees, "random_state": random_state}
    return HistGradientBoostingRegressor(**settings).fit(x, y)



def cross_fitted_scores(groups: list[tuple[np.ndarray, np.ndarray]], folds: list[int],
                        config: RerankConfig, random_state: int | None = None
                        ) -> list[np.ndarray | None]:
    """Each group's candidate scores under trees fitted on the groups of the other folds
    (None where a fold has nothing to learn from)."""
    scores: list[np.ndarray | None] = [None] * len(groups)
    for k in range(config.folds):
        held = [i for i, f in enumerate(folds) if f == k]
        rest = [g for g, f in zip(groups, folds, strict=True) if f != k]
        if held and rest:
            trees = fit_trees(rest, config, random_state)
            for i in held:
                scores[i] = np.asarray(trees.predict(design(groups[i][0])))
    return scores


def cross_fitted_best(groups: list[tuple[np.ndarray, np.ndarray]], folds: list[int],
                      config: RerankConfig, random_state: int | None = None) -> np.ndarray:
    """(groups,) index of each group's best-scoring candidate under trees fitted on the
    groups of the other folds (-1 where a fold has nothing to learn from)."""
    return best_of(cross_fitted_scores(groups, folds, config, random_state))


def best_of(scores: list[np.ndarray | None]) -> np.ndarray:
    """(groups,) the index of each group's highest score (-1 for None)."""
    return np.array([-1 if s is None else int(np.argmax(s)) for s in scores], dtype=int)
