"""Learned reranker: retrieve training programs, substitute the objects the text names, rerank.

For a description x:

1. **Weights.** Every training example j gets w_j = softmax_j(sim(x, j) / tau), sim the
   mean of the MiniLM cosines of the descriptions and of the titles, at each tau of `TAUS`.
2. **Candidates.** The `TOP_K` training programs of highest expected steps LCS under each
   weighting (minimum Bayes risk: tau -> 0 is nearest-neighbour retrieval, uniform weights
   within an activity the title-medoid), the 3 most similar ones, and their *substitutions*:
   an object class the text does not name (`lexicon.ObjectLexicon`) replaced by one it
   names and the program lacks, where every step using it allows the new class (the
   action catalog's property needs, rooms only for rooms); singly and greedily all at once.
   Then the *drops* of the first `DROP_FROM` candidates: the steps using one class the text
   does not name (nor a room) left out, singly, and all such classes that training usually
   names (implicit rate below `CHAIN_IMPLICIT`) left out at once. Last the *medians*
   (`median.Medians`): under each tau, the step sequence of highest expected LCS to the
   `NEAR` nearest neighbours, searched from that tau's best program; and the median of the
   programs of the query's activity, searched from their medoid.
3. **Score.** Gradient-boosted regression trees over features of (x, candidate)
   (`FEATURES`): the expected LCS under each tau against the `NEAR` nearest neighbours,
   the share of named classes the candidate uses and of its classes that are named, how
   often its unnamed classes are left implicit in training, whether the mention order
   agrees, its length against the neighbours' and the text's, its source's similarity,
   whether it was edited.
4. **Choice.** The best-scoring candidate that executes in the example's home
   (`execution.executable`, checked best-first; the best one if none does).
5. **Insertion.** The steps the text says that the choice lacks and that a classifier
   finds likely, inserted where the neighbours have them (`insertion`), when the result
   still executes there.

The trees regress the candidates' steps LCS to the truth, centred within each description
(only the order within a description matters), on each feature and on its deviation from
the description's mean; they are fitted on training descriptions each queried against the
rest of the training set with what the split hides removed: for the stratified split the
training programs equal to its own, for leave-activities-out every program of its
activity. Their settings (`TREES`) were chosen by 5-fold cross-validation over those
training queries and on the dev split, never on test. Everything is deterministic.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property, partial
from typing import TYPE_CHECKING

import numpy as np

from homesim.learn.data import Example
from homesim.learn.lexicon import ObjectLexicon, actions, classes, words
from homesim.program.metrics import lcs_steps, normalized_lcs, step_tokens
from homesim.program.model import Program

if TYPE_CHECKING:
    from sklearn.ensemble import HistGradientBoostingRegressor

    from homesim.learn.deletion import Deleter
    from homesim.learn.insertion import Inserter, Known
    from homesim.learn.likelihood import CrossFitted
    from homesim.learn.text2prog import Text2Prog

TAUS = (0.02, 0.05, 0.1, 0.3)
TOP_K = 8
NEAR = 25
MAX_SUBSTITUTIONS = 5
DROP_FROM = 40
"""Candidates (retrieved and substituted, in order) whose drops are added."""
CHAIN_IMPLICIT = 0.7
"""Unnamed classes left implicit in fewer than this share of training programs are dropped
together in one more candidate."""
TREES = {"max_iter": 200, "learning_rate": 0.05, "max_leaf_nodes": 15, "min_samples_leaf": 40,
         "random_state": 0}
"""`sklearn.ensemble.HistGradientBoostingRegressor` settings (module docstring)."""
HOLDOUTS = ("program", "activity")
"""What a training query may not see of the rest of training: programs equal to its own
(stratified split) or its whole activity (leave-activities-out)."""
CHECK_EXECUTABLE = 10
"""Candidates checked for executability, best first, before giving up."""
FEATURES = (*(f"expected LCS, tau {t}" for t in TAUS), "named classes used",
            "classes named", "classes unexplained", "edited", "log length ratio",
            "abs log length ratio", "source similarity", "source description cosine",
            "source title cosine", "steps with named objects", "named classes missing",
            "log implicit rate", "mention order", "classes", "log length x log words",
            "named actions used", "actions named", "source words cosine")


@dataclass(frozen=True)
class Candidate:
    """A candidate program, the training example it came from, and whether it was edited."""

    program: Program
    tokens: tuple
    source: int
    edited: bool


@dataclass
class Bank:
    """The training side: step tokens, their pairwise LCS, sentence vectors, lexicon."""

    train: list[Example]
    lexicon: ObjectLexicon = field(init=False)

    def __post_init__(self) -> None:
        self.tokens = [tuple(step_tokens(e.program)) for e in self.train]
        n = len(self.train)
        self.lcs = np.eye(n)
        for i in range(n):
            for j in range(i + 1, n):
                self.lcs[i, j] = self.lcs[j, i] = normalized_lcs(self.tokens[i], self.tokens[j])
        from homesim.learn.embeddings import example_vectors

        self.desc, self.title = example_vectors(self.train)
        self.lengths = np.array([len(t) for t in self.tokens], dtype=float)
        self.lexicon = ObjectLexicon.fit(self.train)
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
            from homesim.learn.embeddings import example_vectors

            desc, title = example_vectors([self.example])
            self.vectors = (desc[0], title[0])
        self.desc, self.title = self.vectors
        self.sims = 0.5 * (self.bank.desc @ self.desc) + 0.5 * (self.bank.title @ self.title)
        sims = np.where(self.allowed, self.sims, -np.inf)
        top = sims.max()
        self.weights = {}
        for tau in TAUS:
            w = np.where(self.allowed, np.exp((sims - top) / tau), 0.0)
            self.weights[tau] = w / w.sum()
        self.named = self.bank.lexicon.mentions(self.example.text)
        self.verbs = self.bank.lexicon.actions(self.example.text)
        self.overlap = self.bank.bags @ _bag(self.example.text, self.bank.idf)
        self.near = np.argsort(-self.weights[TAUS[1]], kind="stable")[:NEAR]
        self.candidates = self._candidates(sims)

    def activity_programs(self) -> np.ndarray:
        """Indices of the training programs of the query's activity that it may see."""
        return np.flatnonzero(self.allowed & self.bank.activity_mask(self.example.activity))

    def _candidates(self, sims: np.ndarray) -> list[Candidate]:
        sources: list[int] = []
        best: dict[float, int] = {}
        for tau in TAUS:
            expected = np.where(self.allowed, self.weights[tau] @ self.bank.lcs, -1.0)
            ranked = [int(j) for j in np.argsort(-expected, kind="stable")[:TOP_K]]
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
            for q in substitutions(program, self.named):
                add(q, j, True)
        for c in out[:DROP_FROM]:
            for p in drops(c.program, self.named, self.bank.lexicon.implicit_rate):
                add(p, c.source, True)
        for j, p in self._medians(best):
            if p.steps:
                add(p, j, True)
        return out

    def _medians(self, best: dict[float, int]) -> list[tuple[int, Program]]:
        """(start, median) pairs: the median of the `NEAR` nearest neighbours under each tau's
        weights, started from that tau's best expected-LCS program (`best`), and the median
        of the programs of the query's activity (uniform weights) started from their medoid."""
        from homesim.learn.median import Medians, uniform_median

        bank, out = self.bank, []
        references = [bank.train[k].program for k in self.near]
        for tau in TAUS:
            medians = Medians(references, self.weights[tau][self.near])
            out.append((best[tau], medians.median(bank.train[best[tau]].program)))
        same = self.activity_programs()
        if len(same):
            start = bank.medoid(same)
            out.append((start, uniform_median([bank.train[k].program for k in same],
                                              bank.train[start].program)))
        return out

    def features(self) -> np.ndarray:
        """(candidates, len(FEATURES)) feature rows."""
        return np.array([self._row(c) for c in self.candidates])

    def _row(self, c: Candidate) -> list[float]:
        bank, near = self.bank, self.near
        lcs = (np.array([normalized_lcs(c.tokens, bank.tokens[k]) for k in near]) if c.edited
               else bank.lcs[c.source][near])
        expected = [float(self.weights[t][near] @ lcs / max(self.weights[t][near].sum(), 1e-12))
                    for t in TAUS]
        used, named = classes(c.program), self.named
        from homesim.ground.prepare import ROOM_NAMES

        size = max(len(used), 1)
        ratio = np.log(len(c.tokens) / (self.weights[TAUS[2]] @ bank.lengths)) if c.tokens else -3.0
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
                len(acts & self.verbs) / max(len(acts), 1), float(self.overlap[c.source])]


