"""The video tasks' split: which part each episode belongs to, its role (train, val,
test) and the test rows, declared in one place.

A plan folder (`homesim dataset generate --plan`, `homesim.dataset.plan`) says it: every
part is a folder of its own and the plan names each part's role and the rows. Folders made
without a plan are split by `LEGACY`'s rule (the homes and agents of each episode, as the
paper's protocol): train = `SEEN_HOMES` x `TRAIN_AGENTS` less a held-out share (by a hash
of the key and `SPLIT_SEED`, not the training seed), validation = `VAL_HOME`, tests =
the held-out share, the other agents in the seen homes, and every other home.
Validation chooses epochs and settings and is never pooled into a test row.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

SEEN_HOMES = ("scene1", "scene2", "scene3", "scene4")
TRAIN_AGENTS = ("male1", "female1")
VAL_HOME = "scene5"
HELD_OUT = 0.25
"""Share of seen-home, train-agent episodes kept for the test-seen part."""
SPLIT_SEED = 0


@dataclass(frozen=True)
class Split:
    """Each part's role and the test rows (row, label, the test parts it pools)."""

    roles: dict[str, str]
    rows: tuple[tuple[str, str, tuple[str, ...]], ...]

    def parts(self, role: str) -> list[str]:
        return [p for p, r in self.roles.items() if r == role]


LEGACY = Split(
    {"train": "train", "val": "val", "test-seen": "test", "test-unseen-agents": "test",
     "test-unseen-homes": "test"},
    (("seen", "seen homes and agents", ("test-seen",)),
     ("unseen-agents", "seen homes, unseen agents", ("test-unseen-agents",)),
     ("unseen-homes", "unseen homes (not scene1-5)", ("test-unseen-homes",)),
     ("all", "all test episodes", ("test-seen", "test-unseen-agents", "test-unseen-homes"))))
"""The split of folders made without a plan (`legacy_part`)."""


def legacy_part(key: str, home: str, agent: str) -> str:
    """Which part of `LEGACY` an episode of a folder without a plan belongs to."""
    home = home.removesuffix("_trimmed")
    if home == VAL_HOME:
        return "val"
    if home not in SEEN_HOMES:
        return "test-unseen-homes"
    if agent not in TRAIN_AGENTS:
        return "test-unseen-agents"
    digest = hashlib.sha256(f"{SPLIT_SEED}-{key}".encode()).digest()
    return "test-seen" if digest[0] / 256 < HELD_OUT else "train"
