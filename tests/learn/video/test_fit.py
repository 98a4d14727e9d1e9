"""Resumable training: a run stopped after an epoch and run again ends with the weights
of a run never stopped."""

from __future__ import annotations

import numpy as np
import pytest

torch = pytest.importorskip("torch")

from homesim.errors import HomesimError  # noqa: E402
from homesim.learn.video.fit import batches, fit  # noqa: E402


def _model_and_step():
    torch.manual_seed(0)
    model = torch.nn.Sequential(torch.nn.Linear(4, 8), torch.nn.Dropout(0.5),
                                torch.nn.Linear(8, 2))
    x = torch.randn(64, 4, generator=torch.Generator().manual_seed(1))
    y = (x[:, 0] > 0).long()

    def step(opt, rng):
        losses = []
        for batch in batches(len(y), 16, rng):
            loss = torch.nn.functional.cross_entropy(model(x[batch]), y[batch])
            opt.zero_grad()
            loss.backward()
            opt.step()
            losses.append(float(loss.detach()))
        return float(np.mean(losses))

    def score():
        with torch.no_grad():
            return float((model(x).argmax(1) == y).float().mean())
    return model, step, score


def test_a_stopped_run_resumes_to_the_same_weights(tmp_path):
    model, step, score = _model_and_step()
    whole = fit(model, step, epochs=4, lr=1e-2, seed=3, score=score)
    straight = [p.detach().clone() for p in model.parameters()]

    model, step, score = _model_and_step()
    ckpt = tmp_path / "m.ckpt"
    fit(model, step, epochs=2, lr=1e-2, seed=3, score=score, checkpoint=ckpt, config={"a": 1})
    model, step, score = _model_and_step()  # a new process: fresh weights
    resumed = fit(model, step, epochs=4, lr=1e-2, seed=3, score=score, checkpoint=ckpt,
                  config={"a": 1})
    assert resumed.losses == whole.losses and resumed.scores == whole.scores
    assert resumed.best_epoch == whole.best_epoch
    assert all(torch.equal(a, b) for a, b in zip(straight, model.parameters(), strict=True))
    with pytest.raises(HomesimError, match="a checkpoint of other settings"):
        fit(model, step, epochs=4, lr=1e-2, seed=3, checkpoint=ckpt, config={"a": 2})


def test_batches_cover_every_item_once():
    rng = np.random.default_rng(0)
    got = np.concatenate(batches(10, 4, rng))
    assert sorted(got.tolist()) == list(range(10))
    assert [len(b) for b in batches(10, 4, rng, min_batch=3)] == [4, 4]
