"""Which object classes a description names: knowledge-base names plus words learned from training.

A class is *mentioned* by a text when every word of one of its names occurs in it: the class
name itself (``remote_control``: "remote" and "control") or a script name the knowledge base
gives it (``television``: "tv"). Names of one or two letters are ignored. On top of that,
`ObjectLexicon.fit` learns associations from the training pairs: a word w points to a class
c when c is in the program of at least ``min_pairs`` training examples whose text has w, in
at least ``precision`` of the examples whose text has w and ``coverage`` of the programs
with c ("kitchen" -> ``dining_room``, "living" -> ``home_office``).

The same rule links words to action keys ("sit" -> ``SIT``). It also learns how often each
class is left implicit: in a program but not mentioned by its text (rooms and the objects
one walks to usually are).
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field

from homesim.knowledge.objects import load_kb
from homesim.learn.data import Example
from homesim.program.model import Program


@dataclass(frozen=True)
class LexiconConfig:
    """When a word points to a class or an action (part of `config.RerankConfig`)."""

    min_pairs: int = 2
    """Training examples whose text has the word and whose program has the part."""
    precision: float = 0.5
    """Share of the examples whose text has the word that have the part."""
    coverage: float = 0.2
    """Share of the programs with the part whose text has the word."""


def words(text: str) -> list[str]:
    """The lower-case words of a text."""
    return re.findall(r"[a-z]+", text.lower())


def classes(program: Program) -> frozenset[str]:
    """The object classes a program uses."""
    return frozenset(ref.name for step in program.steps for ref in step.args)


@dataclass
class ObjectLexicon:
    """Class names (knowledge base and training classes) and learned word -> class links."""

    names: list[tuple[frozenset[str], str]]
    links: dict[str, frozenset[str]] = field(default_factory=dict)
    implicit: dict[str, float] = field(default_factory=dict)
    action_links: dict[str, frozenset[str]] = field(default_factory=dict)

    @classmethod
    def fit(cls, train: list[Example], config: LexiconConfig = LexiconConfig()
            ) -> ObjectLexicon:
        """The lexicon of the knowledge base's classes and `train`'s, with learned links."""
        kb = load_kb()
        seen = sorted({c for e in train for c in classes(e.program)} | set(kb.classes()))
        names = sorted({(frozenset(name.split("_")), c) for c in seen
                        for name in (c, *kb.script_names(c)) if len(name) > 2},
                       key=lambda n: (n[1], sorted(n[0])))
        lexicon = cls(names, _links(train, classes, config))
        lexicon.implicit = _implicit_rates(train, lexicon)
        lexicon.action_links = _links(train, actions, config)
        return lexicon

    def mentions(self, text: str) -> frozenset[str]:
        """The classes `text` names or points to."""
        present = set(words(text))
        found = {c for parts, c in self.names if parts <= present}
        for w in present:
            found |= self.links.get(w, frozenset())
        return frozenset(found)

    def actions(self, text: str) -> frozenset[str]:
        """The action keys `text` points to (learned links only)."""
        found: set[str] = set()
        for w in set(words(text)):
            found |= self.action_links.get(w, frozenset())
        return frozenset(found)

    def implicit_rate(self, cls: str) -> float:
        """How often `cls` is in a training program whose text does not mention it
        (add-one smoothed; 0.5 for a class never in training)."""
        return self.implicit.get(cls, 0.5)


def actions(program: Program) -> frozenset[str]:
    """The action keys a program uses."""
    return frozenset(step.action.key for step in program.steps)


def _links(train: list[Example], parts: Callable[[Program], frozenset[str]],
           config: LexiconConfig) -> dict[str, frozenset[str]]:
    """Word -> program parts (classes or actions) learned from co-occurrence in the
    training pairs (`LexiconConfig`)."""
    with_word: Counter[str] = Counter()
    with_class: Counter[str] = Counter()
    both: Counter[tuple[str, str]] = Counter()
    for e in train:
        present, used = set(words(e.text)), parts(e.program)
        with_word.update(present)
        with_class.update(used)
        both.update((w, c) for w in present for c in used)
    links: dict[str, set[str]] = {}
    for (w, c), n in sorted(both.items()):
        if (n >= config.min_pairs and n >= config.precision * with_word[w]
                and n >= config.coverage * with_class[c]):
            links.setdefault(w, set()).add(c)
    return {w: frozenset(cs) for w, cs in links.items()}


def _implicit_rates(train: list[Example], lexicon: ObjectLexicon) -> dict[str, float]:
    """Class -> share of the training programs with it whose text does not mention it."""
    used: Counter[str] = Counter()
    unsaid: Counter[str] = Counter()
    for e in train:
        said = lexicon.mentions(e.text)
        for c in classes(e.program):
            used[c] += 1
            unsaid[c] += c not in said
    return {c: (unsaid[c] + 1) / (used[c] + 2) for c in sorted(used)}
