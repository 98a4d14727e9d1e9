"""Why a step cannot run: a kind that code reads, beside a sentence that people read.

Every effect function (`homesim.sim.effects`) returns None when its step runs, else a
`Failure`: its `kind` (one of `FailureKind`) and its `reason` (``the character is not
close to cup 12``). Plan scoring (`homesim.goals.plans`), repair (`homesim.ground.repair`)
and the editor read the kind; the words may change.

>>> f = Failure(FailureKind.ALREADY, "tv 14 is not off")
>>> f.kind.value, str(f)
('already', 'tv 14 is not off')
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum


class FailureKind(str, Enum):
    """What kind of precondition a step failed (its JSON value is the lower-case name)."""

    MISSING = "missing"
    """The home has no node for an object of the step."""
    UNREACHABLE = "unreachable"
    """The character is not close to the object, or one of them is in no room (or the
    object is in another room), or there is no free floor to stand on next to it."""
    NOT_FACING = "not_facing"
    """The step needs the character facing the object."""
    ENCLOSED = "enclosed"
    """The object is inside a closed container."""
    NOT_HELD = "not_held"
    """The step needs something in hand (the object, a knife, a cloth) that is not."""
    HANDS_FULL = "hands_full"
    """The step needs a free hand and both hands hold something."""
    POSTURE = "posture"
    """The character sits or lies where the step needs it standing, or the reverse."""
    ALREADY = "already"
    """The object (or the character) is already in the state the step brings about: open
    the open, switch on the on, sit while sitting, stand up while standing."""
    AFFORDANCE = "affordance"
    """The object cannot take the action: it lacks the property (not GRABBABLE, no
    switch, not food), or it is a room, or the step names it twice."""
    STATE = "state"
    """Another state must hold first: a closed container to put into, an unplugged
    device to switch on, a device that is on to open, a full seat, clothes not worn."""


@dataclass(frozen=True, slots=True)
class Failure:
    """A step's failed precondition: `kind` for code, `reason` (one sentence) for people."""

    kind: FailureKind
    reason: str

    def __str__(self) -> str:
        return self.reason