def substitutions(program: Program, named: frozenset[str]) -> list[Program]:
    """`program` with one unnamed class replaced by a named one it lacks (every such swap the
    actions allow), then with the first allowed swap repeated up to `MAX_SUBSTITUTIONS` times."""
    singles = _swaps(program, named)
    chain, current = [], program
    for _ in range(MAX_SUBSTITUTIONS):
        swaps = _swaps(current, named)
        if not swaps:
            break
        current = swaps[0]
        chain.append(current)
    return singles + chain[1:]


def drops(program: Program, named: frozenset[str],
          implicit_rate: Callable[[str], float]) -> list[Program]:
    """`program` without the steps that use one class the text does not name (rooms kept),
    for each such class, then without all of those whose `implicit_rate` is below
    `CHAIN_IMPLICIT` at once; never an empty program."""
    from homesim.ground.prepare import ROOM_NAMES

    unnamed = sorted(classes(program) - named - ROOM_NAMES)
    rare = frozenset(c for c in unnamed if implicit_rate(c) < CHAIN_IMPLICIT)
    out = [_without(program, frozenset({c})) for c in unnamed]
    if len(rare) > 1:
        out.append(_without(program, rare))
    return [p for p in out if p.steps]


def _without(program: Program, gone: frozenset[str]) -> Program:
    return program.with_steps([s for s in program.steps
                               if not any(r.name in gone for r in s.args)])


