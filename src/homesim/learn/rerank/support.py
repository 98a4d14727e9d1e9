"""How much a text says, and what the reranker writes when it says little.

A title alone, or a title and a few words, names too little to edit a neighbour's program
by: the *typical program* of the activity is then the best guess (the median of the query's
activity's training programs searched from their medoid, as the title-median baseline
writes it; for an activity not in training, the median of the activity of the training
title nearest to the query's: `base.Query`). The reranker learns when that is so from its
training data alone:

- its trees also learn from each training description cut short (`reduced`: to the title
  alone and to the title and its first words, `config.RerankConfig.reduced`), queried like
  the whole one;
- two features say whether a candidate is the typical program and how many words the
  description says beyond the title (`words_beyond_title`);
- the typical program is written when its score is within a margin of the best candidate's,
  one margin for each level of how much the text says (`support_level`), chosen by
  cross-validation over the training queries, whole and cut short (`choose_margins`,
  `config.RerankConfig.typical_margins`);
- where the title alone says only the activity and the activity is in training, the
  typical program is written whatever the scores (`reranker.Reranker.choose`).
  Cross-validation chose margin 0 there, yet on dev seed 0 the trees' other choices for a
  bare title (25 of 93) fell .075 steps LCS below the typical program: a title has no
  words to choose another program by. For an activity not in training, the typical
  program is the nearest title's activity's, and the trees' choice was far better on dev
  (.152 against .053, leave-activities-out seed 0).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from homesim.learn.data import Example
from homesim.learn.rerank.lexicon import words


def reduced(example: Example, n_words: int) -> Example:
    """`example` with its description cut to its first `n_words` words; 0: the title alone
    (as `eval.titles.title_only` gives it). The program is kept (what the trees learn)."""
    text = " ".join(example.description.split()[:n_words]) if n_words else ""
    return replace(example, program=replace(example.program,
                                            description=text or example.title))


def words_beyond_title(example: Example) -> int:
    """How many distinct words the description says that the title does not."""
    return len(set(words(example.description)) - set(words(example.title)))


def support_level(example: Example, edges: tuple[int, ...]) -> int:
    """How much the text says, as a level: the number of `edges` that
    `words_beyond_title` reaches (edges (1, 6): 0 the title alone, 1 up to five more words,
    2 more)."""
    beyond = words_beyond_title(example)
    return sum(beyond >= edge for edge in edges)


Scored = tuple[np.ndarray, np.ndarray, int, int]
"""One training query, cross-fitted: its candidates' steps LCS to the truth, their scores
by trees fitted without its fold, the index of its typical program (-1: none) and its
`support_level`."""


def gated(scores: np.ndarray, typical: int, margin: float) -> int:
    """The candidate written: the best-scoring one, or the typical program when its score is
    within `margin` of the best's (strictly less behind; inf: always)."""
    best = int(np.argmax(scores))
    if typical >= 0 and scores[best] - scores[typical] < margin:
        return typical
    return best


def choose_margins(queries: list[Scored], margins: tuple[float, ...], levels: int
                   ) -> tuple[float, ...]:
    """For each support level (0 .. `levels` - 1), the one of `margins` under which `gated`
    writes the highest mean steps LCS over that level's `queries` (ties, and a level
    without queries: the smallest margin)."""
    def mean(level: list[Scored], margin: float) -> float:
        return float(np.mean([lcs[gated(s, t, margin)] for lcs, s, t, _ in level]))

    ordered = sorted(margins)
    chosen = []
    for level in range(levels):
        mine = [q for q in queries if q[3] == level]
        means = [mean(mine, m) for m in ordered] if mine else [0.0]
        chosen.append(ordered[int(np.argmax(means))])
    return tuple(chosen)
