from dataclasses import replace

from homesim.learn.data import split, synthetic_examples
from homesim.learn.eval.splits import SPLITS, leave_activities_out, make_split, steps_of, stratified


def _examples():
    ex = synthetic_examples(120, seed=3)
    # a few exact copies (other ids), so duplicates between train and test are likely
    return ex + [replace(e, id=f"{e.id}-copy") for e in ex[:30]]


def test_stratified_dev_and_test_have_no_copy_of_a_training_program():
    ex = _examples()
    s = stratified(ex, seed=1)
    seen = {steps_of(e) for e in s.train}
    for part in (s.dev, s.test):
        assert part and not any(steps_of(e) in seen for e in part)
    plain = split("", ex, seed=1)
    assert [e.id for e in s.train] == [e.id for e in plain.train]
    for kept, whole in ((s.dev, plain.dev), (s.test, plain.test)):
        assert len(kept) < len(whole)  # some copies were removed from each


def test_leave_activities_out_keeps_test_activities_out_of_training():
    ex = _examples()
    s = leave_activities_out(ex, seed=2)
    train, test = {e.activity for e in s.train}, {e.activity for e in s.test}
    assert test and train and not train & test
    assert not {e.activity for e in s.dev} & train
    assert sorted(e.id for part in (s.train, s.dev, s.test) for e in part) == sorted(
        e.id for e in ex)


def test_splits_are_declared_once_and_seeded():
    ex = _examples()
    for name in SPLITS:
        a, b = make_split(name, ex, seed=4), make_split(name, ex, seed=4)
        assert [e.id for e in a.test] == [e.id for e in b.test]
    assert ({e.activity for e in make_split(SPLITS[1], ex, 4).test}
            != {e.activity for e in make_split(SPLITS[1], ex, 5).test})


def test_locked_seeds_are_refused_without_final():
    import pytest

    from homesim.errors import HomesimError
    from homesim.learn.eval.splits import DEV_SEEDS, LOCKED_FROM, is_locked, locked_seeds

    ex = _examples()
    assert locked_seeds(5) == (100, 101, 102, 103, 104) and LOCKED_FROM == 100
    assert not any(is_locked(s) for s in DEV_SEEDS) and is_locked(100) and not is_locked(99)
    for name in SPLITS:
        with pytest.raises(HomesimError, match="seed 100: seeds from 100 on are the locked"):
            make_split(name, ex, seed=100)
        assert make_split(name, ex, seed=100, final=True).test
