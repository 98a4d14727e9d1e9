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
   `near` nearest neighbours, searched from that tau's best program; and the median of the
   programs of the query's activity, searched from their medoid (`base.Query`).
3. **Score.** Gradient-boosted regression trees (`trees`) over features of (x, candidate)
   (`base.feature_names`): the expected LCS under each tau against the `near` nearest
   neighbours, the share of named classes the candidate uses and of its classes that are
   named, how often its unnamed classes are left implicit in training, whether the mention
   order agrees, its length against the neighbours' and the text's, its source's
   similarity, whether it was edited.
4. **Choice.** The best-scoring candidate that executes in the example's home
   (`execution.executable`, checked best-first among `check_executable`; the best one if
   none does).
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
activity. Their settings (`trees`) were chosen by 5-fold cross-validation over those
training queries and on the dev split, never on test. Everything is deterministic.

Modules: `config` (every setting), `base` (the bank, the query, its candidates and
features), `candidates` (the substitutions and drops), `median`, `lexicon`, `trees` (the
scorer), `insertion` and `deletion` (the editors), `folds` and `editors` (how the editors
learn without a leak).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from homesim.learn.data import Example
from homesim.learn.execution import executable
from homesim.learn.rerank.base import Bank, Query, labelled
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.deletion import Deleter
from homesim.learn.rerank.editors import fit_editors
from homesim.learn.rerank.insertion import Inserter
from homesim.learn.rerank.trees import design, fit_trees
from homesim.program.model import Program

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

    @classmethod
    def fit(cls, train: list[Example], holdout: str, insert: bool = True,
            delete: bool = True, config: RerankConfig | None = None) -> Reranker:
        """Trees fitted on `train` queried against itself, hiding `holdout` (one of
        `HOLDOUTS`), with `config` (default: `RerankConfig()`); `insert`: with the
        `insertion.Inserter` of the steps the text says, `delete`: also the
        `deletion.Deleter` of unsupported steps, fitted on the same queries and kept only
        when, cross-fitted, it raises their mean steps LCS (`editors.fit_editors`)."""
        bank = Bank(train, config or RerankConfig())
        groups, queries = [], []
        for i, example in enumerate(train):
            query = Query(bank, example, ~bank.hidden(example, holdout))
            if query.candidates:
                groups.append(labelled(query))
                queries.append((i, query))
        editors = (fit_editors(bank, holdout, queries, groups, delete) if insert
                   else (None, None))
        return cls(bank, fit_trees(groups, bank.config), *editors)

    @property
    def config(self) -> RerankConfig:
        """The settings the model was fitted with (saved with it, in its bank)."""
        return self.bank.config

    def scores(self, query: Query) -> np.ndarray:
        """(candidates,) the trees' score of each of the query's candidates."""
        return np.asarray(self.trees.predict(design(query.features())))

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
        `config.check_executable` (the best one if none is), edited (`edits`) when `runs`
        accepts the result."""
        query, programs = self.ranked(example, vectors)
        first = programs[:self.config.check_executable]
        chosen = next((p for p in first if runs(p)), programs[0])
        return next((p for p in self.edits(query, chosen)
                     if p.steps != chosen.steps and runs(p)), chosen)

    def edits(self, query: Query, chosen: Program) -> list[Program]:
        """The edited choices to try, best first: with steps inserted and then deleted,
        with steps inserted only."""
        inserted = chosen if self.inserter is None else self.inserter.insert(query, chosen)
        if self.deleter is None:
            return [inserted]
        return [self.deleter.delete(query, inserted), inserted]


def _executable_in(example: Example, program: Program) -> bool:
    return executable(program, example)
