"""Vocabularies: description words, and program steps built from actions and objects.

A step is reduced to its key, (action key, object class names): instance numbers are
dropped, and a decoded program numbers every class instance 1 (as nearly all real programs
do).
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass

from homesim.program.actions import ACTIONS
from homesim.program.model import ObjectRef, Program, Step

StepKey = tuple[str, tuple[str, ...]]
"""(action key, object class names) of a step."""

PAD, UNK = 0, 1
END = 0
"""Index of the end-of-program step in a `StepVocab`."""
_WORD = re.compile(r"[a-z]+|\d+")


def tokenize(text: str) -> list[str]:
    """Lower-case words of a description."""
    return _WORD.findall(text.lower())


def step_key(step: Step) -> StepKey:
    return (step.action.key, tuple(ref.name for ref in step.args))


@dataclass
class WordVocab:
    """Words seen in training (index 0 pads, 1 stands for unknown words)."""

    words: list[str]

    def __post_init__(self) -> None:
        self.index = {w: i for i, w in enumerate(self.words)}

    @classmethod
    def build(cls, texts: Iterable[str], min_count: int = 1) -> WordVocab:
        counts = Counter(w for t in texts for w in tokenize(t))
        kept = sorted(w for w, c in counts.items() if c >= min_count)
        return cls(["<pad>", "<unk>", *kept])

    def encode(self, text: str) -> list[int]:
        ids = [self.index.get(w, UNK) for w in tokenize(text)]
        return ids or [UNK]

    def __len__(self) -> int:
        return len(self.words)


@dataclass
class StepVocab:
    """The steps a model can emit: index 0 ends the program, then every training step.

    `actions` and `objects` list the parts step embeddings are built from (index 0 of each
    is the end marker / no object).
    """

    steps: list[StepKey]

    def __post_init__(self) -> None:
        self.index = {s: i for i, s in enumerate(self.steps)}
        self.actions = ["<end>", *sorted({a for a, _ in self.steps[1:]})]
        self.objects = ["<none>", *sorted({o for _, objs in self.steps[1:] for o in objs})]
        a_index = {a: i for i, a in enumerate(self.actions)}
        o_index = {o: i for i, o in enumerate(self.objects)}
        self.table = [(0, 0, 0)] + [
            (a_index[a], *[o_index[o] for o in objs], *[0] * (2 - len(objs)))
            for a, objs in self.steps[1:]]

    @classmethod
    def build(cls, programs: Iterable[Program]) -> StepVocab:
        keys = sorted({step_key(s) for p in programs for s in p.steps})
        return cls([("<end>", ()), *keys])

    def encode(self, program: Program) -> list[int] | None:
        """Step indices ending with END, or None when a step is not in the vocabulary."""
        ids = [self.index.get(step_key(s)) for s in program.steps]
        return None if None in ids else [*ids, END]  # type: ignore[list-item]

    def decode(self, ids: Iterable[int]) -> Program:
        """The program of step indices (stops at END)."""
        steps = []
        for i in ids:
            if i == END:
                break
            action, objs = self.steps[i]
            steps.append(Step(ACTIONS[action], tuple(ObjectRef(o, 1) for o in objs)))
        return Program(tuple(steps))

    def __len__(self) -> int:
        return len(self.steps)

    def to_json(self) -> list:
        return [[a, list(o)] for a, o in self.steps]

    @classmethod
    def from_json(cls, data: list) -> StepVocab:
        return cls([(a, tuple(o)) for a, o in data])
