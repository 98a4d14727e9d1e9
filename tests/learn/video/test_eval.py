"""Scoring: the bootstrap of mean per-class accuracy over episodes."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("torch")


def test_the_clip_bootstrap_resamples_episodes():
    from homesim.learn.video.eval import clip_summary

    counts = np.array([[2.0, 0.0], [0.0, 1.0]])  # episode 0: 2 clips of class 0, ...
    hits = np.array([[1.0, 0.0], [0.0, 1.0]])
    s = clip_summary([(counts, hits), (counts, counts)])  # two seeds
    assert s["seeds"] == [pytest.approx(75.0), pytest.approx(100.0)]
    assert s["lo"] <= s["mean"] <= s["hi"] <= 100
