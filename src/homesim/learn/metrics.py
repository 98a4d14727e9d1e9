"""Table 3 rows: the normalised LCS scores of `homesim.program.metrics`, and executability.

LCS is divided by the longer of the two sequences (the paper's normalisation). Steps are
compared by action and object class names; instance numbers are ignored.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from homesim.program.metrics import ProgramScores, executability_rate, score_programs
from homesim.program.model import Program


def lcs_scores(pred: Program, truth: Program) -> tuple[float, float, float]:
    """(actions, objects, steps) normalised LCS of one prediction."""
    s = ProgramScores.of(pred, truth)
    return s.actions, s.objects, s.steps


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
    if len(preds) != len(executable):
        raise ValueError(f"{len(preds)} predictions but {len(executable)} executability flags")
    s = score_programs(preds, truths)
    return Scores(s["actions"], s["objects"], s["steps"], s["mean"],
                  100.0 * executability_rate(executable), len(preds))
