"""Stand-ins for names that land with the knowledge-base branch (delete when it has).

`homesim.program.metrics` (LCS scores) and `homesim.knowledge.datasets.ActivityDataset`
(stratified splits) are being written on branch ``kb``. Until they are on main, this module
gives the two pieces `learn` needs, with the same meaning, so the table can be measured.
"""

from __future__ import annotations

import random
from collections import defaultdict
from collections.abc import Hashable, Sequence
from typing import TypeVar

T = TypeVar("T")


def lcs_length(a: Sequence[Hashable], b: Sequence[Hashable]) -> int:
    """Length of the longest common subsequence of two sequences."""
    if not a or not b:
        return 0
    prev = [0] * (len(b) + 1)
    for x in a:
        cur = [0]
        for j, y in enumerate(b):
            cur.append(prev[j] + 1 if x == y else max(prev[j + 1], cur[j]))
        prev = cur
    return prev[-1]


def stratified_split(items: Sequence[T], strata: Sequence[Hashable], seed: int,
                     fractions: tuple[float, float, float] = (0.7, 0.1, 0.2)
                     ) -> tuple[list[T], list[T], list[T]]:
    """Train/dev/test split keeping each stratum's share; the same seed, the same split."""
    groups: dict[Hashable, list[int]] = defaultdict(list)
    for i, s in enumerate(strata):
        groups[s].append(i)
    rng = random.Random(seed)
    parts: tuple[list[int], list[int], list[int]] = ([], [], [])
    carry = [0.0, 0.0]  # dev/test shares carried across strata, so small strata add up
    for key in sorted(groups, key=str):
        idx = groups[key]
        rng.shuffle(idx)
        n, taken = len(idx), []
        for k in (1, 2):
            want = n * fractions[k] + carry[k - 1]
            count = min(int(want), n - sum(taken))
            carry[k - 1] = want - count
            taken.append(count)
        dev, test = idx[:taken[0]], idx[taken[0]:taken[0] + taken[1]]
        parts[1].extend(dev)
        parts[2].extend(test)
        parts[0].extend(idx[taken[0] + taken[1]:])
    return tuple([items[i] for i in sorted(p)] for p in parts)  # type: ignore[return-value]
