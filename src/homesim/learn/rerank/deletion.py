"""Steps of the written program that neither the text nor the neighbours support, deleted.

After the choice and its inserted steps (`insertion`), a classifier (gradient-boosted trees,
the settings of `config.RerankConfig.classifier`) gives each step of the program a
probability of being in the true program, from its support among the query's neighbours
and in its activity, how common it is, whether the text names its objects or says its
action, how close the step in words is to the text in MiniLM's sentence space
(`text_closeness`), where it stands and how long the program is against the neighbours'
(`STEP_FEATURES`). Steps below `config.RerankConfig.delete_threshold` are deleted (never
all of them). Under the steps LCS over the longer length a step the truth lacks costs only
when the program is the longer one, which the length features let the classifier see.

The classifier learns as the inserter's does (`insertion.Known`), each training query with
its cross-fitted choice and the steps an inserter fitted without its fold inserted.
`Reranker.fit` keeps it only where its deletions, cross-fitted, raise the training queries'
mean steps LCS (`rerank.fit_editors`): on the stratified split at all five seeds, on
leave-activities-out at seeds 0-2 of 0-4 (docs/learn.md, "The deleter reads the text").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from homesim.learn.embeddings import lone_sentence_vectors
from homesim.learn.rerank.base import Query
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.folds import Known
from homesim.learn.rerank.insertion import (
    StepClassifier,
    clauses,
    support,
    token_phrase,
)
from homesim.learn.rerank.lexicon import words
from homesim.program.metrics import step_tokens
from homesim.program.model import Program
from homesim.world.vocab import ROOM_NAMES

STEP_FEATURES = ("neighbour support", "activity support", "share of programs with it", "objects",
                 "action", "objects named", "a room", "action said", "position", "length",
                 "length against the neighbours'", "times in the program", "words",
                 "phrase cosine to its closest clause", "against that clause's closest step",
                 "phrase cosine to the text")


def step_features(query: Query, tokens: tuple, known: Known,
                  action_codes: dict[str, int]) -> np.ndarray:
    """(steps, len(STEP_FEATURES)) rows for a program's step tokens `tokens` as the answer
    to `query`; `action_codes` numbers action keys (new ones appended)."""
    named = known.lexicon.mentions(query.example.text)
    said = known.lexicon.actions(query.example.text)
    usual_length = float(query.weights[query.bank.config.position_tau] @ query.bank.lengths)
    n_words = len(words(query.example.text))
    rows = [[*support(query, token, known), len(token[1]),
             action_codes.setdefault(token[0], len(action_codes)),
             float(all(o in named for o in token[1])) if token[1] else -1.0,
             float(any(o in ROOM_NAMES for o in token[1])), float(token[0] in said),
             position / max(len(tokens) - 1, 1), len(tokens),
             len(tokens) / max(usual_length, 1e-12), tokens.count(token), n_words, *close]
            for (position, token), close in zip(enumerate(tokens),
                                                text_closeness(query.example.text, tokens),
                                                strict=True)]
    return np.array(rows, dtype=float).reshape(len(tokens), len(STEP_FEATURES))


def text_closeness(text: str, tokens: tuple) -> np.ndarray:
    """(steps, 3): the MiniLM cosine of each step token's `insertion.token_phrase` to the
    closest clause of `text` (`insertion.clauses`), the most by which it falls short of the
    program step closest to that clause (0 for that step), and its cosine to the whole text.
    Each text is embedded on its own (`embeddings.lone_sentence_vectors`)."""
    parts = clauses(text)
    if not tokens or not parts:
        return np.zeros((len(tokens), 3))
    phrases = lone_sentence_vectors([token_phrase(t) for t in tokens])
    cosine = phrases @ lone_sentence_vectors(parts).T
    nearest = cosine.argmax(axis=1)
    best = cosine.max(axis=1)
    whole = phrases @ lone_sentence_vectors([text])[0]
    return np.stack([best, best - cosine.max(axis=0)[nearest], whole], axis=1)


@dataclass
class Deleter(StepClassifier):
    """Steps' classifier (module docstring)."""

    @classmethod
    def fit(cls, examples: list[tuple[Query, Known, Program]], config: RerankConfig
            ) -> Deleter | None:
        """From (training query, what it may read without its fold, its program as written
        without its fold) triples: label each step by whether the query's own program has
        it. None when there is only one kind to learn from."""
        codes: dict[str, int] = {}
        rows, labels = [], []
        for query, known, program in examples:
            tokens = tuple(step_tokens(program))
            truth = set(step_tokens(query.example.program))
            rows.append(step_features(query, tokens, known, codes))
            labels += [t in truth for t in tokens]
        return cls.fitted(rows, labels, codes, config)

    def delete(self, query: Query, program: Program, known: Known | None = None) -> Program:
        """`program` without the steps of probability below the bank's delete threshold
        (itself when that would leave none); `known` defaults to `Known.everything`."""
        tokens = tuple(step_tokens(program))
        if not tokens:
            return program
        rows = step_features(query, tokens, known or Known.everything(query),
                             dict(self.action_codes))
        keep = self.chances(rows) >= query.bank.config.delete_threshold
        if not keep.any() or keep.all():
            return program
        return program.with_steps([s for s, k in zip(program.steps, keep, strict=True) if k])
