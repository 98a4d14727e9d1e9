import numpy as np

from homesim.learn.rerank.deletion import (
    STEP_FEATURES,
    Deleter,
    step_features,
    text_closeness,
)
from homesim.learn.rerank.folds import Known
from homesim.learn.rerank.insertion import token_phrase
from homesim.program.metrics import step_tokens
from homesim.program.model import Program
from tests.learn.rerank.test_insertion import TV, Fixed, _bank, _query


def _fixed(chances: list[float]) -> Fixed:
    return Fixed(chances, len(STEP_FEATURES))


def test_unlikely_steps_are_deleted_but_never_all():
    bank = _bank()
    query = _query(bank, "watch tv")
    program = Program.parse(TV)
    low = bank.config.delete_threshold - 0.01
    edited = Deleter(_fixed([0.9, low, 0.8]), {}).delete(query, program)  # type: ignore[arg-type]
    assert step_tokens(edited) == [("WALK", ("home_office",)), ("WATCH", ("television",))]
    assert Deleter(_fixed([low] * 3), {}).delete(query, program) is program  # type: ignore[arg-type]
    assert Deleter(_fixed([0.9] * 3), {}).delete(query, program) is program  # type: ignore[arg-type]


def test_step_features_see_the_text_and_the_neighbours():
    bank = _bank()
    query = _query(bank, "watch tv")
    tokens = (*step_tokens(Program.parse(TV)), ("SWITCHON", ("light",)))
    rows = step_features(query, tokens, Known.everything(query), {})
    assert rows.shape == (4, len(STEP_FEATURES))
    named = STEP_FEATURES.index("objects named")
    assert list(rows[:, named]) == [1.0, 1.0, 1.0, 0.0]  # "watch" points to home_office
    support = STEP_FEATURES.index("activity support")
    assert rows[2, support] == 1.0 and rows[3, support] == 0.0
    room = STEP_FEATURES.index("a room")
    assert list(rows[:, room]) == [1.0, 0.0, 0.0, 0.0]
    said = STEP_FEATURES.index("phrase cosine to its closest clause")
    assert rows[2, said] > rows[3, said]  # "watch tv" says the watching, not the light


def test_steps_are_compared_with_the_text_in_words():
    text = "Watch TV. Sit on the couch, then switch on the light."
    tokens = (("WALK", ("home_office",)), ("SWITCHON", ("light",)), ("SIT", ("couch",)),
              ("WATCH", ("television",)))
    assert token_phrase(tokens[1]) == "switch on light"
    close = text_closeness(text, tokens)
    assert close.shape == (4, 3) and np.all(np.abs(close) <= 1 + 1e-6)
    cosine, short, whole = close.T
    assert cosine[1] > cosine[0] and cosine[2] > cosine[0]  # said, against a walk unsaid
    assert short[1] == short[2] == short[3] == 0.0  # each the closest step to its clause
    assert short[0] < 0.0 and whole[0] < whole[3]
    assert not np.allclose(whole, cosine)  # the whole text is not its closest clause ...
    alone = text_closeness("watch tv", tokens)
    assert np.allclose(alone[:, 2], alone[:, 0])  # ... unless it is one clause
    assert text_closeness(text, ()).shape == (0, 3)
    assert text_closeness("", tokens[:2]).shape == (2, 3)
