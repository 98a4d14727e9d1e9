from dataclasses import replace

import numpy as np

from homesim.knowledge.datasets import ActivityProgram
from homesim.learn.lexicon import ObjectLexicon
from homesim.learn.rerank import (
    FEATURES,
    Bank,
    Query,
    Reranker,
    allows,
    fit_ridge,
    mention_order,
    rename,
    substitutions,
)
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


def test_ridge_learns_which_feature_ranks():
    rng = np.random.default_rng(0)
    groups = []
    for _ in range(30):
        x = rng.normal(size=(6, 3))
        groups.append((x, 2 * x[:, 1] + rng.normal(scale=0.01, size=6) + rng.normal()))
    coef = fit_ridge(groups, 0.1)
    assert np.argmax(np.abs(coef)) == 1 and coef[1] > 1.5


def test_reranker_prefers_the_program_whose_objects_the_text_names(tiny_splits):
    train, dev, test = tiny_splits.train, tiny_splits.dev, tiny_splits.test
    model = Reranker.fit(train, dev, "program")
    assert model.coef.shape == (len(FEATURES),)
    query = Query(model.bank, test[0], np.ones(len(train), bool))
    assert query.features().shape == (len(query.candidates), len(FEATURES))
    preds = model.predict(test[:4])
    assert [str(p) for p in preds] == [str(p) for p in Reranker.fit(
        train, dev, "program").predict(test[:4])]
    pool = {e.program.steps for e in train}
    assert all(p.steps in pool or len(p) for p in preds)


def test_a_training_query_does_not_see_what_the_split_hides(tiny_splits):
    bank = Bank(tiny_splits.train)
    e = tiny_splits.train[0]
    assert bank.hidden(e, "program")[0]
    same = [x.activity == e.activity for x in tiny_splits.train]
    assert list(bank.hidden(e, "activity")) == same
