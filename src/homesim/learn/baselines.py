"""The paper's baselines: random sampling, random retrieval, nearest-neighbour retrieval."""

from __future__ import annotations

import random

import numpy as np

from homesim.learn.data import Example
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


def nn_retrieval(train: list[Example], test: list[Example],
                 train_vectors: np.ndarray | None = None,
                 test_vectors: np.ndarray | None = None) -> list[Program]:
    """The program of the training example whose description is nearest (cosine of MiniLM
    sentence embeddings); vectors may be passed in when already computed."""
    from homesim.learn.embeddings import sentence_vectors

    if train_vectors is None:
        train_vectors = sentence_vectors([e.text for e in train])
    if test_vectors is None:
        test_vectors = sentence_vectors([e.text for e in test])
    nearest = (test_vectors @ train_vectors.T).argmax(1)
    return [Program(train[i].program.steps) for i in nearest]
