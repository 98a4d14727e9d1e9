"""Steps the description says, inserted into the reranker's choice.

The reranker chooses a whole program; descriptions often spell out a step that program
lacks ("look at the light switch", "put the book on the table"). Per clause of the text (split
at punctuation, "and", "then"), a *proposal* is every step token seen in the programs the
query may see whose action a word of the clause links to and whose objects the clause all
names (`lexicon.ObjectLexicon`). A classifier (gradient-boosted trees) predicts
whether each proposal the choice lacks is in the true program, from its support among the
query's neighbours and in its activity, how common it is, its clause, how it relates to
the choice, and how close the step in words is to the clauses proposing it in MiniLM's
sentence space (`closeness`: the lexicon links "grab" to both GRAB and FIND; the encoder
tells which one "grab the remote" says) (`PROPOSAL_FEATURES`). Those above the insert
threshold, most likely first, are inserted one by one at the position of highest expected
steps LCS to the query's nearest neighbours (`median.Medians`, weights at the position
tau). The settings (classifier, threshold, tau) are the bank's `config.RerankConfig`.

The classifier learns from the training queries without a copy in training, each with the
choice of trees fitted without its cross-validation fold, proposals from a lexicon fitted
without that fold and counts over the programs of the other folds only (`folds.Known`), so that
they look as they will for a test description: counted over the programs the query may see,
a count moved with whether its own hidden program had the step, and the classifier learned
that. Why insert at all: proposals the choice lacks are in the truth about one time in six,
but the classifier finds those it can trust (docs/learn.md, "Steps the text says").
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeVar

import numpy as np

from homesim.learn.embeddings import lone_sentence_vectors
from homesim.learn.rerank.base import Query
from homesim.learn.rerank.config import RerankConfig
from homesim.learn.rerank.folds import Known
from homesim.learn.rerank.lexicon import ObjectLexicon, words
from homesim.learn.rerank.median import Medians
from homesim.program.actions import ACTIONS
from homesim.program.metrics import StepToken, step_tokens
from homesim.program.model import Program, Step

if TYPE_CHECKING:
    from sklearn.ensemble import HistGradientBoostingClassifier

PROPOSAL_FEATURES = ("neighbour support", "activity support", "share of programs with it",
                     "objects", "action", "clause position", "proposals in its clause",
                     "clause words", "clause classes", "clause actions", "proposals",
                     "choice has its objects", "choice has its action", "choice length",
                     "phrase cosine to its clause", "against its clause's closest")
CLAUSE_BREAK = re.compile(r"[.,;!?\n]|\band\b|\bthen\b")


def support(query: Query, token: StepToken, known: Known) -> tuple[float, float, float]:
    """The step's weighted share among the query's nearest neighbours (weights at the
    position tau), among the counted programs of its activity (0 when none) and among all
    counted programs (those the query may see)."""
    has = query.bank.having(token)
    weights = query.weights[query.bank.config.position_tau][query.near]
    counted = known.counted & query.allowed
    same = counted & query.bank.activity_mask(query.example.activity)
    return (float(weights @ has[query.near].astype(float) / max(weights.sum(), 1e-12)),
            float(has[same].mean()) if same.any() else 0.0,
            float(has[counted].mean()) if counted.any() else 0.0)


def clauses(text: str) -> list[str]:
    """The lower-case clauses of a text: split at punctuation, "and" and "then"."""
    return [c for c in CLAUSE_BREAK.split(text.lower()) if c.strip()]


@dataclass(frozen=True)
class Proposal:
    """A step the text proposes, and what is known of it before looking at a choice."""

    token: StepToken
    step: Step
    clause_features: tuple[float, ...]
    """Of the first clause proposing it: its position, proposals, words, classes, actions."""
    clauses: tuple[int, ...]
    """The indices of the clauses proposing it."""


def proposals(query: Query, lexicon: ObjectLexicon) -> list[Proposal]:
    """The steps the query's text proposes, clause by clause (within one, in order of first
    appearance in the training programs the query may see), each once."""
    bank = query.bank
    first: dict[StepToken, tuple[Step, tuple[float, ...]]] = {}
    where: dict[StepToken, list[int]] = {}
    parts = clauses(query.example.text)
    for i, clause in enumerate(parts):
        acts, named = lexicon.actions(clause), lexicon.mentions(clause)
        here = sorted((_first_seen(query, t), t) for t, ks in bank.step_index.items()
                      if t[0] in acts and t[1] and all(o in named for o in t[1])
                      and query.allowed[ks].any())
        shape = (i / max(len(parts) - 1, 1), len(here), len(words(clause)), len(named),
                 len(acts))
        for (k, position), token in here:
            first.setdefault(token, (bank.train[k].program.steps[position], shape))
            where.setdefault(token, []).append(i)
    return [Proposal(t, step, shape, tuple(where[t])) for t, (step, shape) in first.items()]


def step_phrase(step: Step) -> str:
    """A step in words: "[SwitchOn] <television>" -> "switch on television"."""
    return token_phrase((step.action.key, tuple(ref.name for ref in step.args)))


def token_phrase(token: StepToken) -> str:
    """A step token in words: ("SWITCHON", ("television",)) -> "switch on television"."""
    verb = re.sub(r"(?<!^)([A-Z])", r" \1", ACTIONS[token[0]].name).lower()
    return " ".join([verb, *(name.replace("_", " ") for name in token[1])])


def closeness(query: Query, found: list[Proposal]) -> np.ndarray:
    """(proposals, 2): the MiniLM cosine of each proposal's `step_phrase` to the closest
    clause proposing it, and the most by which it exceeds (<= 0: falls short of) the
    highest cosine of any of `found` to one of those clauses."""
    if not found:
        return np.zeros((0, 2))
    parts = lone_sentence_vectors(clauses(query.example.text))
    cosine = lone_sentence_vectors([step_phrase(p.step) for p in found]) @ parts.T
    closest: dict[int, float] = {}
    for j, p in enumerate(found):
        for i in p.clauses:
            closest[i] = max(closest.get(i, -1.0), float(cosine[j, i]))
    return np.array([[max(float(cosine[j, i]) for i in p.clauses),
                      max(float(cosine[j, i]) - closest[i] for i in p.clauses)]
                     for j, p in enumerate(found)])


def _first_seen(query: Query, token: StepToken) -> tuple[int, int]:
    """(program, step) where `token` first occurs in the programs the query may see."""
    ks = query.bank.step_index[token]
    k = int(ks[query.allowed[ks]][0])
    return k, query.bank.tokens[k].index(token)


def proposal_features(query: Query, found: list[Proposal], choice: tuple, known: Known,
                      action_codes: dict[str, int]) -> np.ndarray:
    """(proposals, len(PROPOSAL_FEATURES)) rows for the proposals, against the choice's
    step tokens `choice`; `action_codes` numbers action keys (new ones appended)."""
    used = {o for t in choice for o in t[1]}
    acts = {t[0] for t in choice}
    rows = [[*support(query, p.token, known), len(p.token[1]),
             action_codes.setdefault(p.token[0], len(action_codes)), *p.clause_features,
             len(found), float(all(o in used for o in p.token[1])), float(p.token[0] in acts),
             len(choice), *close] for p, close in zip(found, closeness(query, found), strict=True)]
    return np.array(rows, dtype=float).reshape(len(found), len(PROPOSAL_FEATURES))


def lacking(found: list[Proposal], choice: tuple) -> list[Proposal]:
    """The proposals whose step the choice does not have."""
    return [p for p in found if p.token not in choice]


@dataclass
class StepClassifier:
    """A fitted classifier of steps (in the true program or not) and the action numbering
    its features use."""

    classifier: HistGradientBoostingClassifier
    action_codes: dict[str, int]

    @classmethod
    def fitted(cls: type[C], rows: list[np.ndarray], labels: list[bool],
               codes: dict[str, int], config: RerankConfig) -> C | None:
        """Trees (`config.classifier`) fitted on feature `rows` and `labels`; None when the
        labels are all of one kind (or there are none)."""
        # deferred: scikit-learn takes seconds to import
        from sklearn.ensemble import HistGradientBoostingClassifier

        if len(set(labels)) < 2:
            return None
        classifier = HistGradientBoostingClassifier(**config.classifier)
        return cls(classifier.fit(np.vstack(rows), np.array(labels)), codes)

    def chances(self, rows: np.ndarray) -> np.ndarray:
        """(rows,) the probability that each step is in the truth."""
        return np.asarray(self.classifier.predict_proba(rows)[:, 1])


C = TypeVar("C", bound=StepClassifier)


@dataclass
class Inserter(StepClassifier):
    """Proposals' classifier (module docstring)."""

    @classmethod
    def fit(cls, examples: list[tuple[Query, Known, tuple]], config: RerankConfig
            ) -> Inserter | None:
        """From (training query, what it may read without its fold, cross-fitted choice's
        step tokens) triples: label each proposal the choice lacks by whether the query's
        own program has it. None when there is nothing (or only one kind) to learn from."""
        codes: dict[str, int] = {}
        rows, labels = [], []
        for query, known, choice in examples:
            found = lacking(proposals(query, known.lexicon), choice)
            if found:
                truth = set(step_tokens(query.example.program))
                rows.append(proposal_features(query, found, choice, known, codes))
                labels += [p.token in truth for p in found]
        return cls.fitted(rows, labels, codes, config)

    def probabilities(self, query: Query, found: list[Proposal], choice: tuple, known: Known
                      ) -> np.ndarray:
        """(proposals,) the probability that each is in the truth."""
        if not found:
            return np.zeros(0)
        return self.chances(proposal_features(query, found, choice, known,
                                              dict(self.action_codes)))

    def insert(self, query: Query, program: Program, known: Known | None = None) -> Program:
        """`program` (the choice for `query`) with the likely proposals it lacks inserted
        (module docstring); `known` defaults to `Known.everything`."""
        known = known or Known.everything(query)
        choice = tuple(step_tokens(program))
        found = lacking(proposals(query, known.lexicon), choice)
        chance = self.probabilities(query, found, choice, known)
        likely = [found[int(i)] for i in np.argsort(-chance, kind="stable")
                  if chance[int(i)] >= query.bank.config.insert_threshold]
        if not likely:
            return program
        return insert_steps(query, program, [p.step for p in likely])


def insert_steps(query: Query, program: Program, steps: list[Step]) -> Program:
    """`program` with each of `steps` inserted in turn at the position of highest expected
    steps LCS to the query's nearest neighbours (weights at the position tau; ties: the
    earliest)."""
    bank, near = query.bank, query.near
    medians = Medians([bank.train[k].program for k in near],
                      query.weights[bank.config.position_tau][near], bank.config.median)
    current = medians.encode(program)
    for step in steps:
        current = medians.best_insertion(current, medians.symbol(step))
    return medians.decode(program, current)
