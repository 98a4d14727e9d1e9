"""Cross-validation folds of the training queries, and what an editor may read without its
fold."""

from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.folds import fold_knowledge, folds


def test_folds_are_round_robin_or_whole_activities(tiny_splits):
    train = tiny_splits.train
    assert folds(train, "program", 5) == [i % 5 for i in range(len(train))]
    by_activity = folds(train, "activity", 5)
    for a, fa in zip(train, by_activity, strict=True):
        assert all(fb == fa for b, fb in zip(train, by_activity, strict=True)
                   if b.activity == a.activity)
    assert len(set(by_activity)) > 1
    assert set(folds(train, "program", 3)) == {0, 1, 2}


def test_an_editor_reads_only_the_other_folds(tiny_splits):
    train = tiny_splits.train
    fold_of, known = fold_knowledge(train, "program", RerankConfig(folds=3))
    assert len(known) == 3
    for k, seen in enumerate(known):
        assert list(seen.counted) == [f != k for f in fold_of]
