"""What the reranker and its editors read of one description: the training bank, the query
and its candidates with their feature rows.

`Bank` holds the training side (step tokens, their pairwise steps LCS, sentence vectors,
the lexicon) and the settings (`config.RerankConfig`); `Query` is one description against
it: similarities, neighbour weights at each of the settings' taus, the classes and
actions the text names, and the candidates (`reranker` module docstring, steps 1-2) with
their features (`feature_names`). The reranker
(`reranker.Reranker`) and the editors (`insertion`, `deletion`) read these; none of them
is imported here.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from homesim.learn.data import Example
from homesim.learn.embeddings import example_vectors
from homesim.learn.rerank.candidates import drops, mention_order, substitutions
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.lexicon import ObjectLexicon, actions, classes, words
from homesim.learn.rerank.median import Medians, uniform_median
from homesim.learn.rerank.support import words_beyond_title
from homesim.program.metrics import normalized_lcs, step_tokens
from homesim.program.model import Program
from homesim.world.vocab import ROOM_NAMES


def feature_names(config: RerankConfig) -> tuple[str, ...]:
    """The names of a candidate's features (`Query.features` columns), in order."""
    return (*(f"expected LCS, tau {t}" for t in config.taus), "named classes used",
            "classes named", "classes unexplained", "edited", "log length ratio",
            "abs log length ratio", "source similarity", "source description cosine",
            "source title cosine", "steps with named objects", "named classes missing",
            "log implicit rate", "mention order", "classes", "log length x log words",
            "named actions used", "actions named", "source words cosine", "typical program",
            "log words beyond the title")


@dataclass(frozen=True)
class Candidate:
    """A candidate program, the training example it came from, and whether it was edited."""

    program: Program
    tokens: tuple
    source: int
    edited: bool


@dataclass
class Bank:
    """The training side: step tokens, their pairwise LCS, sentence vectors, lexicon, and
    the settings everything fitted on it reads."""

    train: list[Example]
    config: RerankConfig = field(default_factory=RerankConfig)
    lexicon: ObjectLexicon = field(init=False)

    def __post_init__(self) -> None:
        self.tokens = [tuple(step_tokens(e.program)) for e in self.train]
        n = len(self.train)
        self.lcs = np.eye(n)
        for i in range(n):
            for j in range(i + 1, n):
                self.lcs[i, j] = self.lcs[j, i] = normalized_lcs(self.tokens[i], self.tokens[j])
        self.desc, self.title = example_vectors(self.train)
        self.lengths = np.array([len(t) for t in self.tokens], dtype=float)
        self.lexicon = ObjectLexicon.fit(self.train, self.config.lexicon)
        self.idf, self.bags = _bags([e.text for e in self.train])

    @cached_property
    def step_index(self) -> dict[tuple, np.ndarray]:
        """Step token -> indices (ascending) of the training programs that have it."""
        index: dict[tuple, list[int]] = {}
        for k, tokens in enumerate(self.tokens):
            for token in dict.fromkeys(tokens):
                index.setdefault(token, []).append(k)
        return {token: np.array(ks) for token, ks in index.items()}

    def having(self, token: tuple) -> np.ndarray:
        """(train,) True where the training program has the step `token`."""
        out = np.zeros(len(self.train), bool)
        if token in self.step_index:
            out[self.step_index[token]] = True
        return out

    @cached_property
    def activities(self) -> np.ndarray:
        """(train,) each training program's activity."""
        return np.array([e.activity for e in self.train])

    def activity_mask(self, activity: str) -> np.ndarray:
        """(train,) True for the training programs of `activity`."""
        return self.activities == activity

    def medoid(self, indices: np.ndarray) -> int:
        """The one of `indices` (not empty) with the highest summed steps LCS to the others
        (ties: the first)."""
        return int(indices[int(np.argmax(self.lcs[np.ix_(indices, indices)].sum(1)))])

    def hidden(self, example: Example, holdout: str) -> np.ndarray:
        """(train,) True where a training query `example` may not see the example."""
        if holdout == "activity":
            return self.activity_mask(example.activity)
        own = tuple(step_tokens(example.program))
        return np.array([t == own for t in self.tokens])


