import pytest

from homesim.errors import HomesimError
from homesim.learn.execution import executable
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.text.train import TrainConfig, train_mle


def test_save_load_gives_the_same_predictions(tiny_splits, tmp_path):
    t2p = Text2Prog.create(tiny_splits.train, seed=0)  # MiniLM word vectors
    assert t2p.model.config.word_dim == 384 and t2p.meta["embeddings"] == "minilm"
    train_mle(t2p, tiny_splits.train, TrainConfig(epochs=1, batch_size=8))
    path = tmp_path / "m.pt"
    t2p.save(path)
    back = Text2Prog.load(path)
    a = [str(p) for p in t2p.predict(tiny_splits.test)]
    assert a == [str(p) for p in back.predict(tiny_splits.test)]
    safe = back.predict(tiny_splits.test, constrained=True)
    assert all(executable(p, e) for p, e in zip(safe, tiny_splits.test, strict=True))


def test_bad_checkpoint_is_one_clear_error(tmp_path):
    bad = tmp_path / "bad.pt"
    bad.write_text("not a checkpoint")
    with pytest.raises(HomesimError, match=r"bad\.pt: not a text2prog checkpoint"):
        Text2Prog.load(bad)


def test_word2vec_and_unknown_embeddings(tiny_splits):
    t2p = Text2Prog.create(tiny_splits.train, seed=0, embeddings="word2vec")
    assert t2p.model.config.word_dim == 100
    vectors = t2p.model.words.weight
    assert vectors[t2p.words.index["the"]].abs().sum() > 0
    with pytest.raises(HomesimError, match="unknown embeddings 'glove'"):
        Text2Prog.create(tiny_splits.train, seed=0, embeddings="glove")
