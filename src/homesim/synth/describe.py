"""Descriptions that read like people: a seeded paraphrase grammar over a program's steps.

The fixed templates (`homesim.synth.templates`) say every task in one of 3-5 phrases; a
model learns to invert them. People write differently, and this grammar imitates how:

1. **Clauses.** Runs of steps that belong together become one clause (`PATTERNS`: open
   the fridge + grab the milk = "take the milk out of the fridge"; switch on the TV + sit
   on the sofa + look at the TV = "turn on the TV and watch it from the sofa"); every
   clause kind has several phrasings (`homesim.synth.phrasebook.PHRASINGS`).
2. **Obvious steps left out.** A walk to the object the next clause is about is usually
   not said ("grab the cup", not "walk to the cup and grab it"), or said as a lead-in
   ("go to the fridge and open it"); standing up before walking away sometimes is not.
   Walks to rooms are always said.
3. **Names and pronouns.** An object just mentioned is usually "it"; objects have the
   names people use (television: "TV"; couch: "sofa"); a first mention may be "a cup"
   or say where it is ("the cup on the kitchen counter").
4. **Order.** Adjacent clauses that commute (disjoint objects, each starts by walking to
   its own object, no hands left full, no posture change) may be told in either order;
   "Before you sit down, turn on the TV" tells two clauses back to front while keeping
   their order.
5. **Sentences.** One voice per description ("Grab the cup" or "I grab the cup"); 1-3
   clauses per sentence with varied connectors and sentence starters; sometimes an
   opening sentence for the activity ("I want to watch some TV.").

Every choice comes from the `random.Random` passed in: same seed, same text.
`Description.order` is the step order the text implies (a valid order of the program:
tests/synth/test_describe.py runs it) and `omitted` the steps it leaves out.
"""

from __future__ import annotations

import random
import re
from collections.abc import Sequence
from dataclasses import dataclass, field

from homesim.synth.phrasebook import (
    CONNECTORS,
    EXTRAS,
    FIRST_STARTERS,
    LAST_STARTERS,
    LEADS,
    OPENERS,
    PHRASINGS,
    STARTERS,
)
from homesim.world.class_table import class_row


@dataclass(frozen=True)
class Thing:
    """An object of a step: its node (what makes two mentions the same), its class, and
    where it is when the program starts, as (``"on"``, ``"desk"``), if known."""

    node: int
    name: str
    room: bool = False
    where: tuple[str, str] | None = None


Act = tuple[str, tuple[Thing, ...]]
"""One program step: an action key (``GRAB``) and its objects."""


@dataclass(frozen=True)
class Description:
    """A description, the step order it implies, and the steps it leaves out."""

    text: str
    order: tuple[int, ...]
    omitted: tuple[int, ...]


PATTERNS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("watch", ("SWITCHON x", "WALK y?", "SIT y", "LOOKAT x")),
    ("take_out_close_put", ("OPEN c", "GRAB x", "CLOSE c", "WALK y?", "PUTBACK x y")),
    ("take_out_put", ("OPEN c", "GRAB x", "WALK y?", "PUTBACK x y")),
    ("take_out_close", ("OPEN c", "GRAB x", "CLOSE c")),
    ("take_out", ("OPEN c", "GRAB x")),
    ("move", ("GRAB x", "WALK y?", "PUTBACK x y")),
    ("open_close", ("OPEN x", "CLOSE x")),
    ("sit_look", ("SIT x", "LOOKAT y")),
)
"""Runs of steps said as one clause, longest first: ``ACTION slots``, ``?`` = optional
(an optional walk is left out of the text). Adjacent steps are taken to belong together,
as they do in the grammar's tasks."""

SINGLE: dict[str, str] = {
    "SWITCHON": "switch_on", "SWITCHOFF": "switch_off", "GRAB": "grab", "PUTBACK": "put",
    "OPEN": "open", "CLOSE": "close", "TOUCH": "touch", "SIT": "sit", "LOOKAT": "look",
    "STANDUP": "stand_up",
}
"""A step said on its own: action -> clause kind (walks: `_walk_kind`)."""

