from dataclasses import replace

import numpy as np
import pytest

from homesim.learn.likelihood import (
    FEATURES,
    FOLDS,
    UNKNOWN_LOGP,
    CrossFitted,
    folds,
    likelihoods,
)
from homesim.learn.rerank import FEATURES as RERANK_FEATURES
from homesim.learn.rerank import Query, Reranker
from homesim.program.metrics import step_tokens
from homesim.program.model import Program


@pytest.fixture(scope="module")
def fitted(tiny_splits):
    return CrossFitted.fit(tiny_splits.train, "program", seed=3)


def test_folds_are_round_robin_or_whole_activities(tiny_splits):
    train = tiny_splits.train
    assert folds(train, "program") == [i % FOLDS for i in range(len(train))]
    by_activity = folds(train, "activity")
    for a, fa in zip(train, by_activity, strict=True):
        assert all(fb == fa for b, fb in zip(train, by_activity, strict=True)
                   if b.activity == a.activity)
    assert len(set(by_activity)) > 1


def test_a_fold_model_never_read_its_folds_programs(tiny_splits, fitted):
    train = tiny_splits.train
    assert sorted(fitted.models) == sorted(set(fitted.folds))
    some_unknown = False
    for i, example in enumerate(train):
        model = fitted.for_training_query(i)
        held = {tuple(step_tokens(e.program)) for e, f in zip(train, fitted.folds, strict=True)
                if f == fitted.folds[i]}
        assert tuple(step_tokens(example.program)) in held
        # a step only the fold's programs use is one its model cannot emit
        elsewhere = {s for e, f in zip(train, fitted.folds, strict=True) if f != fitted.folds[i]
                     and tuple(step_tokens(e.program)) not in held for s in step_tokens(e.program)}
        unknown = likelihoods(model, example, [example.program])[0, 2]
        own = set(step_tokens(example.program))
        assert (unknown > 0) == bool(own - elsewhere)
        some_unknown |= unknown > 0
    assert some_unknown  # the tiny data has steps only one fold uses


def test_likelihoods_rank_a_training_program_above_its_reversal(tiny_splits, fitted):
    train = tiny_splits.train
    example = train[0]
    backwards = replace(example.program, steps=example.program.steps[::-1])
    rows = likelihoods(fitted.full, example, [example.program, backwards, Program(())])
    assert rows.shape == (3, len(FEATURES))
    assert rows[0, 1] > rows[1, 1]  # mean log-likelihood per step
    assert np.all(rows[:, 0] <= 0) and np.all(rows[:, 2] == 0)
    alien = Program.parse("[Walk] <no_such_thing> (1)")
    total, mean, unknown = likelihoods(fitted.full, example, [alien])[0]
    assert unknown == 0.5 and total <= UNKNOWN_LOGP and mean == total / 2  # step, end


def test_reranker_with_likelihoods_scores_every_candidate_and_repeats(tiny_splits):
    train, test = tiny_splits.train, tiny_splits.test
    model = Reranker.fit(train, "program", likelihood=True, seed=3)
    query = Query(model.bank, test[0], np.ones(len(train), bool))
    assert model.scores(query).shape == (len(query.candidates),)
    assert model.trees.n_features_in_ == 2 * (len(RERANK_FEATURES) + len(FEATURES))
    again = Reranker.fit(train, "program", likelihood=True, seed=3)
    assert [str(p) for p in model.predict(test[:3])] == [str(p) for p in again.predict(test[:3])]
