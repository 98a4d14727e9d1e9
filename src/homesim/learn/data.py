"""Description -> program examples: the real data set and the synthetic one, with splits.

An example is an `ActivityProgram` (the one data set record) with its program ungrounded
(``<cup> (1)``): its `bindings` say how the objects were bound in its home (a built-in
home, or the stored initial graph of a real program), so predictions can be executed there.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from homesim.knowledge.datasets import ActivityDataset, ActivityProgram, real_programs
from homesim.program.bindings import Bindings
from homesim.program.model import Program
from homesim.synth import generate, read_jsonl

SPLIT_FRACTIONS = (0.7, 0.1, 0.2)
"""Train, dev and test shares (stratified by activity, i.e. program title)."""

Example = ActivityProgram
"""A learning example is a data set record (`ActivityProgram`); the name reads better here."""


@dataclass(frozen=True)
class Splits:
    """Train, dev and test examples of one data set."""

    name: str
    train: list[Example]
    dev: list[Example]
    test: list[Example]


def ungrounded(program: Program) -> tuple[Program, Bindings]:
    """The program with node ids removed, and the bindings they gave."""
    example = ActivityProgram("", program).ungrounded()
    return example.program, example.bindings


def real_examples(directory: Path | None = None) -> list[Example]:
    """The 518 real programs as examples (needs ``homesim data fetch``)."""
    return [rp.ungrounded() for rp in real_programs(directory)]


def synthetic_examples(n: int = 5000, seed: int = 0, path: Path | None = None,
                       style: str = "templates") -> list[Example]:
    """Synthetic examples: read from a `homesim synth` file, or generated with `seed`.

    `style` is the description style (`homesim.synth.grammar.STYLES`): the learning
    figures in docs/results.md were made with ``"templates"``, which stays the default
    here so that they reproduce; ``"people"`` is the paraphrase grammar (same programs)."""
    return read_jsonl(path) if path is not None else list(generate(n, seed, style=style))


def split(name: str, examples: list[Example], seed: int) -> Splits:
    """70/10/20 train/dev/test, stratified by activity; the same seed gives the same split.

    The split is `ActivityDataset.split` (activity = normalized title).
    """
    parts = ActivityDataset(examples, name).split(seed, SPLIT_FRACTIONS)
    train, dev, test = (list(parts[k]) for k in ("train", "val", "test"))
    return Splits(name, train, dev, test)
