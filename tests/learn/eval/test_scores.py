import pytest

from homesim.learn.eval.scores import lcs_scores, score
from homesim.program import parse_program

TRUTH = parse_program("[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[Walk] <sofa> (1)\n[Sit] <sofa> (1)")


def test_identical_programs_score_one():
    assert lcs_scores(TRUTH, TRUTH) == (1.0, 1.0, 1.0)


def test_partial_match_is_normalised_by_the_longer():
    pred = parse_program("[Walk] <tv> (1)\n[SwitchOff] <tv> (1)")
    action, objects, steps = lcs_scores(pred, TRUTH)
    assert action == pytest.approx(1 / 4)  # only the first Walk is shared
    assert objects == pytest.approx(2 / 4)
    assert steps == pytest.approx(1 / 4)


def test_score_averages_and_counts_executable():
    s = score([TRUTH, parse_program("[Sit] <sofa> (1)")], [TRUTH, TRUTH], [True, False])
    assert s.steps == pytest.approx((1 + 0.25) / 2)
    assert s.simulator == 50.0 and s.n == 2
    assert s.mean == pytest.approx((s.action + s.objects + s.steps) / 3)
    with pytest.raises(ValueError):
        score([], [], [])


def test_trivial_programs_cannot_game_the_solved_metric():
    from homesim.learn.eval.scores import example_scores
    from homesim.program.model import Program

    empty = example_scores(Program(()), TRUTH, runs_here=True, runs_elsewhere=1.0)
    assert empty["simulator"] == 1.0  # an empty program executes...
    assert empty["solved"] == 0.0 and empty["steps"] == 0.0  # ...but solves nothing
    one = example_scores(parse_program("[Walk] <tv> (1)"), TRUTH, True, 1.0)
    assert one["simulator"] == 1.0 and one["solved"] == 0.0
    assert example_scores(TRUTH, TRUTH, True, 1.0)["solved"] == 1.0
    assert example_scores(TRUTH, TRUTH, False, 0.0)["solved"] == 0.0  # must execute too


def test_repeats_count_steps_equal_to_the_one_before():
    from homesim.learn.eval.scores import repeats

    loop = parse_program("[Walk] <tv> (1)\n[Walk] <tv> (1)\n[Walk] <tv> (2)\n[Sit] <sofa> (1)")
    assert repeats(loop) == 2 and repeats(TRUTH) == 0
