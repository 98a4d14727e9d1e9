"""What a text supports: descriptions cut short, support levels, the typical program's gate."""

import math

import numpy as np

from homesim.learn.rerank.support import (
    choose_margins,
    gated,
    reduced,
    support_level,
    words_beyond_title,
)
from tests.learn.rerank.test_reranker import TV, _example


def test_a_description_cut_short_keeps_its_title_and_program():
    e = _example("Watch TV", "Walk to the TV and switch it on.", TV)
    assert reduced(e, 0).description == "Watch TV"  # the title alone
    assert reduced(e, 3).description == "Walk to the"
    assert reduced(e, 3).program.steps == e.program.steps and reduced(e, 3).title == e.title
    assert words_beyond_title(e) == 7 and words_beyond_title(reduced(e, 0)) == 0
    assert [support_level(x, (1, 6)) for x in (reduced(e, 0), reduced(e, 3), e)] == [0, 1, 2]


def test_the_typical_program_is_written_within_its_margin():
    scores = np.array([0.5, 0.25, 0.0])
    assert gated(scores, 1, 0.0) == 0 and gated(scores, 1, 0.25) == 0  # strictly less behind
    assert gated(scores, 1, 0.3) == 1 and gated(scores, 2, math.inf) == 2
    assert gated(scores, -1, math.inf) == 0  # no typical program: the best


def test_each_support_level_gets_the_margin_that_writes_most():
    lcs = np.array([0.2, 0.6])  # the typical program (1) is right
    title = (lcs, np.array([0.5, 0.1]), 1, 0)  # ... but scored .4 behind
    wrong = (np.array([0.6, 0.2]), np.array([0.5, 0.45]), 1, 1)  # the best is right
    margins = (0.0, 0.1, math.inf)
    assert choose_margins([title, wrong], margins, 3) == (math.inf, 0.0, 0.0)
