"""The consensus of the seq2seq model and retrieval on tiny data: seeded, and what it
promises."""

from homesim.learn.execution import executable
from homesim.learn.rerank.retrieve import RetrieveEdit
from homesim.learn.text.consensus import Consensus
from homesim.learn.text.text2prog import Text2Prog


def test_consensus_is_seeded_and_prefers_executable_programs(tiny_splits):
    t2p = Text2Prog.create(tiny_splits.train, seed=0, embeddings="none")
    retrieval = RetrieveEdit(tiny_splits.train)
    a = Consensus(t2p, retrieval, seed=1).predict(tiny_splits.test)
    b = Consensus(t2p, retrieval, seed=1).predict(tiny_splits.test)
    assert [str(p) for p in a] == [str(p) for p in b]
    # an untrained model samples junk, but retrieved training programs execute: chosen
    assert all(executable(p, e) for p, e in zip(a, tiny_splits.test, strict=True))


def test_the_dev_grid_and_pool_sizes_are_the_configs(tiny_splits):
    from homesim.learn.text.consensus import ConsensusConfig

    t2p = Text2Prog.create(tiny_splits.train, seed=0, embeddings="none")
    config = ConsensusConfig(samples=2, neighbours=3, betas=(0.75,))
    model = Consensus.fit(t2p, RetrieveEdit(tiny_splits.train), tiny_splits.dev[:3], 1, config)
    assert model.beta == 0.75 and model.config is config
    pool = model.pools(tiny_splits.test[:1])[0]
    assert len(pool.samples) == 2 and len(pool.neighbours) == 3
