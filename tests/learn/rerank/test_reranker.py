"""The reranker end to end on tiny data: seeded, and its settings saved with it."""

import pickle
from dataclasses import replace

import numpy as np
import pytest

from homesim.knowledge.datasets import ActivityProgram
from homesim.learn.rerank.base import Bank, Query, feature_names
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.reranker import Reranker, runnable_part
from homesim.program.model import Program


def _example(title: str, description: str, program: str) -> ActivityProgram:
    p = Program.parse(program)
    return ActivityProgram("x", replace(p, title=title, description=description))


TV = "[Walk] <home_office> (1)\n[Walk] <television> (1)\n[SwitchOn] <television> (1)"
LAMP = "[Walk] <bedroom> (1)\n[Walk] <light> (1)\n[SwitchOn] <light> (1)"


def test_reranker_prefers_the_program_whose_objects_the_text_names(tiny_splits):
    train, test = tiny_splits.train, tiny_splits.test
    model = Reranker.fit(train, "program")
    query = Query(model.bank, test[0], np.ones(len(train), bool))
    assert query.features().shape == (len(query.candidates), len(feature_names(model.config)))
    assert model.scores(query).shape == (len(query.candidates),)
    preds = model.predict(test[:4])
    assert [str(p) for p in preds] == [str(p) for p in Reranker.fit(
        train, "program").predict(test[:4])]
    pool = {e.program.steps for e in train}
    assert all(p.steps in pool or len(p) for p in preds)


def test_the_settings_are_saved_with_the_model_and_read_from_it(tiny_splits):
    train, test = tiny_splits.train, tiny_splits.test
    config = RerankConfig(top_k=2, near=5, check_executable=1)
    model = Reranker.fit(train, "program", insert=False, config=config)
    assert model.config == config and model.bank.config is config
    again = pickle.loads(pickle.dumps(model))
    assert again.config == config  # the pickle (the program writer's) carries them
    assert [str(p) for p in again.predict(test[:3])] == [str(p) for p in model.predict(test[:3])]
    everything = np.ones(len(train), bool)
    default = Query(Bank(train), test[0], everything)
    fewer = Query(model.bank, test[0], everything)
    assert len(fewer.near) == 5 < len(default.near)
    assert len(fewer.candidates) < len(default.candidates)


def test_settings_that_cannot_work_are_refused():
    with pytest.raises(ValueError, match="position_tau"):
        RerankConfig(taus=(0.02, 0.05, 0.3))


def test_when_no_candidate_runs_the_steps_of_the_best_that_run_are_written(tiny_splits):
    def runs(p: Program) -> bool:  # a home where nothing can be switched on
        return not any(s.action.key == "SWITCHON" for s in p.steps)

    tv = Program.parse(TV)
    assert [str(s) for s in runnable_part(tv, runs).steps] == [str(s) for s in tv.steps[:2]]
    assert runnable_part(tv, lambda p: not p.steps).steps == ()
    train, test = tiny_splits.train, tiny_splits.test
    model = Reranker.fit(train, "program", config=RerankConfig(check_executable=1))
    for example in test[:3]:
        chosen = model.choose(example, runs)
        assert runs(chosen)


def test_a_bare_title_gets_the_typical_program_unedited(tiny_splits):
    import math

    from homesim.learn.eval.titles import title_only

    train, test = tiny_splits.train, tiny_splits.test
    config = RerankConfig(typical_margins=(math.inf,))  # the typical program at every level
    model = Reranker.fit(train, "program", config=config)
    assert model.typical_margins == (math.inf,) * 3
    for example in test[:3]:
        bare = title_only(example)
        query, ranked = model.ranked(bare)
        typical = query.candidates[query.typical].program
        assert ranked[0] is typical
        assert model.choose(bare, lambda p: True).steps == typical.steps  # unedited
        elsewhere = model.choose(bare, lambda p, t=typical: p.steps != t.steps)
        assert elsewhere.steps != typical.steps  # where it does not run: as for any text


def test_a_bare_title_gets_the_typical_program_whatever_the_trees_score(tiny_splits):
    from homesim.learn.eval.titles import title_only

    train, test = tiny_splits.train, tiny_splits.test
    model = Reranker.fit(train, "program", config=RerankConfig(typical_margins=(0.0,)))

    def typical_last(query: Query) -> np.ndarray:
        scores = np.ones(len(query.candidates))
        scores[query.typical] = -1.0
        return scores

    model.scores = typical_last  # type: ignore[method-assign]
    for example in test[:3]:
        bare = title_only(example)
        query, ranked = model.ranked(bare)
        typical = query.candidates[query.typical].program
        assert ranked[0] is not typical  # the trees would write another
        assert model.choose(bare, lambda p: True).steps == typical.steps
        mended = Program((*typical.steps, *Program.parse(TV).steps[:1]))
        chosen = model.choose(bare, lambda p, t=typical: p.steps != t.steps,
                              repair=lambda p, m=mended: m)
        assert chosen is mended  # where it does not run: repaired, still unedited
    unseen = title_only(_example("Zorble the quux", "", TV))  # an activity not in training
    query, ranked = model.ranked(unseen)
    assert query.typical >= 0 and not len(query.activity_programs())
    guess = query.candidates[query.typical].program  # the nearest title's activity's
    assert model.choose(unseen, lambda p: True).steps != guess.steps  # the trees decide


def test_when_no_candidate_runs_the_best_one_repaired_is_written(tiny_splits):
    def runs(p: Program) -> bool:  # a home where nothing can be switched on
        return not any(s.action.key == "SWITCHON" for s in p.steps)

    def repair(p: Program) -> Program:  # a stand-in for repair's inserted steps
        return Program(tuple(s for s in p.steps if s.action.key != "SWITCHON")[:1])

    train, test = tiny_splits.train, tiny_splits.test
    model = Reranker.fit(train, "program", insert=False,
                         config=RerankConfig(check_executable=1, typical_margins=(0.0,)))
    failing = [e for e in test if not runs(model.ranked(e)[1][0])][:3]
    assert failing  # the best candidate of some texts switches something on
    for example in failing:
        _, ranked = model.ranked(example)
        assert model.choose(example, runs, repair=repair).steps == repair(ranked[0]).steps
        assert model.choose(example, runs, repair=lambda p: None).steps == runnable_part(
            ranked[0], runs).steps
