"""The action catalog: every action a program may use, as one table row each.

A row gives the action's canonical name (as printed in programs), its arity (how many
objects it takes), its category (the block palette of the editor, after the paper's
Scratch interface) and whether the paper animates it. The simulator registers one effect
function per row (`homesim.sim.effects`); a contract test checks that each row has one.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from enum import Enum
from typing import Any


class Category(str, Enum):
    """The 9 block categories of the program editor."""

    MOVEMENT = "movement"
    ATTENTION = "attention"
    HANDS = "hands"
    PLACING = "placing"
    OPEN_CLOSE = "open_close"
    DEVICES = "devices"
    BODY = "body"
    CLEANING = "cleaning"
    EATING = "eating"


Requirement = frozenset[str]
"""Properties of which an object needs at least one (``{"DRINKABLE", "RECIPIENT"}``)."""


@dataclass(frozen=True, slots=True)
class ActionSpec:
    """One action of the catalog.

    Attributes:
        key: upper-case identifier, as the reference simulator and the data sets spell it.
        name: canonical spelling in printed programs (``SwitchOn``).
        arity: number of objects the action takes (0, 1 or 2).
        category: editor block category.
        animated: True for the 12 actions the paper animates in 3D.
        description: a short English gloss, used by the editor and the CLI.
        needs: per argument, the requirements its object must meet, each a set of
            properties of which it needs one (the editor lists such objects first).
        connector: the word between the two objects in the editor's block (PutBack
            <plate> *on* <table>); None for actions with fewer than two.
        aliases: other spellings of the key found in data (``PUT`` for PutBack).

    >>> ACTIONS["PUTIN"].to_dict()["connector"]
    'into'
    """

    key: str
    name: str
    arity: int
    category: Category
    animated: bool
    description: str
    needs: tuple[tuple[Requirement, ...], ...] = ()
    connector: str | None = None
    aliases: tuple[str, ...] = ()

    def __str__(self) -> str:
        return self.name

    def to_dict(self) -> dict[str, Any]:
        """The row as JSON-ready data (sets become sorted lists)."""
        return {
            "key": self.key, "name": self.name, "arity": self.arity,
            "category": self.category.value, "animated": self.animated,
            "description": self.description,
            "needs": [[sorted(r) for r in arg] for arg in self.needs],
            "connector": self.connector, "aliases": list(self.aliases),
        }


_M, _A, _H, _P, _O, _D, _B, _C, _E = (
    Category.MOVEMENT,
    Category.ATTENTION,
    Category.HANDS,
    Category.PLACING,
    Category.OPEN_CLOSE,
    Category.DEVICES,
    Category.BODY,
    Category.CLEANING,
    Category.EATING,
)

# name, arity, category, animated, description
_ROWS: tuple[tuple[str, int, Category, bool, str], ...] = (
    ("Walk", 1, _M, True, "walk to an object or a room"),
    ("Run", 1, _M, True, "run to an object or a room"),
    ("Find", 1, _M, False, "find an object, walking to it if needed"),
    ("TurnTo", 1, _M, False, "turn to face an object"),
    ("LookAt", 1, _A, True, "look at an object the agent faces"),
    ("Watch", 1, _A, False, "watch something in the same room"),
    ("PointAt", 1, _A, False, "point at an object the agent faces"),
    ("Read", 1, _A, False, "read something held in hand"),
    ("Greet", 1, _A, False, "greet a person"),
    ("Grab", 1, _H, True, "take an object in a free hand"),
    ("Drop", 1, _H, False, "let go of a held object"),
    ("Release", 1, _H, False, "release a held object"),
    ("Touch", 1, _H, True, "touch an object within reach"),
    ("Push", 1, _H, False, "push an object"),
    ("Pull", 1, _H, False, "pull a movable object"),
    ("Move", 1, _H, False, "move a movable object"),
    ("Squeeze", 1, _H, False, "squeeze something soft"),
    ("PutBack", 2, _P, True, "put a held object on another"),
    ("PutIn", 2, _P, False, "put a held object inside an open container"),
    ("PutObjBack", 1, _P, False, "put a held object back where it was taken from"),
    ("Pour", 2, _P, False, "pour a held liquid into a recipient"),
    ("Open", 1, _O, True, "open a door or container"),
    ("Close", 1, _O, True, "close a door or container"),
    ("SwitchOn", 1, _D, True, "switch a device on"),
    ("SwitchOff", 1, _D, True, "switch a device off"),
    ("PlugIn", 1, _D, False, "plug a device in"),
    ("PlugOut", 1, _D, False, "unplug a device"),
    ("Type", 1, _D, False, "type on a keyboard or device"),
    ("Sit", 1, _B, True, "sit on something sittable"),
    ("StandUp", 0, _B, True, "stand up from sitting or lying"),
    ("Lie", 1, _B, False, "lie on something lieable"),
    ("Sleep", 0, _B, False, "sleep while lying or sitting"),
    ("WakeUp", 0, _B, False, "wake up while lying or sitting"),
    ("PutOn", 1, _B, False, "put on held clothes"),
    ("PutOff", 1, _B, False, "take off worn clothes"),
    ("Wipe", 1, _C, False, "wipe an object clean with something held"),
    ("Wash", 1, _C, False, "wash an object"),
    ("Rinse", 1, _C, False, "rinse an object"),
    ("Scrub", 1, _C, False, "scrub an object"),
    ("Eat", 1, _E, False, "eat food, or food on a plate"),
    ("Drink", 1, _E, False, "drink from a held recipient"),
    ("Cut", 1, _E, False, "cut food while holding a knife"),
)



def _needs(*args: str) -> tuple[tuple[Requirement, ...], ...]:
    """Per argument: requirements joined by ``&``, alternatives by ``|``
    (``"DRINKABLE|RECIPIENT"``; ``""``: none)."""
    return tuple(tuple(frozenset(r.split("|")) for r in arg.split("&") if r) for arg in args)


# The other columns, for the rows that have them.
_MORE: dict[str, dict[str, Any]] = {
    "LookAt": dict(aliases=("LOOKAT_SHORT", "LOOKAT_MEDIUM", "LOOKAT_LONG")),
    "Watch": dict(needs=_needs("LOOKABLE")),
    "Read": dict(needs=_needs("READABLE")),
    "Greet": dict(needs=_needs("PERSON")),
    "Grab": dict(needs=_needs("GRABBABLE")),
    "PutBack": dict(needs=_needs("GRABBABLE", ""), connector="on", aliases=("PUT",)),
    "PutIn": dict(needs=_needs("GRABBABLE", ""), connector="into"),
    "Pour": dict(needs=_needs("POURABLE|DRINKABLE", "RECIPIENT"), connector="into"),
    "Open": dict(needs=_needs("CAN_OPEN")),
    "Close": dict(needs=_needs("CAN_OPEN")),
    "SwitchOn": dict(needs=_needs("HAS_SWITCH")),
    "SwitchOff": dict(needs=_needs("HAS_SWITCH")),
    "PlugIn": dict(needs=_needs("HAS_PLUG")),
    "PlugOut": dict(needs=_needs("HAS_PLUG")),
    "Sit": dict(needs=_needs("SITTABLE")),
    "Lie": dict(needs=_needs("LIEABLE")),
    "PutOn": dict(needs=_needs("CLOTHES")),
    "PutOff": dict(needs=_needs("CLOTHES")),
    "Drink": dict(needs=_needs("DRINKABLE|RECIPIENT")),
    "Cut": dict(needs=_needs("CUTTABLE")),
}

ACTIONS: dict[str, ActionSpec] = {
    name.upper(): ActionSpec(name.upper(), name, arity, category, animated, description,
                             **_MORE.get(name, {}))
    for name, arity, category, animated, description in _ROWS
}
"""Every action by its upper-case key (``ACTIONS["SWITCHON"].name == "SwitchOn"``)."""

# Spellings found in VirtualHome data that name a catalog action.
_ALIASES: dict[str, str] = {alias: a.key for a in ACTIONS.values() for alias in a.aliases}

ANIMATED: frozenset[str] = frozenset(k for k, a in ACTIONS.items() if a.animated)


def lookup_action(text: str) -> ActionSpec | None:
    """Return the action spelled `text` in any case (``walk``, ``WALK``, ``Walk``), or None."""
    key = text.upper().replace(" ", "").replace("-", "")
    key = _ALIASES.get(key, key)
    return ACTIONS.get(key)


def suggest_action(text: str) -> str | None:
    """Return the canonical name of the catalog action closest to `text`, if any is close."""
    keys = list(ACTIONS) + list(_ALIASES)
    match = difflib.get_close_matches(text.upper(), keys, n=1, cutoff=0.6)
    if not match:
        return None
    return ACTIONS[_ALIASES.get(match[0], match[0])].name


def actions_in(category: Category) -> list[ActionSpec]:
    """The actions of one editor category, in catalog order."""
    return [a for a in ACTIONS.values() if a.category is category]
