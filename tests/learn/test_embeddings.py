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
