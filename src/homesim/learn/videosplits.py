"""The video tasks' split, declared in one place (the paper's Table 2 protocol, scaled).

The paper trains on the first four homes with two agents and tests on all homes and all
four agents, reporting homes seen and unseen in training. Here:

    train:        episodes in `SEEN_HOMES` acted by `TRAIN_AGENTS`, less a held-out share
    test-seen:    the rest of the episodes in `SEEN_HOMES` (held out, or another agent)
    test-unseen:  episodes in any other home (apartment 5, generated homes ``gen-N``)

Held-out episodes are chosen by a seeded hash of their key, so the same seed gives the
same split whatever order episodes are read in.
"""

from __future__ import annotations

import hashlib
from typing import Protocol, TypeVar

SEEN_HOMES = ("scene1", "scene2", "scene3", "scene4")
TRAIN_AGENTS = ("male1", "female1")
HELD_OUT = 0.25
"""Share of seen-home, train-agent episodes kept for the test-seen split."""
PARTS = ("train", "test-seen", "test-unseen")


class HasHomeAgent(Protocol):
    key: str
    home: str
    agent: str


T = TypeVar("T", bound=HasHomeAgent)


def _home_name(home: str) -> str:
    return home.removesuffix("_trimmed")


def part_of(item: HasHomeAgent, seed: int) -> str:
    """Which of `PARTS` an episode belongs to."""
    if _home_name(item.home) not in SEEN_HOMES:
        return "test-unseen"
    if item.agent not in TRAIN_AGENTS:
        return "test-seen"
    digest = hashlib.sha256(f"{seed}-{item.key}".encode()).digest()
    return "test-seen" if digest[0] / 256 < HELD_OUT else "train"


def video_split(items: list[T], seed: int) -> dict[str, list[T]]:
    """The episodes of each part, in their given order."""
    out: dict[str, list[T]] = {p: [] for p in PARTS}
    for item in items:
        out[part_of(item, seed)].append(item)
    return out
