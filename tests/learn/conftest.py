"""Tiny synthetic splits shared by the learning tests."""

from __future__ import annotations

import pytest

torch = pytest.importorskip("torch")
torch.set_num_threads(1)  # the tiny models gain nothing from threads; shared CPUs lose

from homesim.learn.data import split, synthetic_examples  # noqa: E402


@pytest.fixture(scope="session")
def tiny_splits():
    return split("synthetic", synthetic_examples(40, seed=11), seed=11)
