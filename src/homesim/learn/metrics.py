"""Table 3 scores: normalised LCS of actions, objects and steps, and executability.

LCS is divided by the longer of the two sequences (the paper's normalisation). Steps are
compared by action and object class names; instance numbers are ignored.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from homesim.learn._pending import lcs_length
from homesim.learn.vocab import step_key
from homesim.program.model import Program


def _norm_lcs(a: list, b: list) -> float:
    longest = max(len(a), len(b))
    return 1.0 if longest == 0 else lcs_length(a, b) / longest


def lcs_scores(pred: Program, truth: Program) -> tuple[float, float, float]:
    """(actions, objects, steps) normalised LCS of one prediction."""
    actions = _norm_lcs([s.action.key for s in pred], [s.action.key for s in truth])
    objects = _norm_lcs([r.name for s in pred for r in s.args],
                        [r.name for s in truth for r in s.args])
    steps = _norm_lcs([step_key(s) for s in pred], [step_key(s) for s in truth])
    return actions, objects, steps


@dataclass(frozen=True)
class Scores:
    """One row of Table 3 (LCS as fractions, simulator as a percentage)."""

    action: float
    objects: float
    steps: float
    mean: float
    simulator: float
    n: int

    def to_dict(self) -> dict:
        return asdict(self)


def score(preds: list[Program], truths: list[Program], executable: list[bool]) -> Scores:
    """Average the LCS scores and the executability of predictions against the truth."""
    if not preds or len(preds) != len(truths) or len(preds) != len(executable):
        raise ValueError("need as many predictions as true programs and flags, at least one")
    rows = [lcs_scores(p, t) for p, t in zip(preds, truths, strict=True)]
    n = len(rows)
    action, objects, steps = (sum(r[k] for r in rows) / n for k in range(3))
    return Scores(action, objects, steps, (action + objects + steps) / 3,
                  100.0 * sum(executable) / n, n)
