"""Preconditions and effects of every action: one registered function per catalog row.

An effect function takes the state and the node ids of the step's objects. It first
checks every precondition and returns a `Failure` (its kind, and the reason as a short
English sentence) if one fails, leaving the state untouched; otherwise it applies the
effect and returns None. What the object cannot do (affordance) is checked before where
the character is, so the kind says what is wrong with the step wherever it runs.

The rules follow the VirtualHome reference simulator (PyPI ``virtualhome==2.3.0``) and the
graphs stored with the real programs; docs/simulator.md lists where and why they differ.
"""

from __future__ import annotations

from collections.abc import Callable

from homesim.sim.failure import Failure, FailureKind
from homesim.sim.state import SimState
from homesim.world.vocab import (
    BODY_PART,
    CAN_OPEN,
    CLOSE,
    CLOTHES,
    CUTTABLE,
    DRINKABLE,
    EATABLE,
    FACING,
    GRABBABLE,
    HAS_PLUG,
    HAS_SWITCH,
    HOLDS_LH,
    HOLDS_RH,
    INSIDE,
    LIEABLE,
    LOOKABLE,
    MOVABLE,
    ON,
    PERSON,
    POURABLE,
    READABLE,
    RECIPIENT,
    S_CLEAN,
    S_CLOSED,
    S_DIRTY,
    S_LYING,
    S_OFF,
    S_ON,
    S_OPEN,
    S_PLUGGED_IN,
    S_PLUGGED_OUT,
    S_SITTING,
    SITTABLE,
    SURFACES,
)

AFFORDANCE, ALREADY = FailureKind.AFFORDANCE, FailureKind.ALREADY
ENCLOSED, HANDS_FULL = FailureKind.ENCLOSED, FailureKind.HANDS_FULL
NOT_FACING, NOT_HELD = FailureKind.NOT_FACING, FailureKind.NOT_HELD
POSTURE, STATE, UNREACHABLE = FailureKind.POSTURE, FailureKind.STATE, FailureKind.UNREACHABLE

Effect = Callable[..., Failure | None]
EFFECTS: dict[str, Effect] = {}
"""Action key -> effect function; every catalog action has one."""


def effect(*keys: str) -> Callable[[Effect], Effect]:
    """Register a function as the effect of the given action keys."""

    def register(fn: Effect) -> Effect:
        for key in keys:
            EFFECTS[key] = fn
        return fn

    return register


# ----------------------------------------------------------------------- helpers
_SIT_CAPACITY = {"couch": 4, "bed": 4, "chair": 1, "loveseat": 2, "sofa": 4, "toilet": 1,
                 "pianobench": 2, "bench": 2}
_LIE_CAPACITY = {"couch": 2, "bathtub": 2, "bed": 3, "loveseat": 2, "sofa": 2, "bench": 1}
_SQUEEZABLE = frozenset({"cleaning_solution", "tooth_paste", "shampoo", "food_peanut_butter",
                         "dish_soap", "soap", "towel", "rag", "paper", "sponge", "food_lemon",
                         "check"})
_POUR_INTO = frozenset({"hands_both", "sponge", "face"})
GRABBED_ANYWAY = frozenset({"water", "child"})
"""Classes a hand takes though not GRABBABLE (as the reference simulator lets it)."""
_WALK_CLEARS = (INSIDE, CLOSE, FACING)
NOWHERE: tuple[int, str] = (-1, "")
"""The remembered origin of an object grabbed while resting on nothing."""


def is_close(st: SimState, n: int) -> bool:
    """The character is close to `n`, directly or through something it is close to.

    The loose rule of the reference: close to `x` where `x` is close to `n` or `n` is on `x`.
    """
    close = st.targets(st.char, CLOSE)
    if n in close or not close:
        return n in close
    return not close.isdisjoint(st.sources(n, CLOSE)) or not close.isdisjoint(st.targets(n, ON))


def is_facing(st: SimState, n: int) -> bool:
    """The character faces `n`, or faces something that faces `n`."""
    facing = st.targets(st.char, FACING)
    return n in facing or not facing.isdisjoint(st.sources(n, FACING))


