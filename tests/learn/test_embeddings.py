import numpy as np
import torch

from homesim.learn.embeddings import sentence_vectors, word2vec_vectors, word_vectors


def test_minilm_word_vectors_relate_similar_words():
    v = word_vectors(["<pad>", "television", "tv", "toilet"])
    assert v.shape == (4, 384) and v[0].abs().sum() == 0
    cos = torch.nn.functional.cosine_similarity
    assert cos(v[1:2], v[2:3]) > cos(v[1:2], v[3:4])


def test_sentence_vectors_are_unit_length_and_meaningful():
    v = sentence_vectors(["turn on the tv", "switch the television on", "wash the dishes"])
    assert np.allclose(np.linalg.norm(v, axis=1), 1, atol=1e-4)
    assert v[0] @ v[1] > v[0] @ v[2]


def test_word2vec_is_seeded():
    texts = ["go to the kitchen", "open the fridge", "go to the bedroom"] * 5
    a = word2vec_vectors(["<pad>", "go", "fridge"], texts, seed=1, dim=16)
    b = word2vec_vectors(["<pad>", "go", "fridge"], texts, seed=1, dim=16)
    assert torch.equal(a, b) and a.shape == (3, 16) and a[0].abs().sum() == 0


def test_preload_reuses_a_cache_only_for_the_same_set_of_texts(tmp_path, monkeypatch):
    from homesim.learn import embeddings

    batches: list[list[str]] = []

    def fake(texts: list[str], batch_size: int = 64) -> np.ndarray:
        batches.append(list(texts))
        return np.full((len(texts), 384), float(len(texts)), np.float32)

    monkeypatch.setattr(embeddings, "sentence_vectors", fake)
    monkeypatch.setattr(embeddings, "_VECTORS", {})
    cache = tmp_path / "vectors.npz"
    embeddings.preload_sentence_vectors(["b", "a", "c"], cache)
    embeddings.preload_sentence_vectors(["c", "a", "b", "a"], cache)  # read back from disk
    embeddings.preload_sentence_vectors(["a", "b"], cache)  # other batches: embedded afresh
    assert batches == [["a", "b", "c"], ["a", "b"]]
    assert embeddings.cached_sentence_vectors(["a"])[0, 0] == 2.0


def test_a_lone_vector_is_the_texts_own_whatever_was_batched_before(monkeypatch):
    from homesim.learn import embeddings

    monkeypatch.setattr(embeddings, "_ALONE", {})
    text = "switch on light"
    batched = embeddings.sentence_vectors([text, "walk to the kitchen and open the fridge"])[0]
    alone = embeddings.lone_sentence_vectors([text, text])
    assert np.array_equal(alone[0], embeddings.sentence_vectors([text])[0])
    assert np.array_equal(alone[0], alone[1]) and np.allclose(alone[0], batched, atol=1e-4)
    assert embeddings.lone_sentence_vectors([]).shape == (0, embeddings.WORD_DIM)


def test_lone_vectors_forget_the_oldest_beyond_the_bound_and_come_back_the_same(monkeypatch):
    from homesim.learn import embeddings

    monkeypatch.setattr(embeddings, "_ALONE", {})
    monkeypatch.setattr(embeddings, "ALONE_KEPT", 2)
    first = embeddings.lone_sentence_vectors(["open fridge", "grab milk", "close fridge"])
    assert list(embeddings._ALONE) == ["grab milk", "close fridge"]
    again = embeddings.lone_sentence_vectors(["open fridge"])[0]
    assert np.array_equal(again, first[0])
    assert list(embeddings._ALONE) == ["close fridge", "open fridge"]
