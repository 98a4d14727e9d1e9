import torch

from homesim.learn.execution import StepRunner, executable
from homesim.learn.text import decode
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.vocabularies import END


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


def test_penalty_discourages_reuse_and_forbids_long_runs():
    from homesim.learn.text.decode import penalized
    from homesim.learn.text.seq2seq import Seq2SeqConfig

    config = Seq2SeqConfig(4, 2, 2)  # the defaults: penalty 1, runs of one
    log_probs = torch.log_softmax(torch.tensor([0.0, 3.0, 1.0, 0.5]), 0)
    p = penalized(log_probs, [1, 2, 1, 2], config)
    assert p[1] == log_probs[1] - 2 * config.repeat_penalty and p[3] == log_probs[3]
    assert p[END] == log_probs[END]  # ending is never penalised
    assert penalized(log_probs, [1] * config.max_run, config)[1] == float("-inf")
    assert penalized(log_probs, [2], config)[2] == float("-inf")  # no step directly repeats
    twice = Seq2SeqConfig(4, 2, 2, repeat_penalty=0.5, max_run=2)
    assert penalized(log_probs, [2], twice)[2] == log_probs[2] - 0.5  # a run of two may be
    assert penalized(log_probs, [2, 2], twice)[2] == float("-inf")


def test_constrained_decoding_does_not_loop(tiny_splits):
    t2p = Text2Prog.create(tiny_splits.train, seed=0, embeddings="none")
    with torch.no_grad():  # an untrained model: its favourite step would repeat forever
        t2p.model.out.bias.data += 5 * t2p.model.step_embeddings()[1]
    preds = t2p.predict(tiny_splits.test, constrained=True)
    for p in preds:
        keys = [str(s) for s in p.steps]
        assert len(p) <= t2p.model.config.max_steps
        assert not any(keys[i] == keys[i + 1] == keys[i + 2] for i in range(len(keys) - 2))
