"""Table 3 rows: the normalised LCS scores of `homesim.program.metrics`, and executability.

LCS is divided by the longer of the two sequences (the paper's normalisation). Steps are
compared by action and object class names; instance numbers are ignored.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from itertools import pairwise

from homesim.program.metrics import (
    ProgramScores,
    executability_rate,
    score_programs,
    step_tokens,
)
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


SOLVED_LCS = 0.5
"""Steps LCS a prediction needs (besides executing) to count as solved."""


def repeats(program: Program) -> int:
    """Steps equal to the step before them (action and object classes)."""
    tokens = step_tokens(program)
    return sum(a == b for a, b in pairwise(tokens))


def example_scores(pred: Program, truth: Program, runs_here: bool,
                   runs_elsewhere: float | None) -> dict:
    """One prediction's scores: the three LCS, whether it executes in the example's home,
    the share of the other built-in homes it executes in, whether it is solved
    (executes here and steps LCS >= `SOLVED_LCS`: an empty or one-step program is not),
    its length and its repeated steps."""
    s = ProgramScores.of(pred, truth)
    return {"action": s.actions, "objects": s.objects, "steps": s.steps, "mean": s.mean,
            "simulator": float(runs_here), "elsewhere": runs_elsewhere,
            "solved": float(runs_here and s.steps >= SOLVED_LCS),
            "length": len(pred), "repeats": repeats(pred)}
