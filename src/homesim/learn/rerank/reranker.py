"""Learned reranker: retrieve training programs, substitute the objects the text names, rerank.

For a description x (the settings named here are fields of `config.RerankConfig`):

1. **Weights.** Every training example j gets w_j = softmax_j(sim(x, j) / tau), sim the
   mean of the MiniLM cosines of the descriptions and of the titles, at each of `taus`.
2. **Candidates.** The `top_k` training programs of highest expected steps LCS under each
   weighting (minimum Bayes risk: tau -> 0 is nearest-neighbour retrieval, uniform weights
   within an activity the title-medoid), the 3 most similar ones, and their *substitutions*:
   an object class the text does not name (`lexicon.ObjectLexicon`) replaced by one it
   names and the program lacks, where every step using it allows the new class (the
   action catalog's property needs, rooms only for rooms); singly and greedily all at once.
   Then the *drops* of the first `drop_from` candidates: the steps using one class the text
   does not name (nor a room) left out, singly, and all such classes that training usually
   names (implicit rate below `chain_implicit`) left out at once. Last the *medians*
   (`median.Medians`): under each tau, the step sequence of highest expected LCS to the
   `near` nearest neighbours, searched from that tau's best program; and the *typical
   program*: the median of the programs of the query's activity, searched from their
   medoid, or of the nearest title's activity when the query's is not there (`support`).
3. **Score.** Gradient-boosted regression trees (`trees`) over features of (x, candidate)
   (`base.feature_names`): the expected LCS under each tau against the `near` nearest
   neighbours, the share of named classes the candidate uses and of its classes that are
   named, how often its unnamed classes are left implicit in training, whether the mention
   order agrees, its length against the neighbours' and the text's, its source's
   similarity, whether it was edited, whether it is the typical program, how many words the
   description says beyond the title.
4. **Choice.** For a bare title of an activity in training, the typical program
   (repaired where it does not run in the example's home, `execution.repaired`): a title
   names no object and no step to choose by. (For an activity not in training the typical
   program is a guess from the nearest title, and the trees choose better.) Otherwise the
   best-scoring candidate, or the typical program when its score is within the margin of
   the text's support level (`support`: a few words, more), that executes in the home
   (`execution.executable`, checked best-first among `check_executable`; if none does, the
   best one repaired, or else the steps of it that run there, `runnable_part`), so the
   answer always executes.
5. **Insertion.** The steps the text says that the choice lacks and that a classifier
   finds likely, inserted where the neighbours have them (`insertion`), when the result
   still executes there.
6. **Deletion.** Where the model kept its deleter (`editors.fit_editors`), the steps of
   that result that a second classifier finds unlikely deleted (`deletion`), when the
   result still executes there.

The trees regress the candidates' steps LCS to the truth, centred within each description
(only the order within a description matters), on each feature and on its deviation from
the description's mean; they are fitted on training descriptions each queried against the
rest of the training set with what the split hides removed: for the stratified split the
training programs equal to its own, for leave-activities-out every program of its
activity; each also cut to its title alone and to its first four words (`support.reduced`),
so that they learn what a short text supports. The typical program's margins are chosen by
cross-validation over those same queries (`support.choose_margins`). The trees' settings
(`trees`) were chosen by 5-fold cross-validation over the training queries and on the dev
split, never on test. Everything is deterministic.

Modules: `config` (every setting), `base` (the bank, the query, its candidates and
features), `candidates` (the substitutions and drops), `median`, `lexicon`, `support` (what
a short text supports), `trees` (the scorer), `insertion` and `deletion` (the editors),
`folds` and `editors` (how the editors learn without a leak).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from homesim.learn.data import Example
from homesim.learn.execution import executable, repaired
from homesim.learn.rerank.base import Bank, Query, labelled
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.deletion import Deleter
from homesim.learn.rerank.editors import fit_editors
from homesim.learn.rerank.folds import folds
from homesim.learn.rerank.insertion import Inserter
from homesim.learn.rerank.support import Scored, choose_margins, gated, reduced, support_level
from homesim.learn.rerank.trees import best_of, cross_fitted_scores, design, fit_trees
from homesim.program.model import Program

CHOICE = 2
"""Bumped when `Reranker.choose` writes otherwise from the same fitted model (2: a bare
title of an activity in training always gets the typical program, and a candidate that
does not run is repaired before it is cut to the steps that run)."""
Repair = Callable[[Program], "Program | None"]
"""A program mended to run (repair's inserted steps) in the home at hand, or None."""

if TYPE_CHECKING:
    from sklearn.ensemble import HistGradientBoostingRegressor

HOLDOUTS = ("program", "activity")
"""What a training query may not see of the rest of training: programs equal to its own
(stratified split) or its whole activity (leave-activities-out)."""


@dataclass
class Reranker:
    """A fitted reranker (module docstring); its settings are its bank's (`config`)."""

    bank: Bank
    trees: HistGradientBoostingRegressor
    inserter: Inserter | None = None
    """With it, the steps the text says that the choice lacks are inserted (`insertion`)."""
    deleter: Deleter | None = None
    """With it, the steps of the choice (after insertion) that neither the text nor the
    neighbours support are deleted (`deletion`)."""
    typical_margins: tuple[float, ...] = ()
    """For each support level of the text (`support.support_level`), the typical program is
    chosen when its score is less than this behind the best candidate's (`support.gated`;
    chosen by cross-validation, `support.choose_margins`); none: never."""

    @classmethod
    def fit(cls, train: list[Example], holdout: str, insert: bool = True,
            delete: bool = True, config: RerankConfig | None = None) -> Reranker:
        """Trees fitted on `train` queried against itself, hiding `holdout` (one of
        `HOLDOUTS`), with `config` (default: `RerankConfig()`); `insert`: with the
        `insertion.Inserter` of the steps the text says, `delete`: also the
        `deletion.Deleter` of unsupported steps, fitted on the same queries and kept only
        when, cross-fitted, it raises their mean steps LCS (`editors.fit_editors`). The
        trees also learn from the descriptions cut short (`support`), and the margin of
        the typical program is chosen by cross-validation over all those queries."""
        bank = Bank(train, config or RerankConfig())
        fold_of = folds(train, holdout, bank.config.folds)
        queries, short = [], []
        for i, example in enumerate(train):
            allowed = ~bank.hidden(example, holdout)
            query = Query(bank, example, allowed)
            if query.candidates:
                queries.append((i, query))
                short += [(i, q) for q in (Query(bank, reduced(example, n), allowed)
                                           for n in bank.config.reduced) if q.candidates]
        everything = queries + short
        groups = [labelled(q) for _, q in everything]
        scores = cross_fitted_scores(groups, [fold_of[i] for i, _ in everything], bank.config)
        edges = bank.config.support_edges
        margins = choose_margins(_scored(everything, groups, scores, edges),
                                 bank.config.typical_margins, len(edges) + 1)
        full = len(queries)
        editors = (fit_editors(bank, holdout, queries, groups[:full], delete,
                               best_of(scores[:full])) if insert else (None, None))
        return cls(bank, fit_trees(groups, bank.config), *editors, margins)

    @property
    def config(self) -> RerankConfig:
        """The settings the model was fitted with (saved with it, in its bank)."""
        return self.bank.config

    def margin(self, example: Example) -> float:
        """The typical program's margin for the example's text (`typical_margins`)."""
        if not self.typical_margins:
            return 0.0
        return self.typical_margins[support_level(example, self.config.support_edges)]

    def scores(self, query: Query) -> np.ndarray:
        """(candidates,) the trees' score of each of the query's candidates."""
        return np.asarray(self.trees.predict(design(query.features())))

    def predict(self, examples: list[Example]) -> list[Program]:
        """One program per example: the best-scoring candidate that executes in its home."""
        return [self.choose(e, partial(_executable_in, e), repair=partial(_repaired_in, e))
                for e in examples]

    def ranked(self, example: Example, vectors: tuple[np.ndarray, np.ndarray] | None = None
               ) -> tuple[Query, list[Program]]:
        """The query for an example's title and description and its candidates,
        best-scoring first, the typical program first where the text's margin says so
        (`support.gated`; its program is not read); `vectors` as `Query` takes them."""
        query = Query(self.bank, example, np.ones(len(self.bank.train), bool), vectors)
        scores = self.scores(query)
        first = gated(scores, query.typical, self.margin(example))
        order = [first, *(int(i) for i in np.argsort(-scores, kind="stable") if i != first)]
        return query, [query.candidates[i].program for i in order]

    def choose(self, example: Example, runs: Callable[[Program], bool],
               vectors: tuple[np.ndarray, np.ndarray] | None = None,
               repair: Repair | None = None) -> Program:
        """The best-scoring candidate that `runs` accepts among the first
        `config.check_executable`, edited (`edits`) when `runs` accepts the result. If
        none runs, the best one as `repair` mends it, or else the steps of it that run
        (`runnable_part`): what it returns always runs. Where the text says nothing beyond
        its title (support level 0, `support`) and its activity is in training, the
        activity's typical program is written unedited whatever the trees score (there is
        nothing to edit or choose by), mended by `repair` where it does not run."""
        query, programs = self.ranked(example, vectors)
        bare = support_level(example, self.config.support_edges) == 0
        if bare and query.typical >= 0 and len(query.activity_programs()):
            typical = query.candidates[query.typical].program
            mended = typical if runs(typical) else (repair(typical) if repair else None)
            if mended is not None:
                return mended
        first = programs[:self.config.check_executable]
        chosen = next((p for p in first if runs(p)), None)
        if chosen is None:
            chosen = (repair(programs[0]) if repair else None) or runnable_part(programs[0],
                                                                              runs)
        return next((p for p in self.edits(query, chosen)
                     if p.steps != chosen.steps and runs(p)), chosen)

    def edits(self, query: Query, chosen: Program) -> list[Program]:
        """The edited choices to try, best first: with steps inserted and then deleted,
        with steps inserted only."""
        inserted = chosen if self.inserter is None else self.inserter.insert(query, chosen)
        if self.deleter is None:
            return [inserted]
        return [self.deleter.delete(query, inserted), inserted]


def _scored(queries: list[tuple[int, Query]], groups: list[tuple[np.ndarray, np.ndarray]],
            scores: list[np.ndarray | None], edges: tuple[int, ...]) -> list[Scored]:
    """The cross-fitted queries `support.choose_margins` reads (those with scores), with
    their support levels under `edges`."""
    return [(lcs, s, q.typical, support_level(q.example, edges))
            for (_, q), (_, lcs), s in zip(queries, groups, scores, strict=True) if s is not None]


def runnable_part(program: Program, runs: Callable[[Program], bool]) -> Program:
    """The steps of `program` that `runs` accepts, kept in order: each step is kept when
    the steps kept before it and it run (so the result runs; at worst it is empty)."""
    kept: tuple = ()
    for step in program.steps:
        if runs(Program((*kept, step))):
            kept = (*kept, step)
    return Program(kept)


def _executable_in(example: Example, program: Program) -> bool:
    return executable(program, example)


def _repaired_in(example: Example, program: Program) -> Program | None:
    return repaired(program, example)