def _swaps(program: Program, named: frozenset[str]) -> list[Program]:
    used = classes(program)
    return [rename(program, old, new) for old in sorted(used - named)
            for new in sorted(named - used) if allows(program, old, new)]


def allows(program: Program, old: str, new: str) -> bool:
    """Whether every step of `program` using class `old` accepts class `new` there (the
    action catalog's property needs; a room only for a room)."""
    from homesim.ground.prepare import ROOM_NAMES
    from homesim.knowledge.objects import load_kb

    if (old in ROOM_NAMES) != (new in ROOM_NAMES):
        return False
    props = load_kb().properties(new)
    for step in program.steps:
        for position, ref in enumerate(step.args):
            if ref.name == old and not all(props & need
                                           for need in step.action.needs_of(position)):
                return False
    return True


def rename(program: Program, old: str, new: str) -> Program:
    """`program` with every object of class `old` called `new` (instances kept)."""
    from dataclasses import replace

    return program.with_steps([replace(s, args=tuple(
        replace(r, name=new) if r.name == old else r for r in s.args)) for s in program.steps])


def mention_order(objects: list[str], named: frozenset[str], text: str) -> float:
    """Share of pairs of named classes that the program first uses in the order the text
    first says them (the last word of the class name); 0.5 when fewer than two."""
    lower = text.lower()
    where = {c: lower.find(c.split("_")[-1]) for c in named}
    order = list(dict.fromkeys(o for o in objects if where.get(o, -1) >= 0))
    pairs = [where[a] < where[b] for i, a in enumerate(order) for b in order[i + 1:]]
    return float(np.mean(pairs)) if pairs else 0.5


def design(features: np.ndarray) -> np.ndarray:
    """The trees' input for one description's candidates: each feature's deviation from the
    candidates' mean, then the feature itself."""
    return np.hstack([features - features.mean(0), features])


def fit_trees(groups: list[tuple[np.ndarray, np.ndarray]],
              random_state: int | None = None) -> HistGradientBoostingRegressor:
    """Trees regressing targets centred within each group on `design` (`TREES` settings).

    `random_state` (default `TREES`'s) only picks the 10% of samples scikit-learn holds out
    for early stopping (on from 10 000 samples; it has not stopped before `max_iter` in the
    real runs), yet that moves the dev score by about .01 (docs/learn.md):
    `tools/rerank_dev.py --tree-seeds` averages over it."""
    from sklearn.ensemble import HistGradientBoostingRegressor

    x = np.vstack([design(f) for f, _ in groups])
    y = np.concatenate([t - t.mean() for _, t in groups])
    settings = TREES if random_state is None else {**TREES, "random_state": random_state}
    return HistGradientBoostingRegressor(**settings).fit(x, y)


