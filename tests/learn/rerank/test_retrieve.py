"""Retrieve-and-edit on tiny data: seeded, and what it promises."""

from homesim.learn.rerank.retrieve import RetrieveEdit


def test_retrieve_and_edit_keeps_or_prunes_a_training_program(tiny_splits):
    model = RetrieveEdit.fit(tiny_splits.train, tiny_splits.dev)
    preds = model.predict(tiny_splits.test)
    assert len(preds) == len(tiny_splits.test)
    for p in preds:  # every step comes from one training program, in its order
        assert p.steps and any(all(s in e.program.steps for s in p.steps)
                               for e in tiny_splits.train)
    weights = model.weights(tiny_splits.test)
    assert abs(weights.sum(1) - 1).max() < 1e-6
    assert [str(p) for p in RetrieveEdit.fit(tiny_splits.train, tiny_splits.dev)
            .predict(tiny_splits.test)] == [str(p) for p in preds]


def test_the_dev_grid_is_the_configs(tiny_splits):
    from homesim.learn.rerank.retrieve import RetrieveConfig

    grid = RetrieveConfig(taus=(0.1,), mixes=(0.3,), supports=(0.0,))
    model = RetrieveEdit.fit(tiny_splits.train, tiny_splits.dev, grid)
    assert (model.tau, model.mix, model.support, model.config) == (0.1, 0.3, 0.0, grid)