@dataclass
class Query:
    """One description against the bank: similarities, weights, named classes, candidates."""

    bank: Bank
    example: Example
    allowed: np.ndarray
    vectors: tuple[np.ndarray, np.ndarray] | None = None
    """The description's and the title's sentence vectors (default: embedded here)."""

    def __post_init__(self) -> None:
        if self.vectors is None:
            desc, title = example_vectors([self.example])
            self.vectors = (desc[0], title[0])
        self.desc, self.title = self.vectors
        self.sims = 0.5 * (self.bank.desc @ self.desc) + 0.5 * (self.bank.title @ self.title)
        sims = np.where(self.allowed, self.sims, -np.inf)
        top = sims.max()
        cfg = self.bank.config
        self.weights = {}
        for tau in cfg.taus:
            w = np.where(self.allowed, np.exp((sims - top) / tau), 0.0)
            self.weights[tau] = w / w.sum()
        self.named = self.bank.lexicon.mentions(self.example.text)
        self.verbs = self.bank.lexicon.actions(self.example.text)
        self.overlap = self.bank.bags @ _bag(self.example.text, self.bank.idf)
        self.near = np.argsort(-self.weights[cfg.taus[1]], kind="stable")[:cfg.near]
        self.beyond = np.log1p(words_beyond_title(self.example))
        self.typical_tokens: tuple | None = None
        self.candidates = self._candidates(sims)
        self.typical = next((i for i, c in enumerate(self.candidates)
                             if c.tokens == self.typical_tokens), -1)
        """Index of the typical program among the candidates (`support`); -1: none."""

    def activity_programs(self) -> np.ndarray:
        """Indices of the training programs of the query's activity that it may see."""
        return np.flatnonzero(self.allowed & self.bank.activity_mask(self.example.activity))

    def typical_programs(self) -> np.ndarray:
        """The training programs the typical program is the median of (`support`): those of
        the query's activity that it may see, or if none, those of the activity of the
        nearest title it may see (MiniLM cosine; ties: the first)."""
        same = self.activity_programs()
        seen = np.flatnonzero(self.allowed)
        if len(same) or not len(seen):
            return same
        nearest = int(seen[int(np.argmax(self.bank.title[seen] @ self.title))])
        return np.flatnonzero(self.allowed & self.bank.activity_mask(
            str(self.bank.activities[nearest])))

    def _candidates(self, sims: np.ndarray) -> list[Candidate]:
        cfg = self.bank.config
        sources: list[int] = []
        best: dict[float, int] = {}
        for tau in cfg.taus:
            expected = np.where(self.allowed, self.weights[tau] @ self.bank.lcs, -1.0)
            ranked = [int(j) for j in np.argsort(-expected, kind="stable")[:cfg.top_k]]
            best[tau] = ranked[0]
            sources += ranked
        sources += [int(j) for j in np.argsort(-sims, kind="stable")[:3]]
        out: list[Candidate] = []
        seen: set[tuple] = set()

        def add(p: Program, source: int, edited: bool) -> None:
            """`p` as a candidate unless one with its steps is already there."""
            tokens = tuple(step_tokens(p))
            if tokens not in seen:
                seen.add(tokens)
                out.append(Candidate(Program(p.steps), tokens, source, edited))

        for j in sources:
            program = self.bank.train[j].program
            add(program, j, False)
            for q in substitutions(program, self.named, cfg.max_substitutions):
                add(q, j, True)
        for c in out[:cfg.drop_from]:
            for p in drops(c.program, self.named, self.bank.lexicon.implicit_rate,
                           cfg.chain_implicit):
                add(p, c.source, True)
        for j, p in self._medians(best):
            if p.steps:
                add(p, j, True)
        typical = self._typical()
        if typical is not None:
            add(typical[1], typical[0], True)
            self.typical_tokens = tuple(step_tokens(typical[1]))
        return out

    def _typical(self) -> tuple[int, Program] | None:
        """(start, median) of `typical_programs`, started from their medoid; None when there
        are none or the median is empty."""
        bank, same = self.bank, self.typical_programs()
        if not len(same):
            return None
        start = bank.medoid(same)
        median = uniform_median([bank.train[k].program for k in same],
                                bank.train[start].program, bank.config.median)
        return (start, median) if median.steps else None

    def _medians(self, best: dict[float, int]) -> list[tuple[int, Program]]:
        """(start, median) pairs: the median of the `near` nearest neighbours under each tau's
        weights, started from that tau's best expected-LCS program (`best`)."""
        bank, out, cfg = self.bank, [], self.bank.config
        references = [bank.train[k].program for k in self.near]
        for tau in cfg.taus:
            medians = Medians(references, self.weights[tau][self.near], cfg.median)
            out.append((best[tau], medians.median(bank.train[best[tau]].program)))
        return out

    def features(self) -> np.ndarray:
        """(candidates, len(feature_names)) feature rows."""
        return np.array([self._row(c) for c in self.candidates])

    def _row(self, c: Candidate) -> list[float]:
        bank, near, taus = self.bank, self.near, self.bank.config.taus
        lcs = (np.array([normalized_lcs(c.tokens, bank.tokens[k]) for k in near]) if c.edited
               else bank.lcs[c.source][near])
        expected = [float(self.weights[t][near] @ lcs / max(self.weights[t][near].sum(), 1e-12))
                    for t in taus]
        used, named = classes(c.program), self.named
        size = max(len(used), 1)
        ratio = np.log(len(c.tokens) / (self.weights[taus[2]] @ bank.lengths)) if c.tokens else -3.0
        steps_with = [ref.name for s in c.program.steps for ref in s.args]
        named_steps = [all(r.name in named or r.name in ROOM_NAMES for r in s.args)
                       for s in c.program.steps if s.args]
        unnamed = used - named
        acts = actions(c.program)
        n_words = len(words(self.example.text)) + 1
        return [*expected, len(used & named) / max(len(named), 1), len(used & named) / size,
                len(unnamed - ROOM_NAMES) / size, float(c.edited), ratio, abs(ratio),
                float(self.sims[c.source]), float(bank.desc[c.source] @ self.desc),
                float(bank.title[c.source] @ self.title),
                float(np.mean(named_steps)) if named_steps else 0.0, len(named - used),
                float(np.mean([np.log(bank.lexicon.implicit_rate(o)) for o in sorted(unnamed)]))
                if unnamed else 0.0,
                mention_order(steps_with, named, self.example.text), len(used),
                np.log(max(len(c.tokens), 1)) * np.log(n_words),
                len(acts & self.verbs) / max(len(self.verbs), 1),
                len(acts & self.verbs) / max(len(acts), 1), float(self.overlap[c.source]),
                float(c.tokens == self.typical_tokens), float(self.beyond)]



