"""The words of environment graphs: relations, object states and properties.

Relations, states and properties are plain upper-case strings (as in VirtualHome JSON),
so graphs load without translation and compare with `==`; these constants name the ones
homesim knows.
"""

from __future__ import annotations

# Relations (edge types). CLOSE and FACING come in pairs for CLOSE; HOLDS_* go from the
# character to what its right or left hand holds.
ON = "ON"
INSIDE = "INSIDE"
BETWEEN = "BETWEEN"
CLOSE = "CLOSE"
FACING = "FACING"
HOLDS_RH = "HOLDS_RH"
HOLDS_LH = "HOLDS_LH"
SITTING = "SITTING"

RELATIONS: frozenset[str] = frozenset(
    {ON, INSIDE, BETWEEN, CLOSE, FACING, HOLDS_RH, HOLDS_LH, SITTING}
)
HANDS: tuple[str, str] = (HOLDS_RH, HOLDS_LH)

# Object states the simulator reads or writes.
S_CLOSED = "CLOSED"
S_OPEN = "OPEN"
S_ON = "ON"
S_OFF = "OFF"
S_SITTING = "SITTING"
S_LYING = "LYING"
S_DIRTY = "DIRTY"
S_CLEAN = "CLEAN"
S_PLUGGED_IN = "PLUGGED_IN"
S_PLUGGED_OUT = "PLUGGED_OUT"

STATES: frozenset[str] = frozenset(
    {S_CLOSED, S_OPEN, S_ON, S_OFF, S_SITTING, S_LYING, S_DIRTY, S_CLEAN, S_PLUGGED_IN,
     S_PLUGGED_OUT}
)

# Object properties (affordances) the simulator reads.
SURFACES = "SURFACES"
GRABBABLE = "GRABBABLE"
SITTABLE = "SITTABLE"
LIEABLE = "LIEABLE"
HANGABLE = "HANGABLE"
DRINKABLE = "DRINKABLE"
EATABLE = "EATABLE"
RECIPIENT = "RECIPIENT"
CUTTABLE = "CUTTABLE"
POURABLE = "POURABLE"
CAN_OPEN = "CAN_OPEN"
HAS_SWITCH = "HAS_SWITCH"
READABLE = "READABLE"
LOOKABLE = "LOOKABLE"
CONTAINERS = "CONTAINERS"
CLOTHES = "CLOTHES"
PERSON = "PERSON"
BODY_PART = "BODY_PART"
COVER_OBJECT = "COVER_OBJECT"
HAS_PLUG = "HAS_PLUG"
HAS_PAPER = "HAS_PAPER"
MOVABLE = "MOVABLE"
CREAM = "CREAM"

PROPERTIES: frozenset[str] = frozenset(
    {SURFACES, GRABBABLE, SITTABLE, LIEABLE, HANGABLE, DRINKABLE, EATABLE, RECIPIENT,
     CUTTABLE, POURABLE, CAN_OPEN, HAS_SWITCH, READABLE, LOOKABLE, CONTAINERS, CLOTHES,
     PERSON, BODY_PART, COVER_OBJECT, HAS_PLUG, HAS_PAPER, MOVABLE, CREAM}
)

ROOM_CATEGORY = "Rooms"
ROOM_NAMES = frozenset({
    "bathroom", "bedroom", "kitchen", "livingroom", "living_room", "dining_room",
    "home_office", "office", "garage", "hallway", "entrance_hall", "kids_bedroom"})
"""Room classes of VirtualHome programs and homes: a home lacking one cannot get it."""
CHARACTER_CLASS = "character"