def closed_container(st: SimState, n: int) -> int | None:
    """A closed non-room container `n` is inside of, if any."""
    for x in st.targets(n, INSIDE):
        if x not in st.rooms and S_CLOSED in st.states(x):
            return x
    return None


def free_hand(st: SimState) -> str | None:
    if not st.targets(st.char, HOLDS_RH):
        return HOLDS_RH
    if not st.targets(st.char, HOLDS_LH):
        return HOLDS_LH
    return None


def holding_hand(st: SimState, n: int) -> str | None:
    if n in st.targets(st.char, HOLDS_RH):
        return HOLDS_RH
    if n in st.targets(st.char, HOLDS_LH):
        return HOLDS_LH
    return None


def held(st: SimState) -> list[int]:
    return [*st.targets(st.char, HOLDS_RH), *st.targets(st.char, HOLDS_LH)]


def _not_close(st: SimState, n: int, why: str = "") -> Failure:
    return Failure(UNREACHABLE, f"the character is not close to {st.label(n)}{why}")


def _no_free_hand(st: SimState) -> Failure:
    names = ", ".join(st.label(h) for h in held(st))
    return Failure(HANDS_FULL, f"the character has no free hand (it holds {names})")


def _posture(st: SimState) -> str | None:
    states = st.states(st.char)
    if S_SITTING in states:
        return "sitting"
    if S_LYING in states:
        return "lying"
    return None


def _inside_closed(st: SimState, n: int) -> Failure | None:
    box = closed_container(st, n)
    if box is None:
        return None
    return Failure(ENCLOSED, f"{st.label(n)} is inside closed {st.label(box)}")


# ----------------------------------------------------------------------- movement
@effect("WALK", "RUN")
def walk(st: SimState, n: int) -> Failure | None:
    c = st.char
    char_states = st.states(c)
    if S_SITTING in char_states or S_LYING in char_states:
        return Failure(POSTURE, f"the character is {_posture(st)}; it must stand up first")
    room = st.room_of(n)
    if room is None:
        return Failure(UNREACHABLE, f"{st.label(n)} is not in any room")
    char_room = st.room_of(c)
    if char_room is None:
        return Failure(UNREACHABLE, "the character is not in any room")
    right, left = st.targets(c, HOLDS_RH), st.targets(c, HOLDS_LH)
    in_hands = [*right, *left] if right or left else ()
    st.detach(c, _WALK_CLEARS)
    st.add_edge(c, INSIDE, room)
    # Close to the target, to what contains it and to the body parts (also for a room).
    rooms = st.rooms
    for x in st.targets(n, INSIDE):
        if x not in rooms:
            st.add_pair(c, CLOSE, x)
    for x in st.body_parts:
        st.add_pair(c, CLOSE, x)
    st.add_pair(c, CLOSE, n)
    # Held objects come along; they stay INSIDE the room the walk started from (as in
    # the stored graphs of the real programs).
    for h in in_hands:
        st.detach(h, _WALK_CLEARS)
    for h in in_hands:
        st.add_pair(c, CLOSE, h)
        st.add_edge(h, INSIDE, char_room)
    if SURFACES in st.properties(n):
        for x in tuple(st.sources(n, ON)):
            st.add_pair(c, CLOSE, x)
    return None


@effect("FIND")
def find(st: SimState, n: int) -> Failure | None:
    c = st.char
    if not (c in st.targets(n, ON) or BODY_PART in st.properties(n) or is_close(st, n)
            or _posture(st)):
        return walk(st, n)
    if not is_close(st, n):
        posture = _posture(st)
        why = f" (the character is {posture})" if posture else ""
        return _not_close(st, n, why)
    for x in tuple(st.targets(c, FACING)):
        st.remove_edge(c, FACING, x)
    st.add_pair(c, CLOSE, n)
    return None


@effect("TURNTO")
def turn_to(st: SimState, n: int) -> Failure | None:
    c = st.char
    for x in tuple(st.targets(c, FACING)):
        st.remove_edge(c, FACING, x)
    if n != c:
        st.add_edge(c, FACING, n)
    return None


