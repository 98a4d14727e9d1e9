from itertools import combinations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from homesim.program import parse_program
from homesim.program.metrics import (
    ProgramScores,
    action_tokens,
    executability_rate,
    lcs_actions,
    lcs_length,
    lcs_mean,
    lcs_objects,
    lcs_steps,
    normalized_lcs,
    object_tokens,
    score_programs,
)

WATCH_TV = parse_program("""
[Walk] <tv> (1)
[SwitchOn] <tv> (1)
[Walk] <sofa> (1)
[Sit] <sofa> (1)
[Watch] <tv> (1)
""")
# Same actions but one Walk dropped; "television" instead of "tv".
WATCH_TELEVISION = parse_program("""
[Walk] <television> (1)
[SwitchOn] <television> (1)
[Sit] <sofa> (1)
[Watch] <television> (1)
""")


@pytest.mark.parametrize(("a", "b", "expected"), [
    ("", "", 0),
    ("abc", "", 0),
    ("abc", "abc", 3),
    ("abcd", "acbd", 3),      # abd or acd
    ("abcbdab", "bdcaba", 4),  # the textbook case: bcba
    ("aaaa", "aa", 2),
    ("xyz", "abc", 0),
    (["WALK", "SIT"], ["SIT", "WALK"], 1),
])
def test_lcs_length_hand_cases(a, b, expected):
    assert lcs_length(a, b) == expected
    assert lcs_length(b, a) == expected


def _brute_force_lcs(a, b):
    for k in range(min(len(a), len(b)), 0, -1):
        subsequences = set(combinations(b, k))
        if any(sub in subsequences for sub in combinations(a, k)):
            return k
    return 0


@given(st.lists(st.sampled_from("abc"), max_size=7), st.lists(st.sampled_from("abc"), max_size=7))
def test_lcs_length_matches_brute_force(a, b):
    assert lcs_length(a, b) == _brute_force_lcs(a, b)


def test_normalized_lcs_divides_by_the_longer():
    assert normalized_lcs("abcd", "acb") == 0.5  # LCS ab or ac = 2, longer = 4
    assert normalized_lcs("", "") == 1.0
    assert normalized_lcs("a", "") == 0.0


def test_hand_computed_program_scores():
    # steps: only "[Sit] <sofa>" is shared (tv != television) -> 1/5
    assert lcs_steps(WATCH_TV, WATCH_TELEVISION) == pytest.approx(0.2)
    # actions: WALK SWITCHON SIT WATCH -> 4/5
    assert lcs_actions(WATCH_TV, WATCH_TELEVISION) == pytest.approx(0.8)
    # objects: tv tv sofa sofa tv vs television television sofa television -> sofa, 1/5
    assert lcs_objects(WATCH_TV, WATCH_TELEVISION) == pytest.approx(0.2)
    assert lcs_mean(WATCH_TV, WATCH_TELEVISION) == pytest.approx(0.4)
    scores = ProgramScores.of(WATCH_TV, WATCH_TELEVISION)
    assert scores.as_dict() == pytest.approx(
        {"steps": 0.2, "actions": 0.8, "objects": 0.2, "mean": 0.4})


def test_reordered_program():
    q = parse_program("[Walk] <sofa> (1)\n[Sit] <sofa> (1)\n[SwitchOn] <tv> (1)\n[Watch] <tv> (1)")
    # steps: Walk sofa, Sit sofa, Watch tv -> 3/5; objects: sofa sofa tv -> 3/5
    assert lcs_steps(WATCH_TV, q) == pytest.approx(0.6)
    assert lcs_objects(WATCH_TV, q) == pytest.approx(0.6)
    assert lcs_actions(WATCH_TV, q) == pytest.approx(0.6)


def test_instances_node_ids_and_spelling_do_not_count():
    grounded = parse_program("[WALK] <tv> (2.410)\n[SWITCHON] <tv> (2.410)\n[WALK] <sofa> (1.368)\n"
                             "[SIT] <sofa> (1.368)\n[WATCH] <tv> (2.410)")
    assert lcs_mean(WATCH_TV, grounded) == 1.0


def test_two_object_steps_give_two_object_tokens():
    p = parse_program("[Grab] <cup> (1)\n[PutBack] <cup> (1) <table> (1)\n[StandUp]")
    assert object_tokens(p) == ["cup", "cup", "table"]
    assert action_tokens(p) == ["GRAB", "PUTBACK", "STANDUP"]


def test_empty_programs():
    empty = parse_program("")
    assert lcs_mean(empty, empty) == 1.0
    assert lcs_mean(empty, WATCH_TV) == 0.0


def test_score_programs_means_over_pairs():
    means = score_programs([WATCH_TV, WATCH_TV], [WATCH_TV, WATCH_TELEVISION])
    assert means == pytest.approx({"steps": 0.6, "actions": 0.9, "objects": 0.6, "mean": 0.7})
    with pytest.raises(ValueError, match="2 predictions but 1 references"):
        score_programs([WATCH_TV, WATCH_TV], [WATCH_TV])
    with pytest.raises(ValueError, match="no programs"):
        score_programs([], [])


def test_executability_rate():
    class Result:
        def __init__(self, ok):
            self.executable = ok

    assert executability_rate([True, False, True, True]) == 0.75
    assert executability_rate([Result(True), Result(False)]) == 0.5
    assert executability_rate(iter([False])) == 0.0
    with pytest.raises(ValueError, match="no programs"):
        executability_rate([])
