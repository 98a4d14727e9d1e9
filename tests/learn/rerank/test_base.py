"""The bank and the query: what a training query may see, and its candidates."""

from dataclasses import replace

import numpy as np

from homesim.knowledge.datasets import ActivityProgram
from homesim.learn.rerank.base import Bank, Query, feature_names
from homesim.program.model import Program
from tests.learn.rerank.test_reranker import LAMP, TV, _example


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
    assert query._typical() is not None and tuple(step_tokens(query._typical()[1])) == median
    assert median in {c.tokens for c in query.candidates if c.edited}
    assert query.candidates[query.typical].tokens == median  # the typical program
    features = dict(zip(feature_names(bank.config), query.features()[query.typical],
                        strict=True))
    assert features["typical program"] == 1.0
    assert features["log words beyond the title"] == np.log1p(1)  # "wash fae": "fae"


def test_an_unseen_activity_is_typically_its_nearest_activity(tiny_splits):
    bank = Bank(tiny_splits.train)
    e = tiny_splits.train[0]
    query = Query(bank, e, ~bank.hidden(e, "activity"))  # its activity hidden
    assert not len(query.activity_programs())
    shown = query.typical_programs()
    assert len(shown) and len({bank.train[k].activity for k in shown}) == 1
    assert bank.train[int(shown[0])].activity != e.activity
