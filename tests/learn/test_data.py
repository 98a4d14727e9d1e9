import pytest

from homesim.learn.data import real_examples, split, synthetic_examples, ungrounded
from homesim.program import parse_program


def test_ungrounded_keeps_bindings():
    p, b = ungrounded(parse_program("[Walk] <tv> (1.410)\n[SwitchOn] <tv> (1.410)"))
    assert str(p) == "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)"
    assert b == {("tv", 1): 410}


def test_split_is_seeded_stratified_and_disjoint():
    ex = synthetic_examples(200, seed=2)
    a, b = split("s", ex, seed=5), split("s", ex, seed=5)
    assert [e.id for e in a.test] == [e.id for e in b.test]
    assert [e.id for e in split("s", ex, seed=6).test] != [e.id for e in a.test]
    ids = [e.id for part in (a.train, a.dev, a.test) for e in part]
    assert sorted(ids) == sorted(e.id for e in ex)
    assert abs(len(a.test) - 40) <= 2 and abs(len(a.dev) - 20) <= 2
    for activity in {e.activity for e in ex}:
        total = sum(e.activity == activity for e in ex)
        in_train = sum(e.activity == activity for e in a.train)
        assert abs(in_train - 0.7 * total) <= 2


@pytest.mark.dataset
def test_real_examples(real_data):
    ex = real_examples(real_data)
    assert len(ex) == 518
    first = ex[0]
    assert first.text.startswith("Write an email.")
    assert not first.program.is_grounded and first.bindings
    assert first.graph().character_id is not None