# ----------------------------------------------------------------------- attention
@effect("LOOKAT", "POINTAT")
def look_at(st: SimState, n: int) -> Failure | None:
    if not is_facing(st, n):
        return Failure(NOT_FACING, f"the character does not face {st.label(n)}")
    return None


@effect("WATCH")
def watch(st: SimState, n: int) -> Failure | None:
    if LOOKABLE not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be watched (not LOOKABLE)")
    room, char_room = st.room_of(n), st.room_of(st.char)
    if room is None:
        return Failure(UNREACHABLE, f"{st.label(n)} is not in any room")
    if room != char_room:
        where = "no room" if char_room is None else st.label(char_room)
        return Failure(UNREACHABLE,
                       f"{st.label(n)} is in {st.label(room)}, the character is in {where}")
    if not is_facing(st, n):
        return Failure(NOT_FACING, f"the character does not face {st.label(n)}")
    posture = _posture(st)
    if (posture and st.class_name(n) != "computer"
            and n not in st.targets(st.char, FACING)):
        return Failure(NOT_FACING, f"the character is {posture} and not facing {st.label(n)}")
    return _inside_closed(st, n)


@effect("READ")
def read(st: SimState, n: int) -> Failure | None:
    if READABLE not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be read (not READABLE)")
    if holding_hand(st, n) is None:
        return Failure(NOT_HELD, f"the character is not holding {st.label(n)}")
    return None


@effect("GREET")
def greet(st: SimState, n: int) -> Failure | None:
    if PERSON not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} is not a person")
    return None


# ----------------------------------------------------------------------- hands
def _origin(st: SimState, n: int) -> tuple[int, str]:
    """Where `n` rests now, for PutObjBack: the first non-room, non-character node it is
    ON, INSIDE or CLOSE to (lowest id first), or (-1, "") if it rests on nothing."""
    for r in (ON, INSIDE, CLOSE):
        candidates = [x for x in st.targets(n, r) if x not in st.rooms and x != st.char]
        if candidates:
            return (min(candidates), r)
    return NOWHERE


def can_grab(properties: frozenset[str], class_name: str) -> bool:
    """Whether a hand may take an object: GRABBABLE, or of a class in `GRABBED_ANYWAY`."""
    return GRABBABLE in properties or class_name in GRABBED_ANYWAY


@effect("GRAB")
def grab(st: SimState, n: int) -> Failure | None:
    c = st.char
    if not can_grab(st.properties(n), st.class_name(n)):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be grabbed (not GRABBABLE)")
    if not is_close(st, n):
        return _inside_closed(st, n) or _not_close(st, n)
    holding = holding_hand(st, n)
    if holding is not None:
        # Grabbing what one hand holds takes it in both hands (as the stored graphs show).
        other = HOLDS_LH if holding == HOLDS_RH else HOLDS_RH
        if st.targets(c, other):
            return _no_free_hand(st)
        st.add_edge(c, other, n)
        return None
    why = _inside_closed(st, n)
    if why:
        return why
    hand = free_hand(st)
    if hand is None:
        return _no_free_hand(st)
    char_room = st.room_of(c)
    if char_room is None:
        return Failure(UNREACHABLE, "the character is not in any room")
    origin = _origin(st, n)
    st.detach(n, (ON, INSIDE, CLOSE, HOLDS_LH, HOLDS_RH))
    st.add_pair(c, CLOSE, n)
    st.add_edge(c, hand, n)
    st.add_edge(n, INSIDE, char_room)
    if origin is not NOWHERE:
        st.add_pair(c, CLOSE, origin[0])
    st.remember(n, origin)
    return None


def _release(st: SimState, n: int) -> None:
    st.remove_edge(st.char, HOLDS_RH, n)
    st.remove_edge(st.char, HOLDS_LH, n)


@effect("DROP", "RELEASE")
def drop(st: SimState, n: int) -> Failure | None:
    if holding_hand(st, n) is None:
        return Failure(NOT_HELD, f"the character is not holding {st.label(n)}")
    room = st.room_of(st.char)
    if room is None:
        return Failure(UNREACHABLE, "the character is not in any room")
    _release(st, n)
    st.add_edge(n, INSIDE, room)
    st.remember(n, None)
    return None