def labelled(query: Query) -> tuple[np.ndarray, np.ndarray]:
    """The query's feature rows and each candidate's steps LCS to the query's own program
    (what the trees regress)."""
    truth = tuple(step_tokens(query.example.program))
    return query.features(), np.array([normalized_lcs(c.tokens, truth)
                                       for c in query.candidates])


def _bags(texts: list[str]) -> tuple[dict[str, tuple[int, float]], np.ndarray]:
    """Word -> (column, idf) over `texts`, and their unit tf-idf rows."""
    df: dict[str, int] = {}
    for t in texts:
        for w in set(words(t)):
            df[w] = df.get(w, 0) + 1
    idf = {w: (i, float(np.log((1 + len(texts)) / (1 + n)) + 1))
           for i, (w, n) in enumerate(sorted(df.items()))}
    return idf, np.array([_bag(t, idf) for t in texts]).reshape(len(texts), len(idf))


def _bag(text: str, idf: dict[str, tuple[int, float]]) -> np.ndarray:
    """The unit tf-idf vector of `text` over the words of `idf` (others ignored)."""
    out = np.zeros(len(idf))
    for w in words(text):
        if w in idf:
            out[idf[w][0]] += idf[w][1]
    norm = np.linalg.norm(out)
    return out / norm if norm else out

