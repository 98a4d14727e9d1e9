import torch

from homesim.learn import decode
from homesim.learn.execution import StepRunner, executable
from homesim.learn.text2prog import Text2Prog
from homesim.learn.vocab import END


def test_greedy_sample_and_constrained(tiny_splits):
    t2p = Text2Prog.create(tiny_splits.train, seed=0, embeddings="none")
    t2p.model.eval()
    test = tiny_splits.test
    words, mask = t2p.batch(test)
    ids = decode.greedy(t2p.model, words, mask, max_steps=6)
    assert len(ids) == len(test) and all(len(p) <= 6 for p in ids)
    assert all(0 < i < len(t2p.steps) for p in ids for i in p)
    gen = torch.Generator().manual_seed(0)
    sampled, logp = decode.sample(t2p.model, words, mask, gen, max_steps=6)
    assert logp.shape == (len(test),) and logp.requires_grad and (logp <= 0).all()
    again, _ = decode.sample(t2p.model, words, mask, torch.Generator().manual_seed(0), 6)
    assert sampled == again
    with torch.no_grad():
        runners = [StepRunner(e) for e in test]
        safe = decode.constrained(t2p.model, words, mask, t2p.steps, runners, max_steps=6)
    for p, e in zip(safe, test, strict=True):
        assert END not in p
        assert executable(t2p.steps.decode(p), e)
