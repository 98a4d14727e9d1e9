"""Issue 44's goals: which rows and baselines, judged on the mean or on the interval."""

from homesim.learn.eval.experiment import RERANK_ROW, TITLE_ROW
from homesim.learn.eval.goals import GOALS, beaten, goals_of


def _gaps(row: str, baseline: str, mean: float, lo: float) -> dict:
    return {row: {baseline: {"steps": {"mean": mean, "lo": lo, "hi": mean + 0.01}}}}


def test_mean_goals_and_interval_goals_are_judged_apart():
    medoid, title = goals_of("stratified", RERANK_ROW)[0], goals_of("stratified", TITLE_ROW)[0]
    assert (medoid.baseline, medoid.margin) == ("Title-medoid", 0.05)
    assert medoid.verdict(_gaps(RERANK_ROW, "Title-medoid", 0.051, 0.01)) == "met"
    assert medoid.verdict(_gaps(RERANK_ROW, "Title-medoid", 0.04, 0.03)) == (
        "not met: short by 0.010")
    assert title.on_lower and title.baseline == "Title-median"
    assert title.verdict(_gaps(TITLE_ROW, "Title-median", 0.02, -0.004)) == "met"
    assert title.verdict(_gaps(TITLE_ROW, "Title-median", 0.02, -0.006)).startswith("not met")
    assert medoid.verdict({}) is None


def test_every_goal_baseline_is_shown_first():
    assert len(GOALS) == 5
    assert beaten("leave-activities-out")[RERANK_ROW][0] == "NN (description)"
    assert beaten("leave-activities-out")[TITLE_ROW][0] == "NN (title)"
    assert beaten("stratified")[RERANK_ROW][:2] == ("Title-medoid", "Title-median")