@dataclass
class Reranker:
    """A fitted reranker (module docstring)."""

    bank: Bank
    trees: HistGradientBoostingRegressor
    likelihood: CrossFitted | None = None
    """With it, each candidate also gets `likelihood.FEATURES` (docs/learn.md: they gained on
    dev, not on test, so the table's reranker has none)."""
    inserter: Inserter | None = None
    """With it, the steps the text says that the choice lacks are inserted (`insertion`)."""
    deleter: Deleter | None = None
    """With it, the steps of the choice (after insertion) that neither the text nor the
    neighbours support are deleted (`deletion`)."""

    @classmethod
    def fit(cls, train: list[Example], holdout: str, likelihood: bool = False,
            seed: int = 0, insert: bool = True, delete: bool = True) -> Reranker:
        """Trees fitted on `train` queried against itself, hiding `holdout` (one of
        `HOLDOUTS`); `likelihood`: with the likelihood features of cross-fitted MLE models
        (trained with `seed`); `insert`: with the `insertion.Inserter` of the steps the text
        says, `delete`: also the `deletion.Deleter` of unsupported steps, fitted on the same
        queries and kept only when, cross-fitted, it raises their mean steps LCS
        (`fit_editors`)."""
        from homesim.learn.likelihood import CrossFitted

        bank = Bank(train)
        fitted = CrossFitted.fit(train, holdout, seed) if likelihood else None
        groups, queries = [], []
        for i, example in enumerate(train):
            query = Query(bank, example, ~bank.hidden(example, holdout))
            if query.candidates:
                features, targets = _labelled(query)
                if fitted is not None:
                    features = _with_likelihoods(features, query, fitted.for_training_query(i))
                groups.append((features, targets))
                queries.append((i, query))
        editors = (fit_editors(bank, holdout, queries, groups, delete) if insert
                   else (None, None))
        return cls(bank, fit_trees(groups), fitted, *editors)

    def scores(self, query: Query) -> np.ndarray:
        """(candidates,) the trees' score of each of the query's candidates."""
        features = query.features()
        if self.likelihood is not None:
            features = _with_likelihoods(features, query, self.likelihood.full)
        return np.asarray(self.trees.predict(design(features)))

    def predict(self, examples: list[Example]) -> list[Program]:
        """One program per example: the best-scoring candidate that executes in its home."""
        return [self.choose(e, partial(_executable_in, e)) for e in examples]

    def ranked(self, example: Example, vectors: tuple[np.ndarray, np.ndarray] | None = None
               ) -> tuple[Query, list[Program]]:
        """The query for an example's title and description and its candidates,
        best-scoring first (its program is not read); `vectors` as `Query` takes them."""
        query = Query(self.bank, example, np.ones(len(self.bank.train), bool), vectors)
        order = np.argsort(-self.scores(query), kind="stable")
        return query, [query.candidates[int(i)].program for i in order]

    def choose(self, example: Example, runs: Callable[[Program], bool],
               vectors: tuple[np.ndarray, np.ndarray] | None = None) -> Program:
        """The best-scoring candidate that `runs` accepts among the first
        `CHECK_EXECUTABLE` (the best one if none is), edited (`edits`) when `runs` accepts
        the result."""
        query, programs = self.ranked(example, vectors)
        chosen = next((p for p in programs[:CHECK_EXECUTABLE] if runs(p)), programs[0])
        return next((p for p in self.edits(query, chosen)
                     if p.steps != chosen.steps and runs(p)), chosen)

    def edits(self, query: Query, chosen: Program) -> list[Program]:
        """The edited choices to try, best first: with steps inserted and then deleted,
        with steps inserted only."""
        inserted = chosen if self.inserter is None else self.inserter.insert(query, chosen)
        if self.deleter is None:
            return [inserted]
        return [self.deleter.delete(query, inserted), inserted]


def cross_fitted_best(groups: list[tuple[np.ndarray, np.ndarray]], folds: list[int],
                      random_state: int | None = None) -> np.ndarray:
    """(groups,) index of each group's best-scoring candidate under trees fitted on the
    groups of the other folds (-1 where a fold has nothing to learn from)."""
    from homesim.learn.likelihood import FOLDS

    best = np.full(len(groups), -1)
    for k in range(FOLDS):
        held = [i for i, f in enumerate(folds) if f == k]
        rest = [g for g, f in zip(groups, folds, strict=True) if f != k]
        if held and rest:
            trees = fit_trees(rest, random_state)
            best[held] = [int(np.argmax(trees.predict(design(groups[i][0])))) for i in held]
    return best


