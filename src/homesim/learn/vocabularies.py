"""Vocabularies: description words, and program steps built from actions and objects.

A step is reduced to its key, (action key, ((class name, instance), ...)): the instance
numbers are kept, so a decoded program can use two chairs (``<chair> (1)``, ``<chair> (2)``).
The metrics ignore instance numbers; the simulator does not.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass

from homesim.program.actions import ACTIONS
from homesim.program.model import ObjectRef, Program, Step

ObjectKey = tuple[str, int]
"""(class name, instance number) of a step's object."""
StepKey = tuple[str, tuple[ObjectKey, ...]]
"""(action key, objects) of a step."""
MAX_INSTANCE = 4
"""Instances above this share one instance embedding (`StepVocab.table`)."""

PAD, UNK = 0, 1
END = 0
"""Index of the end-of-program step in a `StepVocab`."""
_WORD = re.compile(r"[a-z]+|\d+")


def tokenize(text: str) -> list[str]:
    """Lower-case words of a description."""
    return _WORD.findall(text.lower())


def step_key(step: Step) -> StepKey:
    """The step's action key and its objects' (class, instance)."""
    return (step.action.key, tuple((ref.name, ref.instance) for ref in step.args))


def key_step(key: StepKey) -> Step:
    """The ungrounded step of a key."""
    return Step(ACTIONS[key[0]], tuple(ObjectRef(name, inst) for name, inst in key[1]))


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
    is the end marker / no object); `table` gives each step's (action, object, object,
    instance, instance) indices, instance index 0 standing for instance 1 or no object.
    """

    steps: list[StepKey]

    def __post_init__(self) -> None:
        self.index = {s: i for i, s in enumerate(self.steps)}
        self.actions = ["<end>", *sorted({a for a, _ in self.steps[1:]})]
        self.objects = ["<none>", *sorted({o for _, objs in self.steps[1:] for o, _ in objs})]
        a_index = {a: i for i, a in enumerate(self.actions)}
        o_index = {o: i for i, o in enumerate(self.objects)}
        pad = [0] * 2
        self.table = [(0, 0, 0, 0, 0)] + [
            (a_index[a], *([o_index[o] for o, _ in objs] + pad)[:2],
             *([min(i, MAX_INSTANCE) - 1 for _, i in objs] + pad)[:2])
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
            steps.append(key_step(self.steps[i]))
        return Program(tuple(steps))

    def unseen_share(self, programs: Iterable[Program]) -> float:
        """Share of the programs' steps that are not in the vocabulary (no model can emit
        them: they bound the step LCS any decoder here reaches)."""
        keys = [step_key(s) for p in programs for s in p.steps]
        return sum(k not in self.index for k in keys) / max(1, len(keys))

    def __len__(self) -> int:
        return len(self.steps)

    def to_json(self) -> list:
        return [[a, [list(o) for o in objs]] for a, objs in self.steps]

    @classmethod
    def from_json(cls, data: list) -> StepVocab:
        return cls([(a, tuple((o, int(i)) for o, i in objs)) for a, objs in data])