WALKS = frozenset({"WALK", "RUN", "FIND"})
_WALK_KINDS = frozenset({"walk_obj", "run_obj", "walk_room", "run_room"})
_SWAPPABLE = frozenset({"switch_on", "switch_off", "open", "close", "open_close", "touch",
                        "move", "take_out_put", "take_out_close_put"})

P_LEAVE_OUT_WALK = 0.7
P_LEAVE_OUT_STANDUP = 0.35
P_PRONOUN = 0.75
P_SWAP = 0.25
P_BEFORE = 0.12
P_AFTER = 0.08
P_OPENER = 0.3
P_EXTRA = 0.15
P_FIRST_PERSON = 0.5
P_WHERE = 0.15
_PERSON = {"my": ("my", "your"), "me": ("me", "you"), "I": ("I", "you")}
"""Voice-dependent slots: (first person, imperative)."""


@dataclass(frozen=True)
class Clause:
    """Steps said together: the phrasing kind, its objects, and which steps it covers."""

    kind: str
    slots: dict[str, Thing]
    steps: tuple[int, ...]
    omitted: tuple[int, ...] = ()
    lead: Thing | None = None
    walks_first: bool = False
    """Whether its first step is a walk to its own object (then where the agent was
    before does not matter to it)."""

    def nodes(self) -> frozenset[int]:
        extra = () if self.lead is None else (self.lead.node,)
        return frozenset([*(t.node for t in self.slots.values()), *extra])


# ------------------------------------------------------------------ steps -> clauses
def _bind(element: str, act: Act, slots: dict[str, Thing]) -> bool:
    """Whether `act` fits a pattern element, binding its slot names in `slots`."""
    key, *names = element.rstrip("?").split()
    fits = act[0] in WALKS if key == "WALK" else act[0] == key
    if not fits or len(names) != len(act[1]):
        return False
    for name, thing in zip(names, act[1], strict=True):
        if slots.setdefault(name, thing).node != thing.node:
            return False
    return True


def _match(acts: Sequence[Act], i: int, elements: tuple[str, ...]
           ) -> tuple[dict[str, Thing], list[int], list[int]] | None:
    """Slots, covered and left-out steps of the pattern at step `i`, or None."""
    slots: dict[str, Thing] = {}
    covered: list[int] = []
    skipped: list[int] = []
    j = i
    for element in elements:
        trial = dict(slots)
        if j < len(acts) and _bind(element, acts[j], trial):
            slots = trial
            covered.append(j)
            if element.endswith("?"):
                skipped.append(j)
            j += 1
        elif not element.endswith("?"):
            return None
    return slots, covered, skipped


def _walk_kind(act: Act) -> str:
    target = act[1][0]
    run = act[0] == "RUN"
    if target.room:
        return "run_room" if run else "walk_room"
    return "run_obj" if run else "walk_obj"


def _clause_at(acts: Sequence[Act], i: int, rng: random.Random) -> Clause:
    """The clause starting at step `i` (with an obvious walk or stand-up folded in)."""
    folded = _fold_walk(acts, i, rng) or _fold_stand_up(acts, i, rng)
    if folded is not None:
        return folded
    for kind, elements in PATTERNS:
        found = _match(acts, i, elements)
        if found:
            slots, covered, skipped = found
            return Clause(kind, slots, tuple(covered), tuple(skipped))
    key, things = acts[i]
    if key in WALKS and things:
        return Clause(_walk_kind(acts[i]), {"room" if things[0].room else "x": things[0]}, (i,))
    return Clause(SINGLE.get(key, key), dict(zip("xy", things, strict=False)), (i,))


def _fold_walk(acts: Sequence[Act], i: int, rng: random.Random) -> Clause | None:
    """A walk to the object of the next clause, folded into it: left out or said as a
    lead-in ("go to the fridge and ..."); None if step `i` is no such walk."""
    key, things = acts[i]
    if key not in WALKS or not things or things[0].room or i + 1 == len(acts):
        return None
    following = _clause_at(acts, i + 1, rng)
    if (things[0].node not in following.nodes() or following.lead is not None
            or following.kind in _WALK_KINDS):
        return None
    steps = (i, *following.steps)
    if rng.random() < P_LEAVE_OUT_WALK:
        return Clause(following.kind, following.slots, steps, (i, *following.omitted),
                      walks_first=True)
    return Clause(following.kind, following.slots, steps, following.omitted,
                  lead=things[0], walks_first=True)


