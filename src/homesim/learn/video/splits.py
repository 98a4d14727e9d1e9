"""The video tasks' split, declared in one place (the paper's Table 2 protocol, scaled).

The paper trains on the first four homes with two agents, validates on the fifth home
and tests on all homes and all four agents, reporting homes seen and unseen in training.
Here each episode belongs to one part:

    train:               `SEEN_HOMES` x `TRAIN_AGENTS`, less a held-out share
    test-seen:           `SEEN_HOMES` x `TRAIN_AGENTS`, the held-out share
    test-unseen-agents:  `SEEN_HOMES`, acted by the other two agents
    val:                 `VAL_HOME` (chooses the training epoch of every model)
    test-unseen-homes:   any other home (generated homes ``gen-N``)

and the test rows are `TEST_ROWS`: seen homes and agents, unseen agents, unseen homes
(`VAL_HOME` and the generated homes: as in the paper, the validation home is also a test
home), and all test episodes. Held-out episodes are chosen by a hash of their key and
`SPLIT_SEED` (not the training seed: every seed trains on the same episodes), so the split
does not depend on the order episodes are read in.
"""

from __future__ import annotations

import hashlib
from typing import Protocol, TypeVar

SEEN_HOMES = ("scene1", "scene2", "scene3", "scene4")
TRAIN_AGENTS = ("male1", "female1")
VAL_HOME = "scene5"
HELD_OUT = 0.25
"""Share of seen-home, train-agent episodes kept for the test-seen part."""
SPLIT_SEED = 0
PARTS = ("train", "val", "test-seen", "test-unseen-agents", "test-unseen-homes")
TEST_ROWS = {
    "seen": ("seen homes and agents", ("test-seen",)),
    "unseen-agents": ("seen homes, unseen agents", ("test-unseen-agents",)),
    "unseen-homes": ("unseen homes (scene5, gen-*)", ("val", "test-unseen-homes")),
    "all": ("all test episodes", ("test-seen", "test-unseen-agents", "val",
                                  "test-unseen-homes")),
}
"""Test row -> (label, the parts it pools)."""


class HasHomeAgent(Protocol):
    key: str
    home: str
    agent: str


T = TypeVar("T", bound=HasHomeAgent)


def _home_name(home: str) -> str:
    return home.removesuffix("_trimmed")


def part_of(item: HasHomeAgent) -> str:
    """Which of `PARTS` an episode belongs to."""
    home = _home_name(item.home)
    if home == VAL_HOME:
        return "val"
    if home not in SEEN_HOMES:
        return "test-unseen-homes"
    if item.agent not in TRAIN_AGENTS:
        return "test-unseen-agents"
    digest = hashlib.sha256(f"{SPLIT_SEED}-{item.key}".encode()).digest()
    return "test-seen" if digest[0] / 256 < HELD_OUT else "train"


def video_split(items: list[T]) -> dict[str, list[T]]:
    """The episodes of each part, in their given order."""
    out: dict[str, list[T]] = {p: [] for p in PARTS}
    for item in items:
        out[part_of(item)].append(item)
    return out


def test_rows(parts: dict[str, list[T]]) -> dict[str, list[T]]:
    """The episodes of each of `TEST_ROWS` (rows with none are left out)."""
    rows = {row: [e for p in pooled for e in parts[p]] for row, (_, pooled) in
            TEST_ROWS.items()}
    return {row: eps for row, eps in rows.items() if eps}
