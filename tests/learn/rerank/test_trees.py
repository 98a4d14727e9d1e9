"""The scorer: trees that rank within a description, seeded by their settings."""

import numpy as np

from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.trees import design, fit_trees


def test_trees_learn_which_feature_ranks_within_a_group():
    rng = np.random.default_rng(0)
    groups = []
    for _ in range(60):
        x = rng.normal(size=(6, 3))
        groups.append((x, 2 * x[:, 1] + rng.normal(scale=0.01, size=6) + rng.normal()))
    trees = fit_trees(groups, RerankConfig())
    hits = [int(np.argmax(trees.predict(design(x)))) == int(np.argmax(x[:, 1]))
            for x in (rng.normal(size=(6, 3)) for _ in range(40))]
    assert np.mean(hits) > 0.8


def test_tree_seed_defaults_to_the_settings_and_picks_the_early_stopping_holdout():
    """From 10 000 samples scikit-learn holds some out for early stopping; `random_state`
    picks which (docs/learn.md, "How much of a dev difference is noise")."""
    rng = np.random.default_rng(1)
    groups = [(x, x[:, 0] + rng.normal(scale=0.5, size=20))
              for x in (rng.normal(size=(20, 2)) for _ in range(520))]
    probe = design(rng.normal(size=(50, 2)))
    config = RerankConfig()
    default, same, other = (fit_trees(groups, config, r).predict(probe)
                            for r in (None, int(config.trees["random_state"]), 1))
    assert np.array_equal(default, same)
    assert not np.array_equal(default, other)