def _fold_stand_up(acts: Sequence[Act], i: int, rng: random.Random) -> Clause | None:
    """Sometimes, standing up left out before the next clause; None if not."""
    if acts[i][0] != "STANDUP" or i + 1 == len(acts) or rng.random() >= P_LEAVE_OUT_STANDUP:
        return None
    following = _clause_at(acts, i + 1, rng)
    return Clause(following.kind, following.slots, (i, *following.steps),
                  (i, *following.omitted), following.lead)


def clauses(acts: Sequence[Act], rng: random.Random) -> list[Clause]:
    """The program's steps cut into clauses, in program order."""
    out: list[Clause] = []
    i = 0
    while i < len(acts):
        clause = _clause_at(acts, i, rng)
        out.append(clause)
        i = max(clause.steps) + 1
    return out


def commute(a: Clause, b: Clause) -> bool:
    """Whether two adjacent clauses may be told in either order: each walks to its own
    objects first, they share none, and neither leaves a hand full or changes posture."""
    return (a.kind in _SWAPPABLE and b.kind in _SWAPPABLE
            and a.walks_first and b.walks_first and not a.nodes() & b.nodes())


def _reorder(parts: list[Clause], rng: random.Random) -> list[Clause]:
    out = list(parts)
    for i in range(len(out) - 1):
        if commute(out[i], out[i + 1]) and rng.random() < P_SWAP:
            out[i], out[i + 1] = out[i + 1], out[i]
    return out


# ------------------------------------------------------------------ clauses -> words
def names_for(class_name: str) -> tuple[str, ...]:
    """What a description may call an object of this class (``television``: "TV", ...):
    its class-table row's names, else the class name with spaces."""
    row = class_row(class_name)
    return row.names if row is not None and row.names else (class_name.replace("_", " "),)


@dataclass
class _Speaker:
    """Says noun phrases: pronouns for the object just mentioned, names people use."""

    rng: random.Random
    first_person: bool
    last: int | None = None
    names: dict[int, str] = field(default_factory=dict)

    def name(self, thing: Thing) -> str:
        if thing.node not in self.names:
            self.names[thing.node] = self.rng.choice(names_for(thing.name))
        return self.names[thing.node]

    def noun_phrase(self, thing: Thing, slot: str) -> str:
        """`thing` said in `slot` (``x``: may be "it" or "a cup"; ``X``: a name)."""
        again = thing.node in self.names
        if slot.islower() and thing.node == self.last and self.rng.random() < P_PRONOUN:
            return "it"
        name = self.name(thing)
        self.last = thing.node
        said = self._determiner(thing, name, slot, again) + name
        if not again and thing.where is not None and self.rng.random() < P_WHERE:
            preposition, place = thing.where  # "the cup on the kitchen counter"
            return f"{said} {preposition} the {names_for(place)[0]}"
        return said

    def _determiner(self, thing: Thing, name: str, slot: str, again: bool) -> str:
        if self._namesake(thing, name):  # a second rug: "another rug", "the other rug"
            return "another " if not again and slot in "xX" else "the other "
        roll = self.rng.random()
        if not again and slot in "xX" and roll < 0.2 and not name.endswith("s"):
            return "an " if name[0] in "aeiou" else "a "
        if not again and self.first_person and roll > 0.9:
            return "my "
        return "the "

    def _namesake(self, thing: Thing, name: str) -> bool:
        """Whether an object mentioned before `thing` goes by the same name."""
        for node, other in self.names.items():
            if node == thing.node:
                return False
            if other == name:
                return True
        return False

    def fill(self, template: str, slots: dict[str, Thing]) -> str:
        def slot(m: re.Match[str]) -> str:
            key = m.group(1)
            if key in _PERSON:
                return _PERSON[key][0 if self.first_person else 1]
            return self.noun_phrase(slots[key.lower()], "ROOM" if key == "room" else key)

        return re.sub(r"\{(\w+)\}", slot, template)

    def verb_phrase(self, clause: Clause) -> str:
        """The clause in words (base form: fits "I ..." and the imperative)."""
        said = self._clause_words(clause)
        extras = EXTRAS.get(clause.kind)
        if extras and self.rng.random() < P_EXTRA:
            return said + " " + self.fill(self.rng.choice(extras), {})
        return said

    def _clause_words(self, clause: Clause) -> str:
        phrasings = PHRASINGS.get(clause.kind)
        if phrasings is None:  # an action the phrasebook lacks: its key as the verb
            phrasings = (" ".join([clause.kind.lower(), *(f"{{{k}}}" for k in clause.slots)]),)
        if clause.lead is None:
            return self.fill(self.rng.choice(phrasings), clause.slots)
        lead = self.fill(self.rng.choice(LEADS), {"x": clause.lead})
        # Just named by the lead: prefer phrasings that may call it "it".
        named = [k.upper() for k, t in clause.slots.items() if t.node == clause.lead.node]
        fits = [p for p in phrasings if not any(f"{{{k}}}" in p for k in named)]
        return lead + " " + self.fill(self.rng.choice(fits or phrasings), clause.slots)