def fit_editors(bank: Bank, holdout: str, queries: list[tuple[int, Query]],
                groups: list[tuple[np.ndarray, np.ndarray]], delete: bool = False
                ) -> tuple[Inserter | None, Deleter | None]:
    """The `insertion.Inserter` and `deletion.Deleter` learned from the training queries
    (`queries`: (index in training, query), their `groups` in order) without a copy in
    training, each with its cross-fitted choice, what it may read of the folds it is not in
    (`insertion.Known`), and for the deleter the steps inserted by an inserter fitted on
    those folds (`delete`; else None). The deleter is None too unless its deletions,
    cross-fitted (`cross_deleted`), raise those queries' mean steps LCS: on the stratified
    split they did at all five seeds, without their activity at three of five
    (docs/learn.md)."""
    from homesim.learn.deletion import Deleter
    from homesim.learn.insertion import Inserter

    fold_of, known = fold_knowledge(bank.train, holdout)
    query_folds = [int(fold_of[i]) for i, _ in queries]
    best = cross_fitted_best(groups, query_folds)
    chosen = [(q, known[f], q.candidates[b], f) for (_, q), f, b
              in zip(queries, query_folds, best, strict=True)
              if b >= 0 and not has_copy(bank, q.example)]
    inserter = Inserter.fit([(q, k, c.tokens) for q, k, c, _ in chosen])
    if not delete:
        return inserter, None
    written = cross_inserted([(q, k, c, f, True) for q, k, c, f in chosen])
    deleted = cross_deleted([(q, k, f, True) for q, k, _, f in chosen], written)
    if not _raises_lcs([q for q, *_ in chosen], written, deleted):
        return inserter, None
    by_fold = sorted(range(len(chosen)), key=lambda i: chosen[i][3])
    return inserter, Deleter.fit([(chosen[i][0], chosen[i][1], written[i]) for i in by_fold])


def cross_deleted(chosen: list[tuple[Query, Known, int, bool]], written: list[Program]
                  ) -> list[Program]:
    """Each (training query, what it may read, its fold, whether editors learn from it)'s
    `written` program without the steps a `deletion.Deleter` deletes that was fitted on the
    written programs of the other folds' queries editors learn from (unchanged where there
    are none)."""
    from homesim.learn.deletion import Deleter
    from homesim.learn.likelihood import FOLDS

    deleted = list(written)
    for fold in range(FOLDS):
        deleter = Deleter.fit([(q, k, p) for (q, k, f, learns), p
                               in zip(chosen, written, strict=True) if f != fold and learns])
        if deleter is not None:
            for i, (q, k, f, _) in enumerate(chosen):
                if f == fold:
                    deleted[i] = deleter.delete(q, written[i], k)
    return deleted


def _raises_lcs(queries: list[Query], before: list[Program], after: list[Program]) -> bool:
    """Whether `after` has a higher mean steps LCS to the queries' own programs."""
    def mean(programs: list[Program]) -> float:
        return float(np.mean([lcs_steps(p, q.example.program)
                              for p, q in zip(programs, queries, strict=True)]))

    return bool(queries) and mean(after) > mean(before)


def cross_inserted(chosen: list[tuple[Query, Known, Candidate, int, bool]]) -> list[Program]:
    """Each (training query, what it may read, its cross-fitted choice, its fold, whether
    editors learn from it)'s choice with the steps inserted by an `insertion.Inserter`
    fitted on the queries of the other folds that editors learn from (the choice unchanged
    where there are none)."""
    from homesim.learn.insertion import Inserter
    from homesim.learn.likelihood import FOLDS

    written = [c.program for _, _, c, _, _ in chosen]
    for fold in range(FOLDS):
        inserter = Inserter.fit([(q, k, c.tokens) for q, k, c, f, learns in chosen
                                 if f != fold and learns])
        if inserter is not None:
            for i, (q, k, c, f, _) in enumerate(chosen):
                if f == fold:
                    written[i] = inserter.insert(q, c.program, k)
    return written


def fold_knowledge(train: list[Example], holdout: str) -> tuple[np.ndarray, list[Known]]:
    """Each training example's cross-validation fold (`likelihood.folds`), and for each fold
    what its training queries' editors may read: the lexicon fitted on, and the programs of,
    the other folds."""
    from homesim.learn.insertion import Known
    from homesim.learn.likelihood import FOLDS, folds

    fold_of = np.array(folds(train, holdout))
    return fold_of, [Known(ObjectLexicon.fit([e for e, f in zip(train, fold_of, strict=True)
                                               if f != k]), fold_of != k)
                     for k in range(FOLDS)]


def has_copy(bank: Bank, example: Example) -> bool:
    """Whether another training example has the same steps as `example` (a training one).
    The editors learn only from training queries without one: a copy the query may not see
    would make a count move with whether its program has a step."""
    return int(bank.hidden(example, "program").sum()) > 1


def _executable_in(example: Example, program: Program) -> bool:
    from homesim.learn.execution import executable

    return executable(program, example)


def _with_likelihoods(features: np.ndarray, query: Query, t2p: Text2Prog) -> np.ndarray:
    """The query's feature rows with `likelihood.FEATURES` under `t2p` appended."""
    from homesim.learn.likelihood import likelihoods

    programs = [c.program for c in query.candidates]
    return np.hstack([features, likelihoods(t2p, query.example, programs)])


def _labelled(query: Query) -> tuple[np.ndarray, np.ndarray]:
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

