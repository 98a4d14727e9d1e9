"""Every setting of the reranker and its editors, in one dataclass saved with the model.

`RerankConfig` travels with the fitted model: `base.Bank` holds it, so every query, the
trees and both editors read the settings the model was fitted with, and a pickled
`reranker.Reranker` (the program writer's) carries them. The defaults are the settings
the evaluation's table was measured with; how each was chosen is in docs/learn.md
(cross-validation over the training queries and the dev split, never test).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from homesim.learn.rerank.lexicon import LexiconConfig
from homesim.learn.rerank.median import MedianConfig


def _trees() -> dict[str, Any]:
    return {"max_iter": 200, "learning_rate": 0.05, "max_leaf_nodes": 15,
            "min_samples_leaf": 40, "random_state": 0}


def _classifier() -> dict[str, Any]:
    return {"max_iter": 150, "learning_rate": 0.05, "max_leaf_nodes": 15,
            "min_samples_leaf": 40, "random_state": 0}


@dataclass(frozen=True)
class RerankConfig:
    """The reranker's settings (`reranker` module docstring), its editors' and its folds'."""

    taus: tuple[float, ...] = (0.02, 0.05, 0.1, 0.3)
    """Temperatures of the neighbour weights softmax(similarity / tau), one candidate list
    and one expected-LCS feature each."""
    top_k: int = 8
    """Training programs of highest expected steps LCS taken as candidates under each tau."""
    near: int = 25
    """Nearest neighbours (weights at the second tau) the expected-LCS features, the
    medians and the editors' support read."""
    max_substitutions: int = 5
    """Length of the chain of greedy substitutions (`candidates.substitutions`)."""
    drop_from: int = 40
    """Candidates (retrieved and substituted, in order) whose drops are added."""
    chain_implicit: float = 0.7
    """Unnamed classes left implicit in fewer than this share of training programs are
    dropped together in one more candidate (`candidates.drops`)."""
    median: MedianConfig = field(default_factory=MedianConfig)
    """The medians' search (`median.Medians`)."""
    lexicon: LexiconConfig = field(default_factory=LexiconConfig)
    """What a word must share with a class or action to point to it (`lexicon`)."""
    trees: dict[str, Any] = field(default_factory=_trees)
    """`sklearn.ensemble.HistGradientBoostingRegressor` settings of the scorer (`trees`)."""
    check_executable: int = 10
    """Candidates checked for executability, best first, before giving up."""
    folds: int = 5
    """Cross-validation folds of the training queries (`folds`)."""
    classifier: dict[str, Any] = field(default_factory=_classifier)
    """`sklearn.ensemble.HistGradientBoostingClassifier` settings of both editors."""
    insert_threshold: float = 0.5
    """Proposals the inserter gives at least this probability of being in the truth are
    inserted (`insertion`)."""
    position_tau: float = 0.1
    """The neighbour weights (one of `taus`) the editors place steps and count support by."""
    delete_threshold: float = 0.2
    """Steps the deleter gives less than this probability of being in the truth are
    deleted (`deletion`)."""
    reduced: tuple[int, ...] = (0, 4)
    """The trees also learn from each training description cut to this many words (0: the
    title alone; `support.reduced`), so that they know what a short text supports."""
    support_edges: tuple[int, ...] = (1, 6)
    """Words beyond the title that start each support level above 0 (`support.support_level`):
    the title alone, up to five more words, more."""
    typical_margins: tuple[float, ...] = (0.0, 0.01, 0.02, 0.03, 0.05, 0.1, float("inf"))
    """The margins `support.choose_margins` chooses from by cross-validation, one for each
    support level: the typical program is written when its score is less than the margin
    behind the best one's (inf: always)."""

    def __post_init__(self) -> None:
        if self.position_tau not in self.taus or len(self.taus) < 3:
            raise ValueError(f"RerankConfig: taus {self.taus} must be at least three and "
                             f"hold position_tau {self.position_tau}")
