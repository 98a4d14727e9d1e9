"""Baselines that learn nothing: random sampling and retrieval, the title's medoid and
median programs, nearest-neighbour retrieval by title or by description.

Sentence vectors are all-MiniLM-L6-v2's (`embeddings.sentence_vectors`), the modern
stand-in for the paper's skip-thoughts.
"""

from __future__ import annotations

import random

import numpy as np

from homesim.learn.data import Example
from homesim.learn.embeddings import cached_sentence_vectors, sentence_vectors
from homesim.learn.rerank.median import uniform_median
from homesim.program.metrics import normalized_lcs, step_tokens
from homesim.program.model import Program


def random_sampling(train: list[Example], test: list[Example], seed: int) -> list[Program]:
    """Programs of training-like length whose steps are drawn from the training steps."""
    rng = random.Random(seed)
    lengths = [len(e.program) for e in train]
    pool = [s for e in train for s in e.program.steps]  # draws follow step frequencies
    return [Program(tuple(rng.choice(pool) for _ in range(rng.choice(lengths))))
            for _ in test]


def random_retrieval(train: list[Example], test: list[Example], seed: int) -> list[Program]:
    """The program of a random training example, for each test example."""
    rng = random.Random(seed)
    return [Program(rng.choice(train).program.steps) for _ in test]


def oracle_retrieval(train: list[Example], test: list[Example]) -> list[Program]:
    """The training program closest to each test program (steps LCS; ties: the first).
    It reads the truth, so it is no baseline but the ceiling of every method that returns
    a training program unchanged."""
    pool = list({tuple(step_tokens(e.program)): e.program for e in reversed(train)}.items())
    pool.reverse()
    out = []
    for e in test:
        truth = step_tokens(e.program)
        scores = [normalized_lcs(tokens, truth) for tokens, _ in pool]
        out.append(Program(pool[scores.index(max(scores))][1].steps))
    return out


def nn_retrieval(train: list[Example], test: list[Example],
                 train_vectors: np.ndarray | None = None,
                 test_vectors: np.ndarray | None = None) -> list[Program]:
    """The program of the training example whose description is nearest (cosine of MiniLM
    sentence embeddings); vectors may be passed in when already computed."""
    if train_vectors is None:
        train_vectors = sentence_vectors([e.text for e in train])
    if test_vectors is None:
        test_vectors = sentence_vectors([e.text for e in test])
    nearest = (test_vectors @ train_vectors.T).argmax(1)
    return [Program(train[i].program.steps) for i in nearest]


def nn_title(train: list[Example], test: list[Example]) -> list[Program]:
    """The program of the training example whose title is nearest (MiniLM cosine)."""
    return _nearest(train, test, lambda e: e.title)


def nn_description(train: list[Example], test: list[Example]) -> list[Program]:
    """The program of the training example whose description is nearest (MiniLM cosine)."""
    return _nearest(train, test, lambda e: e.description)


def _nearest(train: list[Example], test: list[Example], field) -> list[Program]:
    train_vectors = cached_sentence_vectors([field(e) for e in train])
    test_vectors = cached_sentence_vectors([field(e) for e in test])
    nearest = (test_vectors @ train_vectors.T).argmax(1)
    return [Program(train[i].program.steps) for i in nearest]


def title_median(train: list[Example], test: list[Example]) -> list[Program]:
    """The generalised median (`median.Medians`, uniform weights) of the test title's
    activity's training programs, searched from their medoid; an activity not in training
    is mapped as `title_medoid` maps it. Like the medoid it reads only the title, but it
    may insert the steps most of the activity's programs share and drop the ones few do."""
    starts = medoids(train)
    centres = {activity: uniform_median([e.program for e in group], starts[activity].program)
               for activity, group in by_activity(train).items()}
    nearest = _nearest_activity(sorted(centres), test)
    return [Program(centres[nearest.get(e.activity, e.activity)].steps) for e in test]


def medoids(train: list[Example]) -> dict[str, Example]:
    """Activity -> its medoid training example: the one with the highest mean steps LCS
    to the other programs of its activity (ties: the first)."""
    return {activity: ranked[0] for activity, ranked in medoid_order(train).items()}


def by_activity(train: list[Example]) -> dict[str, list[Example]]:
    """Activity -> its training examples, in training order."""
    groups: dict[str, list[Example]] = {}
    for e in train:
        groups.setdefault(e.activity, []).append(e)
    return groups


def medoid_order(train: list[Example]) -> dict[str, list[Example]]:
    """Activity -> its training examples by mean steps LCS to the other programs of the
    activity, highest first (ties: in training order); the medoid leads."""
    out = {}
    for activity, group in by_activity(train).items():
        tokens = [step_tokens(e.program) for e in group]
        totals = [sum(normalized_lcs(a, b) for b in tokens) for a in tokens]
        out[activity] = [group[i] for i in sorted(range(len(group)),
                                                  key=lambda i: (-totals[i], i))]
    return out


def title_medoid(train: list[Example], test: list[Example]) -> list[Program]:
    """The medoid program of the test title's activity; an activity not in training is
    mapped to the training activity whose name is nearest (MiniLM cosine)."""
    centres = medoids(train)
    nearest = _nearest_activity(sorted(centres), test)
    return [Program(centres[nearest.get(e.activity, e.activity)].program.steps) for e in test]


def _nearest_activity(known: list[str], test: list[Example]) -> dict[str, str]:
    """Each test activity not in `known` -> the known one whose name is nearest (MiniLM)."""
    unseen = sorted({e.activity for e in test} - set(known))
    if not unseen:
        return {}
    sims = cached_sentence_vectors(unseen) @ cached_sentence_vectors(known).T
    return {a: known[int(i)] for a, i in zip(unseen, sims.argmax(1), strict=True)}