@effect("TOUCH")
def touch(st: SimState, n: int) -> Failure | None:
    if not is_close(st, n):
        return _not_close(st, n)
    return _inside_closed(st, n)


def _move(st: SimState, n: int, pushing: bool) -> Failure | None:
    # As in the reference, anything can be pushed; pulling needs something movable.
    movable = (pushing or MOVABLE in st.properties(n)
               or st.class_name(n) in ("chair", "curtain", "button"))
    if not movable:
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be moved (not MOVABLE)")
    if not is_close(st, n):
        return _not_close(st, n)
    why = _inside_closed(st, n)
    if why:
        return why
    if free_hand(st) is None:
        return _no_free_hand(st)
    return None


@effect("PUSH")
def push(st: SimState, n: int) -> Failure | None:
    return _move(st, n, pushing=True)


@effect("PULL", "MOVE")
def pull(st: SimState, n: int) -> Failure | None:
    return _move(st, n, pushing=False)


@effect("SQUEEZE")
def squeeze(st: SimState, n: int) -> Failure | None:
    if CLOTHES not in st.properties(n) and st.class_name(n) not in _SQUEEZABLE:
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be squeezed")
    if free_hand(st) is None:
        return _no_free_hand(st)
    if not is_close(st, n):
        return _not_close(st, n)
    return None


# ----------------------------------------------------------------------- placing
def _put(st: SimState, src: int, dest: int, relation: str) -> Failure | None:
    if src == dest:
        return Failure(AFFORDANCE, f"cannot put {st.label(src)} on or in itself")
    if holding_hand(st, src) is None:
        return Failure(NOT_HELD, f"the character is not holding {st.label(src)}")
    if not is_close(st, dest):
        return _not_close(st, dest)
    if (relation == INSIDE and CAN_OPEN in st.properties(dest)
            and S_OPEN not in st.states(dest)):
        return Failure(STATE, f"{st.label(dest)} is closed")
    _release(st, src)
    st.add_pair(st.char, CLOSE, dest)
    st.add_pair(src, CLOSE, dest)
    st.add_edge(src, relation, dest)
    st.remember(src, None)
    return None


@effect("PUTBACK")
def put_back(st: SimState, src: int, dest: int) -> Failure | None:
    return _put(st, src, dest, ON)


@effect("PUTIN")
def put_in(st: SimState, src: int, dest: int) -> Failure | None:
    return _put(st, src, dest, INSIDE)


@effect("PUTOBJBACK")
def put_obj_back(st: SimState, n: int) -> Failure | None:
    origin = st.memory.get(n)
    if origin is None:
        return Failure(NOT_HELD, f"{st.label(n)} was not grabbed, so it has no place to go back to")
    if origin is NOWHERE:
        # It rested on nothing but the floor of the room: let go of it where it is.
        if holding_hand(st, n) is None:
            return Failure(NOT_HELD, f"the character is not holding {st.label(n)}")
        _release(st, n)
        st.add_pair(n, CLOSE, st.char)
        st.remember(n, None)
        return None
    return _put(st, n, origin[0], origin[1])


@effect("POUR")
def pour(st: SimState, src: int, dest: int) -> Failure | None:
    if POURABLE not in st.properties(src) and DRINKABLE not in st.properties(src):
        return Failure(AFFORDANCE, f"{st.label(src)} cannot be poured (not POURABLE or DRINKABLE)")
    if RECIPIENT not in st.properties(dest) and st.class_name(dest) not in _POUR_INTO:
        return Failure(AFFORDANCE, f"{st.label(dest)} cannot receive a liquid (not RECIPIENT)")
    if holding_hand(st, src) is None:
        return Failure(NOT_HELD, f"the character is not holding {st.label(src)}")
    if not is_close(st, dest):
        return _not_close(st, dest)
    st.add_edge(src, INSIDE, dest)
    if st.class_name(src) == "water":
        _release(st, src)
    return None


