import pytest

from homesim.learn.eval.summary import summarize, summarize_gap


def _seed(values, repeats=0, length=4):
    return [{"steps": v, "repeats": repeats, "length": length} for v in values]


def test_mean_sd_and_interval_over_seeds():
    runs = [_seed([0.2, 0.4, 0.6]), _seed([0.4, 0.6, 0.8])]
    s = summarize(runs, "steps")
    assert s["mean"] == pytest.approx(0.5) and s["seeds"] == pytest.approx([0.4, 0.6])
    assert s["sd"] == pytest.approx(0.1414, abs=1e-3)
    assert s["lo"] <= s["mean"] <= s["hi"] and s["hi"] - s["lo"] < 0.4
    assert summarize(runs, "steps") == s  # the bootstrap is seeded


def test_repetition_is_pooled_over_steps():
    s = summarize([_seed([0, 0], repeats=1, length=4)], "repetition")
    assert s["mean"] == pytest.approx(0.25) and s["sd"] == 0.0


def test_paired_gap_of_a_constant_shift_has_a_zero_width_interval():
    base = [_seed([0.1, 0.5, 0.9]), _seed([0.3, 0.2, 0.7])]
    better = [[{**e, "steps": e["steps"] + 0.05} for e in run] for run in base]
    g = summarize_gap(better, base, "steps")
    assert g["mean"] == pytest.approx(0.05)
    assert g["lo"] == pytest.approx(0.05) and g["hi"] == pytest.approx(0.05)
