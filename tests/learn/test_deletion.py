from homesim.learn.deletion import DELETE_THRESHOLD, STEP_FEATURES, Deleter, step_features
from homesim.learn.insertion import Known
from homesim.program.metrics import step_tokens
from homesim.program.model import Program
from tests.learn.test_insertion import TV, Fixed, _bank, _query


def _fixed(chances: list[float]) -> Fixed:
    return Fixed(chances, len(STEP_FEATURES))


def test_unlikely_steps_are_deleted_but_never_all():
    bank = _bank()
    query = _query(bank, "watch tv")
    program = Program.parse(TV)
    low = DELETE_THRESHOLD - 0.01
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
