"""Retrieve-and-edit and the consensus model on tiny data: seeded, and what they promise."""

from homesim.learn.consensus import Consensus
from homesim.learn.execution import executable
from homesim.learn.retrieve import RetrieveEdit
from homesim.learn.text2prog import Text2Prog


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


def test_consensus_is_seeded_and_prefers_executable_programs(tiny_splits):
    t2p = Text2Prog.create(tiny_splits.train, seed=0, embeddings="none")
    retrieval = RetrieveEdit(tiny_splits.train)
    a = Consensus(t2p, retrieval, seed=1).predict(tiny_splits.test)
    b = Consensus(t2p, retrieval, seed=1).predict(tiny_splits.test)
    assert [str(p) for p in a] == [str(p) for p in b]
    # an untrained model samples junk, but retrieved training programs execute: chosen
    assert all(executable(p, e) for p, e in zip(a, tiny_splits.test, strict=True))
