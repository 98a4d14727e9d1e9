"""What the agent observes: where it is, what it holds, what it sees, as text and structure.

The agent sees the objects of the room it is in (not walls, floors, ceilings, body parts
or what is inside a closed container), what it holds, and the names of all rooms (so it can
walk to another one). Each object is written as a program would name it, with its node id
as the instance: ``<tv> (14)``, so an action can be copied from the observation
(``[SwitchOn] <tv> (14)``).

>>> from homesim.sim import SimState
>>> from homesim.world import load_home
>>> obs = observe(SimState(load_home("scene1_trimmed")))
>>> obs["room"], obs["holding"]
('<bathroom> (1)', ())
>>> obs["text"].splitlines()[0]
'You are in <bathroom> (1). You hold nothing.'
"""

from __future__ import annotations

import string
from typing import Any

from homesim.sim.effects import closed_container, held, is_close
from homesim.sim.state import SimState
from homesim.world.vocab import BODY_PART

CHARSET = frozenset(string.printable)
"""Characters of observation and action text (printable ASCII)."""

MAX_TEXT = 16384
"""Observation text is cut to this many characters."""

MAX_OBJECTS = 256
"""At most this many visible objects are listed (lowest node ids first)."""

_UNSEEN = frozenset({"Walls", "Ceiling", "Floor", "Floors", "Rooms", "Characters"})


def ref(st: SimState, node: int) -> str:
    """A node as a program names it, instance = node id: ``<tv> (14)``."""
    return f"<{st.class_name(node)}> ({node})"


def visible(st: SimState) -> list[int]:
    """Node ids the character sees: objects of its room not hidden in a closed container,
    and what it holds."""
    room = st.room_of(st.char)
    hands = set(held(st))
    seen = []
    for node in st.graph.nodes.values():
        n = node.id
        if n in hands or node.category in _UNSEEN or BODY_PART in node.properties:
            continue
        if st.room_of(n) == room and closed_container(st, n) is None:
            seen.append(n)
    return sorted([*seen, *hands])[:MAX_OBJECTS]


def observe(st: SimState, goal_text: str | None = None) -> dict[str, Any]:
    """The observation: ``text`` (for people and language models), ``room``, ``holding``
    (refs), ``objects`` (one dict per visible object: ``id``, ``name``, ``states``
    (comma-joined), ``close`` (1 when within reach)) and ``rooms`` (refs)."""
    room = st.room_of(st.char)
    here = "nowhere" if room is None else ref(st, room)
    holding = tuple(ref(st, n) for n in held(st))
    objects = tuple({"id": n, "name": st.class_name(n), "states": ",".join(sorted(st.states(n))),
                     "close": int(is_close(st, n))} for n in visible(st))
    rooms = tuple(ref(st, r) for r in sorted(st.rooms))
    posture = sorted(st.states(st.char) & {"SITTING", "LYING"})
    lines = [f"You are in {here}. You hold {', '.join(holding) or 'nothing'}."
             + (f" You are {posture[0].lower()}." if posture else "")]
    lines.append("You see: " + ", ".join(_seen(st, o) for o in objects) + ".")
    lines.append("Rooms: " + ", ".join(rooms) + ".")
    if goal_text:
        lines.append(f"Goal: {goal_text}.")
    text = "\n".join(lines)
    text = "".join(c for c in text if c in CHARSET)[:MAX_TEXT]
    return {"text": text, "room": here, "holding": holding, "objects": objects,
            "rooms": rooms}


def _seen(st: SimState, o: dict[str, Any]) -> str:
    extra = [s for s in (o["states"], "close" if o["close"] else "") if s]
    return ref(st, o["id"]) + (f" [{'; '.join(extra)}]" if extra else "")
