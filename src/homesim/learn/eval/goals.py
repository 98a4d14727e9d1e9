"""The goals the evaluation is held to (issues 18 and 44), each a paired steps-LCS gap
between a model row and a baseline on one split of the real data.

A goal is met when the gap's mean over seeds reaches its margin, or, for a goal on the
interval (`Goal.on_lower`), when the 95% paired bootstrap interval's lower bound does.
`homesim learn table` checks them on the development seeds and on the locked ones
(`splits`), side by side; the locked seeds' verdict is the one that counts.
"""

from __future__ import annotations

from dataclasses import dataclass

from homesim.learn.eval.experiment import RERANK_ROW, TITLE_ROW


@dataclass(frozen=True)
class Goal:
    """`row` at least `margin` steps LCS above `baseline` on `split` (real data)."""

    split: str
    row: str
    baseline: str
    margin: float
    on_lower: bool = False
    """Judged on the lower bound of the paired 95% interval, not on the mean."""

    def text(self) -> str:
        """The goal in words."""
        if self.on_lower:
            return (f"the 95% CI of the steps LCS gap to {self.baseline} starts at "
                    f"{self.margin:+.3f} or above")
        return f"steps LCS at least {self.margin:.2f} above {self.baseline}"

    def verdict(self, gaps: dict) -> str | None:
        """'met' or 'not met: ...' from a block's gaps (row -> baseline -> metric ->
        summary), None when the block lacks the pair."""
        gap = gaps.get(self.row, {}).get(self.baseline, {}).get("steps")
        if gap is None:
            return None
        value = gap["lo"] if self.on_lower else gap["mean"]
        return "met" if value >= self.margin else f"not met: short by {self.margin - value:.3f}"


GOALS = (
    Goal("stratified", RERANK_ROW, "Title-medoid", 0.05),
    Goal("stratified", RERANK_ROW, "Title-median", 0.03),
    Goal("leave-activities-out", RERANK_ROW, "NN (description)", 0.08),
    Goal("stratified", TITLE_ROW, "Title-median", -0.005, on_lower=True),
    Goal("leave-activities-out", TITLE_ROW, "NN (title)", 0.03),
)
"""Issue 44's goals (the stratified test has only seen activities)."""

BASELINES = {RERANK_ROW: ("Title-medoid", "Title-median", "NN (description)"),
             TITLE_ROW: ("Title-medoid", "Title-median", "NN (title)")}
"""Model row -> the baselines its gaps are shown to."""


def beaten(split: str) -> dict[str, tuple[str, ...]]:
    """Model row -> its baselines on `split`, those of the split's goals first."""
    return {row: tuple(dict.fromkeys([*(g.baseline for g in GOALS
                                        if g.split == split and g.row == row), *baselines]))
            for row, baselines in BASELINES.items()}


def goals_of(split: str, row: str) -> list[Goal]:
    """The goals set on `split` for `row`."""
    return [g for g in GOALS if g.split == split and g.row == row]