# ----------------------------------------------------------------------- open / close
def _open_close(st: SimState, n: int, opening: bool) -> Failure | None:
    if CAN_OPEN not in st.properties(n) and st.class_name(n) not in ("desk", "window"):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be opened or closed (not CAN_OPEN)")
    if not is_close(st, n):
        return _not_close(st, n)
    if opening and free_hand(st) is None:
        return _no_free_hand(st)
    states = st.states(n)
    if opening:
        if S_CLOSED not in states:
            return Failure(ALREADY, f"{st.label(n)} is not closed")
        if S_ON in states:
            return Failure(STATE, f"{st.label(n)} is on; switch it off first")
        st.swap_state(n, S_CLOSED, S_OPEN)
    else:
        if S_OPEN not in states:
            return Failure(ALREADY, f"{st.label(n)} is not open")
        st.swap_state(n, S_OPEN, S_CLOSED)
    return None


@effect("OPEN")
def open_(st: SimState, n: int) -> Failure | None:
    return _open_close(st, n, opening=True)


@effect("CLOSE")
def close(st: SimState, n: int) -> Failure | None:
    return _open_close(st, n, opening=False)


# ----------------------------------------------------------------------- devices
def _switch(st: SimState, n: int, on: bool) -> Failure | None:
    if HAS_SWITCH not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} has no switch")
    if not is_close(st, n):
        return _not_close(st, n)
    states = st.states(n)
    if on:
        if S_OFF not in states:
            return Failure(ALREADY, f"{st.label(n)} is not off")
        if S_PLUGGED_OUT in states:
            return Failure(STATE, f"{st.label(n)} is unplugged")
        st.swap_state(n, S_OFF, S_ON)
    else:
        if S_ON not in states:
            return Failure(ALREADY, f"{st.label(n)} is not on")
        st.swap_state(n, S_ON, S_OFF)
    return None


@effect("SWITCHON")
def switch_on(st: SimState, n: int) -> Failure | None:
    return _switch(st, n, on=True)


@effect("SWITCHOFF")
def switch_off(st: SimState, n: int) -> Failure | None:
    return _switch(st, n, on=False)


def _plug(st: SimState, n: int, plug_in: bool) -> Failure | None:
    if HAS_PLUG not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} has no plug")
    if not is_close(st, n):
        return _not_close(st, n)
    if free_hand(st) is None:
        return _no_free_hand(st)
    states = st.states(n)
    if plug_in:
        if S_PLUGGED_OUT not in states:
            return Failure(ALREADY, f"{st.label(n)} is not unplugged")
        st.swap_state(n, S_PLUGGED_OUT, S_PLUGGED_IN)
    else:
        if S_PLUGGED_IN not in states:
            return Failure(ALREADY, f"{st.label(n)} is not plugged in")
        # Unplugging a device that is on is allowed and leaves it ON (as the stored
        # graphs of the real programs show).
        st.swap_state(n, S_PLUGGED_IN, S_PLUGGED_OUT)
    return None


@effect("PLUGIN")
def plug_in(st: SimState, n: int) -> Failure | None:
    return _plug(st, n, plug_in=True)


@effect("PLUGOUT")
def plug_out(st: SimState, n: int) -> Failure | None:
    return _plug(st, n, plug_in=False)


@effect("TYPE")
def type_(st: SimState, n: int) -> Failure | None:
    if st.class_name(n) != "keyboard" and HAS_SWITCH not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be typed on")
    if not is_close(st, n):
        return _not_close(st, n)
    return None


# ----------------------------------------------------------------------- body
@effect("SIT")
def sit(st: SimState, n: int) -> Failure | None:
    c = st.char
    if SITTABLE not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be sat on (not SITTABLE)")
    if not is_close(st, n):
        return _not_close(st, n)
    if S_SITTING in st.states(c):
        return Failure(ALREADY, "the character is already sitting")
    if len(st.sources(n, ON)) >= _SIT_CAPACITY.get(st.class_name(n), 1):
        return Failure(STATE, f"there is no room left on {st.label(n)}")
    st.add_edge(c, ON, n)
    for x in tuple(st.targets(n, FACING)):
        st.add_edge(c, FACING, x)
    st.set_states(c, (st.states(c) - {S_LYING}) | {S_SITTING})
    return None


