from dataclasses import replace

import numpy as np
import pytest

from homesim.knowledge.datasets import ActivityProgram
from homesim.learn.rerank.base import FEATURES, TAUS, Bank, Query
from homesim.learn.rerank.candidates import allows, drops, mention_order, rename, substitutions
from homesim.learn.rerank.lexicon import ObjectLexicon
from homesim.learn.rerank.reranker import Reranker
from homesim.learn.rerank.trees import fit_trees
from homesim.program.model import Program


def _example(title: str, description: str, program: str) -> ActivityProgram:
    p = Program.parse(program)
    return ActivityProgram("x", replace(p, title=title, description=description))


TV = "[Walk] <home_office> (1)\n[Walk] <television> (1)\n[SwitchOn] <television> (1)"
LAMP = "[Walk] <bedroom> (1)\n[Walk] <light> (1)\n[SwitchOn] <light> (1)"


def test_lexicon_finds_knowledge_base_names_and_learned_words():
    train = [_example("Watch TV", f"go to the living room and turn on the tv {i}", TV)
             for i in range(3)]
    lexicon = ObjectLexicon.fit(train)
    named = lexicon.mentions("Turn on the TV in the living room")
    assert "television" in named  # "tv" is a knowledge-base name of television
    assert "home_office" in named  # "living" learned from the three pairs
    assert "home_office" not in ObjectLexicon.fit(train[:1]).mentions("the living room")
    assert lexicon.implicit_rate("television") < 0.5 == lexicon.implicit_rate("unheard_of")


def test_substitution_respects_the_actions_needs():
    program = Program.parse(TV)
    assert allows(program, "television", "light")  # both have a switch
    assert not allows(program, "television", "floor")  # a floor cannot be switched on
    assert not allows(program, "home_office", "light")  # rooms only for rooms
    assert str(rename(program, "television", "light")).count("<light> (1)") == 2
    swapped = substitutions(program, frozenset({"light", "bedroom"}))
    texts = {str(p) for p in swapped}
    assert str(rename(program, "television", "light")) in texts
    assert str(rename(rename(program, "home_office", "bedroom"), "television", "light")) in texts
    assert substitutions(program, frozenset({"television", "home_office"})) == []


def test_mention_order_compares_with_the_text():
    named = frozenset({"cup", "table"})
    assert mention_order(["cup", "table"], named, "take the cup to the table") == 1.0
    assert mention_order(["table", "cup"], named, "take the cup to the table") == 0.0
    assert mention_order(["cup"], named, "the cup") == 0.5


def test_trees_learn_which_feature_ranks_within_a_group():
    rng = np.random.default_rng(0)
    groups = []
    for _ in range(60):
        x = rng.normal(size=(6, 3))
        groups.append((x, 2 * x[:, 1] + rng.normal(scale=0.01, size=6) + rng.normal()))
    trees = fit_trees(groups)
    from homesim.learn.rerank.trees import design

    hits = [int(np.argmax(trees.predict(design(x)))) == int(np.argmax(x[:, 1]))
            for x in (rng.normal(size=(6, 3)) for _ in range(40))]
    assert np.mean(hits) > 0.8


def test_tree_seed_defaults_to_the_settings_and_picks_the_early_stopping_holdout():
    """From 10 000 samples scikit-learn holds some out for early stopping; `random_state`
    picks which (docs/learn.md, "How much of a dev difference is noise")."""
    from homesim.learn.rerank.trees import TREES, design

    rng = np.random.default_rng(1)
    groups = [(x, x[:, 0] + rng.normal(scale=0.5, size=20))
              for x in (rng.normal(size=(20, 2)) for _ in range(520))]
    probe = design(rng.normal(size=(50, 2)))
    default, same, other = (fit_trees(groups, r).predict(probe)
                            for r in (None, int(TREES["random_state"]), 1))
    assert np.array_equal(default, same)
    assert not np.array_equal(default, other)


def test_drops_leave_out_unnamed_objects_but_never_rooms_or_everything():
    program = Program.parse(TV + "\n[Walk] <couch> (1)\n[Sit] <couch> (1)")
    rate = {"couch": 0.1, "television": 0.2}.get
    out = {str(p) for p in drops(program, frozenset(), lambda c: rate(c, 0.9))}
    assert str(Program.parse(TV)) in out  # couch left out
    assert str(Program.parse("[Walk] <home_office> (1)")) in out  # both rarely implicit
    assert all("home_office" in p for p in out)
    assert drops(Program.parse("[Walk] <couch> (1)"), frozenset(), lambda c: 0.1) == []


def test_reranker_prefers_the_program_whose_objects_the_text_names(tiny_splits):
    train, test = tiny_splits.train, tiny_splits.test
    model = Reranker.fit(train, "program")
    query = Query(model.bank, test[0], np.ones(len(train), bool))
    assert query.features().shape == (len(query.candidates), len(FEATURES))
    assert model.scores(query).shape == (len(query.candidates),)
    preds = model.predict(test[:4])
    assert [str(p) for p in preds] == [str(p) for p in Reranker.fit(
        train, "program").predict(test[:4])]
    pool = {e.program.steps for e in train}
    assert all(p.steps in pool or len(p) for p in preds)


def test_a_training_query_does_not_see_what_the_split_hides(tiny_splits):
    bank = Bank(tiny_splits.train)
    e = tiny_splits.train[0]
    assert bank.hidden(e, "program")[0]
    same = [x.activity == e.activity for x in tiny_splits.train]
    assert list(bank.hidden(e, "activity")) == same


def test_candidates_include_the_median_of_the_querys_activity():
    from homesim.learn.rerank.median import Medians
    from homesim.program.metrics import step_tokens
    from tests.learn.rerank.test_median import program

    dishes = [ActivityProgram(f"d{i}", Program(program(s).steps, "Wash dishes", f"wash {s}"))
              for i, s in enumerate(("fae", "ebe", "ecda"))]
    bank = Bank([*dishes, _example("Watch TV", "turn on the tv", TV),
                 _example("Turn on light", "switch the lamp on", LAMP)])
    query = Query(bank, replace(dishes[0], id="q"), np.ones(len(bank.train), bool))
    references = [e.program for e in dishes]
    medoid = bank.train[bank.medoid(np.arange(3))].program
    median = tuple(step_tokens(Medians(references, np.ones(3)).median(medoid)))
    assert median not in bank.tokens
    best = {tau: int(np.argmax(query.weights[tau] @ bank.lcs)) for tau in TAUS}
    assert median in {tuple(step_tokens(p)) for _, p in query._medians(best)}
    assert median in {c.tokens for c in query.candidates if c.edited}


@pytest.mark.parametrize("deletions_help", [True, False])
def test_the_deleter_is_kept_only_where_its_cross_fitted_deletions_raise_the_lcs(
        tiny_splits, monkeypatch, deletions_help):
    from homesim.learn.rerank import editors

    def cross_deleted(chosen, written):
        if deletions_help:  # the truth itself: nothing scores higher
            return [q.example.program for q, *_ in chosen]
        return [p.with_steps(p.steps[:1]) for p in written]

    monkeypatch.setattr(editors, "cross_deleted", cross_deleted)
    model = Reranker.fit(tiny_splits.train, "program")
    assert model.inserter is not None
    assert (model.deleter is not None) == deletions_help
    assert Reranker.fit(tiny_splits.train, "program", delete=False).deleter is None
