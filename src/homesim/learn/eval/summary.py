"""Numbers over seeds: mean ± sd of each row's per-seed score, and bootstrap intervals.

A run (one seed) scores every test example (`metrics.example_scores`). A row's figure for
a seed is the mean over its test examples (repetition: repeated steps over all steps).
Across seeds we report the mean and the sample standard deviation of those figures, and a
95% bootstrap interval of their mean: each replicate resamples the test examples of every
seed with replacement and averages the seeds' figures. Gaps between two rows are bootstrapped
paired (the same resampled examples for both), so they are tighter than the rows' own
intervals. The bootstrap has its own seed: same runs, same intervals.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

METRICS = ("steps", "action", "objects", "mean", "simulator", "elsewhere", "solved",
           "repetition")
"""Columns: the three LCS and their mean; executes in the example's home; share of the other
built-in homes it executes in; solved (executes and steps LCS >= 0.5); repeated steps."""
BOOTSTRAP = 1000
BOOTSTRAP_SEED = 0

Figure = Callable[[list[dict], np.ndarray], np.ndarray]
"""(a run's per-example scores, index draws (..., n)) -> the seed's figure for each draw."""


def figure(metric: str) -> Figure:
    """How a seed's figure for `metric` is computed from its (resampled) examples."""
    if metric == "repetition":
        def ratio(examples: list[dict], idx: np.ndarray) -> np.ndarray:
            reps = np.array([e["repeats"] for e in examples], dtype=float)[idx].sum(-1)
            steps = np.array([e["length"] for e in examples], dtype=float)[idx].sum(-1)
            return np.divide(reps, steps, out=np.zeros_like(reps), where=steps > 0)
        return ratio

    def mean(examples: list[dict], idx: np.ndarray) -> np.ndarray:
        values = np.array([np.nan if e[metric] is None else e[metric] for e in examples])
        return np.nanmean(values[idx], axis=-1)
    return mean


def _draws(sizes: list[int]) -> list[np.ndarray]:
    """`BOOTSTRAP` index draws per seed, (BOOTSTRAP, n) each, from one seeded generator."""
    rng = np.random.default_rng(BOOTSTRAP_SEED)
    return [rng.integers(0, n, size=(BOOTSTRAP, n)) for n in sizes]


def summarize(per_seed: list[list[dict]], metric: str) -> dict:
    """Mean, sd over seeds and the 95% bootstrap interval of one row's `metric`."""
    return summarize_gap(per_seed, None, metric)


def summarize_gap(per_seed: list[list[dict]], baseline: list[list[dict]] | None,
                  metric: str) -> dict:
    """Like `summarize`, of the row's figure minus the baseline's (paired) when given."""
    f = figure(metric)

    def value(seed: int, idx: np.ndarray) -> np.ndarray:
        v = f(per_seed[seed], idx)
        return v - f(baseline[seed], idx) if baseline is not None else v

    full = [float(value(k, np.arange(len(ex)))) for k, ex in enumerate(per_seed)]
    draws = _draws([len(ex) for ex in per_seed])
    reps = np.mean([value(k, draws[k]) for k in range(len(per_seed))], axis=0)
    lo, hi = np.nanpercentile(reps, [2.5, 97.5])
    return {"mean": float(np.mean(full)),
            "sd": float(np.std(full, ddof=1)) if len(full) > 1 else 0.0,
            "lo": float(lo), "hi": float(hi), "seeds": full}


def summarize_rows(runs: list[dict]) -> dict[str, dict[str, Any]]:
    """Row -> metric -> summary over the runs (one per seed) of one data set and split.

    A row missing from some runs (a model not trained for every seed) is summarised over
    the runs that have it; ``n_seeds`` says how many.
    """
    names = list(dict.fromkeys(row for r in runs for row in r["rows"]))
    out: dict[str, dict[str, Any]] = {}
    for row in names:
        per_seed = [r["rows"][row]["examples"] for r in runs if row in r["rows"]]
        out[row] = {m: summarize(per_seed, m) for m in METRICS
                    if not _all_none(per_seed, m)}
        out[row]["n_seeds"] = len(per_seed)
    return out


def gaps(runs: list[dict], row: str, baselines: tuple[str, ...],
         metrics: tuple[str, ...] = ("steps", "simulator", "solved")) -> dict[str, dict]:
    """Baseline -> metric -> paired summary of `row` minus that baseline, over the runs
    that have both."""
    out: dict[str, dict[str, Any]] = {}
    for b in baselines:
        both = [r for r in runs if row in r["rows"] and b in r["rows"]]
        if both:
            out[b] = {m: summarize_gap([r["rows"][row]["examples"] for r in both],
                                       [r["rows"][b]["examples"] for r in both], m)
                      for m in metrics}
            out[b]["n_seeds"] = len(both)
    return out


def _all_none(per_seed: list[list[dict]], metric: str) -> bool:
    return metric != "repetition" and all(e[metric] is None for ex in per_seed for e in ex)
