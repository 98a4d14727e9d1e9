import random

import numpy as np
import pytest

from homesim.learn.rerank.median import Medians, lcs_length, position_masks
from homesim.program.metrics import lcs_length as dynamic_lcs
from homesim.program.metrics import normalized_lcs, step_tokens
from homesim.program.parse import parse_program

OBJECTS = {"a": "cup", "b": "plate", "c": "glass", "d": "fork", "e": "knife", "f": "bowl"}


def program(letters: str):
    return parse_program("\n".join(f"[Grab] <{OBJECTS[x]}> (1)" for x in letters))


def mean_lcs(p, references) -> float:
    return float(np.mean([normalized_lcs(step_tokens(p), step_tokens(q)) for q in references]))


def test_bit_parallel_lcs_equals_the_dynamic_programme():
    rng = random.Random(3)
    for _ in range(300):
        a = [rng.randrange(5) for _ in range(rng.randrange(0, 12))]
        b = [rng.randrange(5) for _ in range(rng.randrange(0, 12))]
        assert lcs_length(a, position_masks(b), len(b)) == dynamic_lcs(a, b)


def test_the_median_beats_every_reference_where_none_is_central():
    references = [program(s) for s in ("fae", "ebe", "ecda")]
    medians = Medians(references, np.ones(3))
    medoid = max(references, key=lambda p: mean_lcs(p, references))
    median = medians.median(medoid)
    assert mean_lcs(median, references) > mean_lcs(medoid, references) + 0.05
    assert step_tokens(median) not in [step_tokens(p) for p in references]


def test_the_median_follows_the_weights():
    references = [program(s) for s in ("abcd", "ef", "fe")]
    median = Medians(references, np.array([1.0, 0.0, 0.0])).median(references[1])
    assert step_tokens(median) == step_tokens(references[0])


@pytest.mark.parametrize("weights", [np.ones(3), np.array([0.2, 0.5, 0.3])])
def test_the_search_never_lowers_the_expected_lcs_and_is_deterministic(weights):
    references = [program(s) for s in ("abca", "bcd", "acdf")]
    medians = Medians(references, weights)
    for start in ("f", "abcdef", "dd"):
        median = medians.median(program(start))
        codes = [medians.codes[t] for t in step_tokens(median)]
        start_codes = [medians.codes[t] for t in step_tokens(program(start))]
        assert medians.expected_lcs(codes) >= medians.expected_lcs(start_codes)
        assert step_tokens(Medians(references, weights).median(program(start))) == \
            step_tokens(median)


def test_an_insertion_goes_where_the_references_have_the_step():
    references = [program("abc")] * 3
    medians = Medians(references, np.ones(3))
    start = program("ac")
    b = medians.symbol(program("b").steps[0])
    inserted = medians.best_insertion(medians.encode(start), b)
    assert step_tokens(medians.decode(start, inserted)) == step_tokens(program("abc"))


def _random_program(rng: random.Random, longest: int):
    return program("".join(rng.choice("abcdef") for _ in range(rng.randrange(1, longest))))


@pytest.mark.parametrize("longest", [12, 70])  # 70: references too long for 64-bit rows
def test_all_moves_at_once_score_the_same_floats_as_one_by_one(longest):
    rng = random.Random(longest)
    for _ in range(40):
        references = [_random_program(rng, longest) for _ in range(rng.randrange(1, 9))]
        medians = Medians(references, np.array([rng.random() for _ in references]))
        assert (medians._tables is None) == any(len(p.steps) >= 64 for p in references)
        current = medians.encode(_random_program(rng, 15))
        one_by_one = [medians.expected_lcs(m) for m in medians.moves(current)]
        assert medians.move_scores(current).tolist() == one_by_one
        moves = medians.moves(current)
        assert [medians.move(current, k) for k in range(len(moves))] == moves


def test_a_single_step_has_only_insertions_to_try():
    medians = Medians([program("ab"), program("ba")], np.ones(2))
    current = medians.encode(program("a"))
    moves = medians.moves(current)
    assert all(len(m) == 2 for m in moves) and len(moves) == 2 * len(medians.vocab)
    assert medians.move_scores(current).tolist() == [medians.expected_lcs(m) for m in moves]
