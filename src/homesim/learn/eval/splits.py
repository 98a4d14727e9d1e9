"""The evaluation splits, declared in one place.

    stratified: 70/10/20 train/dev/test by program, stratified by activity
        (`ActivityDataset.split`), then every dev and test program whose steps equal a
        training program's is removed (a copy would be scored as a retrieval; dev keeps
        none either, so that what is chosen on dev is chosen for programs like test's).
    leave-activities-out: whole activities go to train, dev or test (shuffled by seed, each
        activity to the split furthest below its share of programs), so no test activity
        is seen in training; the title no longer names a known activity.

`SPLITS` names them; `make_split(name, examples, seed)` builds one. The same seed gives the
same split.

**Which seeds are for what** (issue 44; fixed before any tuning of that issue, and not to be
changed after a look at the figures). Development chooses everything (features, thresholds,
epochs) by cross-validation within train and on dev, at the development seeds `DEV_SEEDS`
(0-4: their test splits were also looked at while developing, docs/learn.md). The published
test is at the *locked* seeds: the first N seeds from `LOCKED_FROM` (100, 101, ...; N is the
table's ``--seeds``, 5 published). Development never runs them: `make_split` refuses a
locked seed unless told ``final=True``, which only ``homesim learn table --final`` does, and
that command records every such run before it scores anything (`homesim.learn.eval.ledger`).
"""

from __future__ import annotations

import random
from collections import Counter

from homesim.errors import HomesimError
from homesim.learn.data import SPLIT_FRACTIONS, Example, Splits, split
from homesim.program.metrics import step_tokens

SPLITS = ("stratified", "leave-activities-out")
DEV_SEEDS = (0, 1, 2, 3, 4)
"""The development seeds of the table (looked at while developing)."""
LOCKED_FROM = 100
"""The locked test seeds are ``LOCKED_FROM, LOCKED_FROM + 1, ...`` (`locked_seeds`)."""
SPLIT_VERSIONS = {"stratified": 2, "leave-activities-out": 1}
"""Raised when a split's definition changes, so that no run cached with the old one is reused
(`experiment.RunSpec`). Stratified 2: dev drops copies of training programs too."""


def steps_of(example: Example) -> tuple:
    """The example's steps as comparable tokens (action, object classes)."""
    return tuple(step_tokens(example.program))


def stratified(examples: list[Example], seed: int, name: str = "") -> Splits:
    """Stratified split with the dev and test programs that copy a training program removed."""
    parts = split(name, examples, seed)
    seen = {steps_of(e) for e in parts.train}
    dev, test = ([e for e in part if steps_of(e) not in seen] for part in (parts.dev, parts.test))
    return Splits(parts.name, parts.train, dev, test)


def leave_activities_out(examples: list[Example], seed: int, name: str = "") -> Splits:
    """Whole activities per split, in the shares of `SPLIT_FRACTIONS` (by programs)."""
    sizes = Counter(e.activity for e in examples)
    activities = sorted(sizes)
    random.Random(seed).shuffle(activities)
    chosen: list[set[str]] = [set(), set(), set()]
    counts = [0, 0, 0]
    dealt = 0
    for activity in activities:
        dealt += sizes[activity]
        deficits = [share * dealt - c for share, c in zip(SPLIT_FRACTIONS, counts, strict=True)]
        k = max(range(3), key=lambda j: (deficits[j], -j))
        chosen[k].add(activity)
        counts[k] += sizes[activity]
    train, dev, test = ([e for e in examples if e.activity in part] for part in chosen)
    return Splits(name, train, dev, test)


def locked_seeds(n: int) -> tuple[int, ...]:
    """The first `n` locked test seeds (module docstring)."""
    return tuple(range(LOCKED_FROM, LOCKED_FROM + n))


def is_locked(seed: int) -> bool:
    """Whether `seed` is a locked test seed, which development never runs."""
    return seed >= LOCKED_FROM


def check_unlocked(seed: int, final: bool = False) -> None:
    """A clear error for a locked `seed` unless `final` (the recorded final table run)."""
    if is_locked(seed) and not final:
        raise HomesimError(f"seed {seed}: seeds from {LOCKED_FROM} on are the locked test; "
                           "only `homesim learn table --final` runs them (docs/learn.md, "
                           "\"The locked test\"); develop on seeds 0-4")


def make_split(split_name: str, examples: list[Example], seed: int, name: str = "",
               final: bool = False) -> Splits:
    """The split called `split_name` (one of `SPLITS`) of `examples`; a locked `seed` only
    with `final` (module docstring)."""
    check_unlocked(seed, final)
    if split_name == "stratified":
        return stratified(examples, seed, name)
    if split_name == "leave-activities-out":
        return leave_activities_out(examples, seed, name)
    raise HomesimError(f"unknown split {split_name!r}: choose from {', '.join(SPLITS)}")