def _sentence(speaker: _Speaker, group: list[Clause], starter: str) -> str:
    rng = speaker.rng
    subject = "I " if speaker.first_person else ""
    text = starter + subject + speaker.verb_phrase(group[0])
    for clause in group[1:]:
        connector = rng.choice(CONNECTORS)
        again = subject if connector.startswith(",") and rng.random() < 0.5 else ""
        text += connector + again + speaker.verb_phrase(clause)
    return text


def _two_way(speaker: _Speaker, first: Clause, then: Clause, before: bool) -> str:
    """"Before you B, A" (told back to front) or "After you A, B"."""
    you = "I" if speaker.first_person else "you"
    subject = "I " if speaker.first_person else ""
    if before:
        said = speaker.verb_phrase(then)
        return f"Before {you} {said}, {subject}{speaker.verb_phrase(first)}"
    said = speaker.verb_phrase(first)
    return f"After {you} {said}, {subject}{speaker.verb_phrase(then)}"


def _sentences(speaker: _Speaker, parts: list[Clause]) -> list[str]:
    rng = speaker.rng
    out: list[str] = []
    i = 0
    while i < len(parts):
        left = len(parts) - i
        roll = rng.random()
        if left >= 2 and roll < P_BEFORE + P_AFTER:
            out.append(_two_way(speaker, parts[i], parts[i + 1], before=roll < P_BEFORE))
            i += 2
            continue
        size = min(left, rng.choice((1, 2, 2, 3)))
        last = i + size >= len(parts)
        starter = rng.choice(FIRST_STARTERS if i == 0 else
                             LAST_STARTERS if last and i > 0 else STARTERS)
        out.append(_sentence(speaker, parts[i:i + size], starter))
        i += size
    return [s[0].upper() + s[1:] + "." for s in out]


def describe(acts: Sequence[Act], rng: random.Random, title: str | None = None
             ) -> Description:
    """A description of the program whose steps are `acts`, every choice from `rng`.

    >>> cup, table = Thing(5, "cup"), Thing(9, "kitchen_table")
    >>> acts = [("WALK", (cup,)), ("GRAB", (cup,)), ("WALK", (table,)),
    ...         ("PUTBACK", (cup, table))]
    >>> describe(acts, random.Random(2)).text
    'Find the cup and bring it over to the kitchen table.'
    """
    parts = _reorder(clauses(acts, rng), rng)
    speaker = _Speaker(rng, first_person=rng.random() < P_FIRST_PERSON)
    sentences = _sentences(speaker, parts)
    if title in OPENERS and rng.random() < P_OPENER:
        sentences.insert(0, rng.choice(OPENERS[title]))
    order = tuple(i for c in parts for i in c.steps)
    omitted = tuple(sorted(i for c in parts for i in c.omitted))
    return Description(" ".join(sentences), order, omitted)
