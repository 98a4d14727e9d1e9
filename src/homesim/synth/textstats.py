"""How varied a set of descriptions is: vocabulary size and distinct-n.

distinct-n (Li et al., 2016) is the number of different word n-grams over the number of
n-grams in the whole set (n-grams do not cross descriptions): 1.0 when no n-gram repeats,
near 0 for text from a few fixed phrases. It falls as a set grows, so compare sets of
the same size (`benchmarks/descriptions.py` uses as many synthetic descriptions as there
are real ones).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

_WORD = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")


def words(text: str) -> list[str]:
    """The lower-cased words of `text` ("I'm" stays one word; punctuation goes).

    >>> words("Grab the TV-remote, then sit.")
    ['grab', 'the', 'tv', 'remote', 'then', 'sit']
    """
    return _WORD.findall(text.lower())


@dataclass(frozen=True)
class TextStats:
    """Measures of a set of texts (see the module docstring)."""

    texts: int
    words: int
    vocabulary: int
    distinct_1: float
    distinct_2: float

    @property
    def mean_words(self) -> float:
        return self.words / self.texts if self.texts else 0.0


def distinct_n(tokenized: list[list[str]], n: int) -> float:
    """Different n-grams / all n-grams over the texts (0.0 when there are none).

    >>> distinct_n([["a", "b", "a", "b"]], 2)  # ab, ba, ab
    0.6666666666666666
    """
    grams = [tuple(ws[i:i + n]) for ws in tokenized for i in range(len(ws) - n + 1)]
    return len(set(grams)) / len(grams) if grams else 0.0


def text_stats(texts: Iterable[str]) -> TextStats:
    """Vocabulary size and distinct-1/2 of `texts`."""
    tokenized = [words(t) for t in texts]
    vocabulary = {w for ws in tokenized for w in ws}
    return TextStats(len(tokenized), sum(map(len, tokenized)), len(vocabulary),
                     distinct_n(tokenized, 1), distinct_n(tokenized, 2))
