"""The action catalog: the one table of every per-action fact, one row per action.

A row (`ActionSpec`) gives the action's canonical name (as printed in programs), its arity,
its editor category and wording, whether the paper animates it and which animation plays
it, and what preparation and grounding must know about it: whether it moves the agent or
needs reach, the properties its objects need, the states and posture it presupposes.
Everything else derives from these rows: `homesim.sim.effects` registers one effect
function per row, `homesim.render.animate` one animation per `motion`, `homesim.ground`
reads the columns, and ``/api/actions`` serves the rows to the editor. A contract test
(tests/test_registries.py) checks that every registry covers every row and nothing more;
docs/simulator.md ("Adding an action") walks through adding one.
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
    """One action of the catalog: every fact about it that is not its effect.

    Attributes:
        key: upper-case identifier, as the reference simulator and the data sets spell it.
        name: canonical spelling in printed programs (``SwitchOn``).
        arity: number of objects the action takes (0, 1 or 2).
        category: editor block category.
        animated: True for the 12 actions the paper animates in 3D.
        description: a short English gloss, used by the editor and the CLI.
        motion: the animation `homesim.render` plays for it (``walk``, ``reach``, ...).
        moves: the step takes the agent to its object (Walk, Run, Find).
        reach: the simulator needs the character close to the (last) object: grounding
            gives the agent a standing spot within reach of it, preparation puts an added
            object where the agent acts on it.
        handles: the step does something to its object (False for steps that only go to,
            turn to or look at it).
        needs: per argument, the requirements its object must meet, each a set of
            properties of which it needs one (the simulator's property checks, without
            their exceptions by class name). Grounding tries objects meeting them first;
            preparation adds an instance when none of the home's meets them.
        presupposes: states the first object must be in before the step (Open: CLOSED).
        presupposes_if_able: states presupposed only where the object has that state's
            group (a plug for PLUGGED_IN, a switch for OFF) and no earlier step set it.
        posture_needed: the character's posture before the step (StandUp: SITTING).
        posture_after: the character's posture after it (SITTING, LYING or STANDING).
        hands: what the step does with a held object: ``take`` (Grab), ``put`` (the first
            object ends at the second), ``let_go`` (it ends where the agent is).
        sets_states: states the first object is in after the step (Open: OPEN).
        worn_before: the object must be worn by the character before the step (PutOff).
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
    motion: str = "idle"
    moves: bool = False
    reach: bool = False
    handles: bool = True
    needs: tuple[tuple[Requirement, ...], ...] = ()
    presupposes: tuple[str, ...] = ()
    presupposes_if_able: tuple[str, ...] = ()
    posture_needed: str | None = None
    posture_after: str | None = None
    hands: str | None = None
    sets_states: tuple[str, ...] = ()
    worn_before: bool = False
    connector: str | None = None
    aliases: tuple[str, ...] = ()

    def __str__(self) -> str:
        return self.name

    def needs_of(self, position: int) -> tuple[Requirement, ...]:
        """The requirements of the object at argument `position` (none past the arity)."""
        return self.needs[position] if position < len(self.needs) else ()

    def to_dict(self) -> dict[str, Any]:
        """The row as JSON-ready data (sets become sorted lists)."""
        return {
            "key": self.key, "name": self.name, "arity": self.arity,
            "category": self.category.value, "animated": self.animated,
            "description": self.description, "motion": self.motion, "moves": self.moves,
            "reach": self.reach, "handles": self.handles,
            "needs": [[sorted(r) for r in arg] for arg in self.needs],
            "presupposes": list(self.presupposes),
            "presupposes_if_able": list(self.presupposes_if_able),
            "posture_needed": self.posture_needed, "posture_after": self.posture_after,
            "hands": self.hands, "sets_states": list(self.sets_states),
            "worn_before": self.worn_before, "connector": self.connector,
            "aliases": list(self.aliases),
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


def _needs(*args: str) -> tuple[tuple[Requirement, ...], ...]:
    """Per argument: requirements joined by ``&``, alternatives by ``|``
    (``"EATABLE&CUTTABLE"``, ``"DRINKABLE|RECIPIENT"``; ``""``: none)."""
    return tuple(tuple(frozenset(r.split("|")) for r in arg.split("&") if r) for arg in args)


_GOES = {"moves": True, "handles": False}
_LOOKS = {"handles": False}
_REACH = {"reach": True, "motion": "reach"}

# name, arity, category, animated, description; then every other column by keyword.
# Why Sit, Lie and Eat need reach and PutObjBack does not: `reach` is the simulator's
# closeness precondition on the step's own (last) object. Sitting, lying and eating
# check it; PutObjBack acts on an object in hand and goes back to where it was taken
# from, which is not one of its arguments. Whether a hand reaches out in the animation
# is the `motion` column (PutObjBack: reach; Sit: sit).
_ROWS: tuple[tuple[str, int, Category, bool, str, dict[str, Any]], ...] = (
    ("Walk", 1, _M, True, "walk to an object or a room",
     dict(_GOES, motion="walk", posture_after="STANDING")),
    ("Run", 1, _M, True, "run to an object or a room",
     dict(_GOES, motion="run", posture_after="STANDING")),
    ("Find", 1, _M, False, "find an object, walking to it if needed",
     dict(_GOES, motion="find")),
    ("TurnTo", 1, _M, False, "turn to face an object", dict(_LOOKS, motion="look")),
    ("LookAt", 1, _A, True, "look at an object the agent faces",
     dict(_LOOKS, motion="look",
          aliases=("LOOKAT_SHORT", "LOOKAT_MEDIUM", "LOOKAT_LONG"))),
    ("Watch", 1, _A, False, "watch something in the same room",
     dict(_LOOKS, motion="look", needs=_needs("LOOKABLE"))),
    ("PointAt", 1, _A, False, "point at an object the agent faces",
     dict(_LOOKS, motion="point")),
    ("Read", 1, _A, False, "read something held in hand",
     dict(motion="use_held", needs=_needs("READABLE"))),
    ("Greet", 1, _A, False, "greet a person", dict(motion="point", needs=_needs("PERSON"))),
    ("Grab", 1, _H, True, "take an object in a free hand",
     dict(_REACH, needs=_needs("GRABBABLE"), hands="take")),
    ("Drop", 1, _H, False, "let go of a held object", dict(motion="let_go", hands="let_go")),
    ("Release", 1, _H, False, "release a held object",
     dict(motion="let_go", hands="let_go")),
    ("Touch", 1, _H, True, "touch an object within reach", _REACH),
    ("Push", 1, _H, False, "push an object", _REACH),
    ("Pull", 1, _H, False, "pull a movable object", _REACH),
    ("Move", 1, _H, False, "move a movable object", _REACH),
    ("Squeeze", 1, _H, False, "squeeze something soft", _REACH),
    ("PutBack", 2, _P, True, "put a held object on another",
     dict(_REACH, needs=_needs("GRABBABLE", ""), hands="put", connector="on",
          aliases=("PUT",))),
    ("PutIn", 2, _P, False, "put a held object inside an open container",
     dict(_REACH, needs=_needs("GRABBABLE", ""), hands="put", connector="into")),
    ("PutObjBack", 1, _P, False, "put a held object back where it was taken from",
     dict(motion="reach", hands="let_go")),
    ("Pour", 2, _P, False, "pour a held liquid into a recipient",
     dict(_REACH, needs=_needs("POURABLE|DRINKABLE", "RECIPIENT"), connector="into")),
    ("Open", 1, _O, True, "open a door or container",
     dict(_REACH, needs=_needs("CAN_OPEN"), presupposes=("CLOSED",),
          presupposes_if_able=("OFF",), sets_states=("OPEN",))),
    ("Close", 1, _O, True, "close a door or container",
     dict(_REACH, needs=_needs("CAN_OPEN"), presupposes=("OPEN",), sets_states=("CLOSED",))),
    ("SwitchOn", 1, _D, True, "switch a device on",
     dict(_REACH, needs=_needs("HAS_SWITCH"), presupposes=("OFF",),
          presupposes_if_able=("PLUGGED_IN",), sets_states=("ON",))),
    ("SwitchOff", 1, _D, True, "switch a device off",
     dict(_REACH, needs=_needs("HAS_SWITCH"), presupposes=("ON",), sets_states=("OFF",))),
    ("PlugIn", 1, _D, False, "plug a device in",
     dict(_REACH, needs=_needs("HAS_PLUG"), presupposes=("PLUGGED_OUT",),
          sets_states=("PLUGGED_IN",))),
    ("PlugOut", 1, _D, False, "unplug a device",
     dict(_REACH, needs=_needs("HAS_PLUG"), presupposes=("PLUGGED_IN",),
          sets_states=("PLUGGED_OUT",))),
    ("Type", 1, _D, False, "type on a keyboard or device", _REACH),
    ("Sit", 1, _B, True, "sit on something sittable",
     dict(reach=True, motion="sit", needs=_needs("SITTABLE"), posture_after="SITTING")),
    ("StandUp", 0, _B, True, "stand up from sitting or lying",
     dict(motion="stand_up", posture_needed="SITTING", posture_after="STANDING")),
    ("Lie", 1, _B, False, "lie on something lieable",
     dict(reach=True, motion="lie", needs=_needs("LIEABLE"), posture_after="LYING")),
    ("Sleep", 0, _B, False, "sleep while lying or sitting",
     dict(motion="rest", posture_needed="LYING")),
    ("WakeUp", 0, _B, False, "wake up while lying or sitting",
     dict(motion="stand_up", posture_needed="LYING")),
    ("PutOn", 1, _B, False, "put on held clothes", dict(needs=_needs("CLOTHES"))),
    ("PutOff", 1, _B, False, "take off worn clothes",
     dict(needs=_needs("CLOTHES"), worn_before=True)),
    ("Wipe", 1, _C, False, "wipe an object clean with something held", _REACH),
    ("Wash", 1, _C, False, "wash an object", _REACH),
    ("Rinse", 1, _C, False, "rinse an object", _REACH),
    ("Scrub", 1, _C, False, "scrub an object", _REACH),
    ("Eat", 1, _E, False, "eat food, or food on a plate",
     dict(reach=True, motion="use_held", needs=_needs("EATABLE"))),
    ("Drink", 1, _E, False, "drink from a held recipient",
     dict(motion="use_held", needs=_needs("DRINKABLE|RECIPIENT"))),
    ("Cut", 1, _E, False, "cut food while holding a knife",
     dict(_REACH, needs=_needs("EATABLE&CUTTABLE"))),
)

ACTIONS: dict[str, ActionSpec] = {
    name.upper(): ActionSpec(name.upper(), name, arity, category, animated, description,
                             **columns)
    for name, arity, category, animated, description, columns in _ROWS
}
"""Every action by its upper-case key (``ACTIONS["SWITCHON"].name == "SwitchOn"``)."""

_ALIASES: dict[str, str] = {alias: a.key for a in ACTIONS.values() for alias in a.aliases}
"""Spellings found in VirtualHome data -> the catalog key they name."""

ANIMATED: frozenset[str] = frozenset(k for k, a in ACTIONS.items() if a.animated)


def keys_where(column: str, value: Any = True) -> frozenset[str]:
    """Keys of the actions whose `column` equals `value` (``keys_where("moves")``)."""
    return frozenset(k for k, a in ACTIONS.items() if getattr(a, column) == value)


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
