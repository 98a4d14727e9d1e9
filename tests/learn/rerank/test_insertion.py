from dataclasses import replace

import numpy as np

from homesim.knowledge.datasets import ActivityProgram
from homesim.learn.rerank.base import Bank, Query
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.folds import Known
from homesim.learn.rerank.insertion import (
    PROPOSAL_FEATURES,
    Inserter,
    clauses,
    closeness,
    proposal_features,
    proposals,
    step_phrase,
)
from homesim.learn.rerank.reranker import Reranker
from homesim.program.metrics import step_tokens
from homesim.program.model import Program

TV = "[Walk] <home_office> (1)\n[Walk] <television> (1)\n[Watch] <television> (1)"
LAMP = "[Walk] <bedroom> (1)\n[Walk] <light> (1)\n[SwitchOn] <light> (1)"


def _example(i: int, title: str, description: str, program: str) -> ActivityProgram:
    p = Program.parse(program)
    return ActivityProgram(f"e{i}", replace(p, title=title, description=description))


def _bank() -> Bank:
    return Bank([_example(i, *spec) for i, spec in enumerate(
        [("Watch TV", "watch tv", TV)] * 3 + [("Turn on light", "switch light", LAMP)] * 3)])


def _query(bank: Bank, text: str, title: str = "Watch TV") -> Query:
    example = _example(99, title, text, TV)  # its text: the title, then the description
    return Query(bank, example, np.ones(len(bank.train), bool))


def test_clauses_split_at_punctuation_and_conjunctions():
    parts = [c.strip() for c in clauses("Walk in, sit down and then watch TV. Relax!")]
    assert [p for p in parts if p] == ["walk in", "sit down", "watch tv", "relax"]
    assert clauses("...") == []


def test_a_clause_proposes_its_actions_with_the_objects_it_names():
    bank = _bank()
    found = proposals(_query(bank, "watch tv, switch light"), bank.lexicon)
    # "watch" and "switch" were learned to point to their rooms too (lexicon links)
    assert [p.token for p in found] == [
        ("WALK", ("home_office",)), ("WALK", ("television",)), ("WATCH", ("television",)),
        ("WALK", ("bedroom",)), ("WALK", ("light",)), ("SWITCHON", ("light",))]
    # nothing crosses clauses: the light is not watched, the tv not switched on
    one_clause = proposals(_query(bank, "watch tv"), bank.lexicon)
    assert [p.token for p in one_clause] == [p.token for p in found[:3]]
    assert proposals(_query(bank, "sit back", "Relax"), bank.lexicon) == []


class Fixed:
    """A stand-in classifier: fixed probabilities, in row order, for rows of `width`."""

    def __init__(self, chances: list[float], width: int = len(PROPOSAL_FEATURES)) -> None:
        self.chances, self.width = chances, width

    def predict_proba(self, rows: np.ndarray) -> np.ndarray:
        assert rows.shape[1] == self.width
        p = np.array(self.chances[:len(rows)])
        return np.stack([1 - p, p], axis=1)


def test_only_likely_proposals_are_inserted_where_the_neighbours_have_them():
    bank = _bank()
    query = _query(bank, "watch tv, switch light")
    choice = Program.parse("[Walk] <home_office> (1)\n[Watch] <television> (1)")
    # lacking: WALK tv, WALK bedroom, WALK light, SWITCHON light (in that order)
    inserter = Inserter(Fixed([0.9, RerankConfig().insert_threshold - 0.01, 0.2, 0.2]), {})  # type: ignore[arg-type]
    edited = inserter.insert(query, choice)
    assert step_tokens(edited) == [("WALK", ("home_office",)), ("WALK", ("television",)),
                                   ("WATCH", ("television",))]
    nothing = Inserter(Fixed([0.1] * 4), {})  # type: ignore[arg-type]
    assert nothing.insert(query, choice) is choice


def test_proposal_features_see_the_choice_and_the_neighbours():
    bank = _bank()
    query = _query(bank, "watch tv, switch light")
    found = proposals(query, bank.lexicon)
    rows = proposal_features(query, found, (("WATCH", ("television",)),),
                             Known.everything(query), {})
    assert rows.shape == (len(found), len(PROPOSAL_FEATURES))
    has_objects = PROPOSAL_FEATURES.index("choice has its objects")
    assert list(rows[:, has_objects]) == [0.0, 1.0, 1.0, 0.0, 0.0, 0.0]
    support = PROPOSAL_FEATURES.index("activity support")
    assert rows[2, support] == 1.0 and rows[5, support] == 0.0  # a Watch TV query
    share = PROPOSAL_FEATURES.index("share of programs with it")
    assert rows[2, share] == 0.5
    # a training query counts only the programs of the other folds
    lamps = Known(bank.lexicon, np.array([False] * 3 + [True] * 3))
    again = proposal_features(query, found, (), lamps, {})
    assert again[2, support] == 0.0 and again[2, share] == 0.0 and again[5, share] == 1.0


def test_the_reranker_inserts_only_what_still_executes(tiny_splits):
    train, test = tiny_splits.train, tiny_splits.test
    model = Reranker.fit(train, "program", delete=False)  # the deleter's rule: test_rerank
    assert model.inserter is not None and model.deleter is None
    plain = Reranker(model.bank, model.trees)
    edited = [e for e in test if model.choose(e, lambda p: True).steps
              != plain.choose(e, lambda p: True).steps]
    assert edited  # the inserter changes some choices ...
    for e in edited:  # ... and none when the longer program would not run
        first = plain.choose(e, lambda p: True)
        assert model.choose(e, lambda p, f=first: p.steps == f.steps).steps == first.steps


def test_a_proposal_is_compared_with_the_clauses_that_propose_it():
    bank = _bank()
    found = proposals(_query(bank, "watch tv, switch light"), bank.lexicon)
    # the text is the title, then the description: "watch tv" twice
    assert [p.clauses for p in found] == [(0, 1)] * 3 + [(2,)] * 3
    assert step_phrase(found[5].step) == "switch on light"
    close = closeness(_query(bank, "watch tv, switch light"), found)
    assert close.shape == (6, 2) and np.all(np.abs(close) <= 1 + 1e-6)
    assert close[2, 1] == 0.0 and close[5, 1] == 0.0  # each clause's closest step
    assert np.all(close[[0, 1, 3, 4], 1] < 0)  # the walks say the clauses less well
    assert closeness(_query(bank, "watch tv"), []).shape == (0, 2)