@effect("LIE")
def lie(st: SimState, n: int) -> Failure | None:
    c = st.char
    if LIEABLE not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be lain on (not LIEABLE)")
    if not is_close(st, n):
        return _not_close(st, n)
    if S_LYING in st.states(c):
        return Failure(ALREADY, "the character is already lying")
    if len(st.sources(n, ON)) >= _LIE_CAPACITY.get(st.class_name(n), 1):
        return Failure(STATE, f"there is no room left on {st.label(n)}")
    st.add_edge(c, ON, n)
    st.set_states(c, (st.states(c) - {S_SITTING}) | {S_LYING})
    return None


@effect("STANDUP")
def stand_up(st: SimState) -> Failure | None:
    c = st.char
    states = st.states(c)
    if S_SITTING not in states and S_LYING not in states:
        return Failure(ALREADY, "the character is not sitting or lying")
    st.set_states(c, states - {S_SITTING, S_LYING})
    return None


@effect("SLEEP", "WAKEUP")
def sleep(st: SimState) -> Failure | None:
    if _posture(st) is None:
        return Failure(POSTURE, "the character is not lying or sitting")
    return None


@effect("PUTON")
def put_on(st: SimState, n: int) -> Failure | None:
    if CLOTHES not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} is not clothes")
    if holding_hand(st, n) is None:
        return Failure(NOT_HELD, f"the character is not holding {st.label(n)}")
    st.add_edge(n, ON, st.char)
    _release(st, n)
    return None


@effect("PUTOFF")
def put_off(st: SimState, n: int) -> Failure | None:
    if CLOTHES not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} is not clothes")
    if st.char not in st.targets(n, ON):
        return Failure(STATE, f"the character is not wearing {st.label(n)}")
    st.remove_edge(n, ON, st.char)
    return None


# ----------------------------------------------------------------------- cleaning
@effect("WIPE")
def wipe(st: SimState, n: int) -> Failure | None:
    if not is_close(st, n):
        return _not_close(st, n)
    if not held(st):
        return Failure(NOT_HELD, "the character holds nothing to wipe with")
    st.set_states(n, (st.states(n) - {S_DIRTY}) | {S_CLEAN})
    return None


@effect("WASH", "RINSE", "SCRUB")
def wash(st: SimState, n: int) -> Failure | None:
    if n in st.rooms:
        return Failure(AFFORDANCE, f"{st.label(n)} is a room; it cannot be washed")
    if not is_close(st, n):
        return _not_close(st, n)
    st.set_states(n, (st.states(n) - {S_DIRTY}) | {S_CLEAN})
    return None


# ----------------------------------------------------------------------- eating
@effect("EAT")
def eat(st: SimState, n: int) -> Failure | None:
    if EATABLE not in st.properties(n) and not any(EATABLE in st.properties(x)
                                                   for x in st.sources(n, ON)):
        return Failure(AFFORDANCE, f"{st.label(n)} is not food and has no food on it")
    if not is_close(st, n):
        return _not_close(st, n)
    return None


@effect("DRINK")
def drink(st: SimState, n: int) -> Failure | None:
    if DRINKABLE not in st.properties(n) and RECIPIENT not in st.properties(n):
        return Failure(AFFORDANCE,
                       f"{st.label(n)} cannot be drunk from (not DRINKABLE or RECIPIENT)")
    if holding_hand(st, n) is None:
        return Failure(NOT_HELD, f"the character is not holding {st.label(n)}")
    return None


@effect("CUT")
def cut(st: SimState, n: int) -> Failure | None:
    if EATABLE not in st.properties(n) or CUTTABLE not in st.properties(n):
        return Failure(AFFORDANCE, f"{st.label(n)} cannot be cut (not EATABLE and CUTTABLE)")
    if free_hand(st) is None:
        return _no_free_hand(st)
    if not is_close(st, n):
        return _not_close(st, n)
    if not any("knife" in st.class_name(h) for h in held(st)):
        return Failure(NOT_HELD, "the character is not holding a knife")
    return None
