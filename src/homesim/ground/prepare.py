"""Scene preparation: make a home ready for a program before grounding it.

Two things are prepared, on a copy of the home (the input graph is never changed):

1. **Missing objects.** A program names objects by class and a per-program instance
   number. When it uses more instances of a class than the home has (counting the
   class's equivalent names), the missing ones are added at a destination the placement
   knowledge base allows for the class (``cup``: ON a table, INSIDE a cupboard, ...).
   Destinations are preferred in this order: not hidden inside a closed container the
   program has not opened by the time it needs the object; near its anchor (where the
   program needs it, see `_Context`); one the program uses before it needs the object (it walks
   to the counter, then grabs the cup); one in a room the program names; ties are broken
   by the seed. A class the knowledge base has no destination for (appliances, lamps,
   body parts) is stood on the floor of a room the program names (else of a room drawn
   by the seed). With geometry, the new object gets a box sized from its prefab, set on
   (or in) the destination, or on free floor, clear of what is already there.
2. **Initial states.** The states the program's first steps on an object presuppose:
   an object it switches on starts OFF (and plugged in), one it opens starts CLOSED, one
   it unplugs starts PLUGGED_IN, and so on; a program that begins by standing up starts
   with the character sitting. These are set on every instance of the object's classes,
   since grounding has not chosen one yet.

>>> from homesim.program import parse_program
>>> from homesim.world import load_home
>>> p = parse_program("[Walk] <dining_room> (1)\\n[Find] <wine_glass> (1)\\n"
...                   "[Grab] <wine_glass> (1)")
>>> prep = prepare(p, load_home("scene1_trimmed"), seed=0)
>>> [(a.class_name, a.relation) for a in prep.added]
[('wine_glass', 'ON')]
"""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from functools import lru_cache
from typing import Any

from homesim.errors import GroundingError
from homesim.ground.kbtypes import ObjectKnowledge, class_names_for, default_kb
from homesim.ground.placement import place_box
from homesim.ground.standing import FloorPlan, has_geometry, note_prepared
from homesim.program.model import ObjectRef, Program
from homesim.sim.state import SimState
from homesim.world.graph import BoundingBox, EnvironmentGraph, Node
from homesim.world.vocab import (
    CHARACTER_CLASS,
    CLOSE,
    CONTAINERS,
    GRABBABLE,
    HAS_PLUG,
    HAS_SWITCH,
    INSIDE,
    ON,
    S_CLOSED,
    S_LYING,
    S_OFF,
    S_ON,
    S_OPEN,
    S_PLUGGED_IN,
    S_PLUGGED_OUT,
    S_SITTING,
    SURFACES,
)

ROOM_NAMES = frozenset({
    "bathroom", "bedroom", "kitchen", "livingroom", "living_room", "dining_room",
    "home_office", "office", "garage", "hallway", "entrance_hall", "kids_bedroom"})
"""Room classes of VirtualHome programs and homes: a home lacking one cannot get it."""
DEFAULT_SIZE = (0.15, 0.15, 0.15)
"""Box size (m) for an added object whose class has no prefab dimensions."""

# Action key -> (state group, the state the object must be in before the step).
_PRESUPPOSES: dict[str, tuple[str, str]] = {
    "SWITCHON": ("switch", S_OFF), "SWITCHOFF": ("switch", S_ON),
    "OPEN": ("door", S_CLOSED), "CLOSE": ("door", S_OPEN),
    "PLUGIN": ("plug", S_PLUGGED_OUT), "PLUGOUT": ("plug", S_PLUGGED_IN),
}
_GROUPS = {"switch": (S_ON, S_OFF), "door": (S_OPEN, S_CLOSED),
           "plug": (S_PLUGGED_IN, S_PLUGGED_OUT)}
# Character posture before a step that needs one: (state, set when first seen).
_POSTURE_NEEDED = {"STANDUP": S_SITTING, "WAKEUP": S_LYING, "SLEEP": S_LYING}
_POSTURE_SET = frozenset({"SIT", "LIE", "WALK", "RUN"})
# (action key, argument position) -> properties of which the object needs one. Mirrors the
# property checks of homesim.sim.effects, which has a few exceptions by class name (water
# can be grabbed, a desk opened): grounding only orders candidates by it (those lacking a
# needed property last) and never rejects one; the simulator stays the judge.
NEEDS: dict[tuple[str, int], frozenset[str]] = {
    (k, i): frozenset(v.split()) for k, i, v in (
        ("GRAB", 0, "GRABBABLE"), ("SWITCHON", 0, "HAS_SWITCH"), ("SWITCHOFF", 0, "HAS_SWITCH"),
        ("SIT", 0, "SITTABLE"), ("LIE", 0, "LIEABLE"), ("OPEN", 0, "CAN_OPEN"),
        ("CLOSE", 0, "CAN_OPEN"), ("WATCH", 0, "LOOKABLE"), ("READ", 0, "READABLE"),
        ("PLUGIN", 0, "HAS_PLUG"), ("PLUGOUT", 0, "HAS_PLUG"), ("PUTON", 0, "CLOTHES"),
        ("PUTOFF", 0, "CLOTHES"), ("DRINK", 0, "DRINKABLE RECIPIENT"),
        ("POUR", 0, "POURABLE DRINKABLE"), ("POUR", 1, "RECIPIENT"), ("GREET", 0, "PERSON"),
        ("CUT", 0, "CUTTABLE"), ("PUTBACK", 0, "GRABBABLE"), ("PUTIN", 0, "GRABBABLE"))}


_LOOKING = frozenset({"WALK", "RUN", "FIND", "TURNTO", "LOOKAT", "POINTAT", "WATCH"})
MOVES = frozenset({"WALK", "RUN", "FIND"})
"""Steps that take the agent to their object."""
NEEDS_REACH = frozenset({
    "GRAB", "TOUCH", "OPEN", "CLOSE", "SWITCHON", "SWITCHOFF", "PLUGIN", "PLUGOUT", "PUSH",
    "PULL", "MOVE", "SQUEEZE", "PUTBACK", "PUTIN", "POUR", "TYPE", "SIT", "LIE", "WIPE",
    "WASH", "RINSE", "SCRUB", "EAT", "CUT"})
"""Steps whose (last) object must be within the agent's reach."""


@dataclass(frozen=True, slots=True)
class Addition:
    """One object added by `prepare`.

    Attributes:
        node_id: id of the new node.
        class_name: its class (the program's name for it).
        destination_id: the node it was put on or in (the room itself for the floor).
        relation: ``ON`` or ``INSIDE``.
        room: id of the room it is in.
    """

    node_id: int
    class_name: str
    destination_id: int
    relation: str
    room: int


@dataclass(eq=False)
class Prepared:
    """The result of `prepare`.

    Attributes:
        graph: the prepared home (the input graph itself when nothing changed).
        added: the objects added, in order.
        states: (node id, states before, states after) for each existing node whose
            initial states were set for the program.
    """

    graph: EnvironmentGraph
    added: list[Addition]
    states: list[tuple[int, frozenset[str], frozenset[str]]] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """JSON view: additions (as `Addition` fields) and states {node, before, after}."""
        return {"added": [asdict(a) for a in self.added],
                "states": [{"node": n, "before": sorted(a), "after": sorted(b)}
                           for n, a, b in self.states]}


def first_use(program: Program, key: tuple[str, int]) -> tuple[int, str]:
    """The 1-based number and text of the first step that names the object `key`."""
    for i, step in enumerate(program.steps):
        if any(ref.key == key for ref in step.args):
            return i + 1, str(step)
    return 0, ""


def instances_of(graph: EnvironmentGraph, classes: list[str]) -> list[int]:
    """Ids of the home's nodes of any of `classes` (never the acting character)."""
    ids: list[int] = []
    for c in classes:
        ids.extend(n.id for n in graph.nodes_of_class(c) if n.id != graph.character_id)
    return ids


def prepare(program: Program, graph: EnvironmentGraph, seed: int = 0,
            kb: ObjectKnowledge | None = None,
            extra: Sequence[tuple[str, int]] = (),
            pins: Mapping[tuple[str, int], int] | None = None) -> Prepared:
    """Add the objects `program` needs and set the initial states it presupposes.

    Args:
        program: the program (grounded or not; only class names and instances matter).
        graph: the home; never modified.
        seed: breaks ties between equally good destinations and picks spots on them.
        kb: the object knowledge base (default: `homesim.knowledge.load_kb()`).
        extra: program objects (class name, instance) to add a new instance for even
            when the home has enough (grounding asks for these when the home's
            instances are all out of reach; see `prepare_and_ground`).
        pins: program object -> node of the home, for objects whose instance is known
            (from a failed grounding): what is added near one goes next to that node.

    Returns:
        `Prepared`: the new graph, the additions and the state changes.

    Raises:
        GroundingError: an object is missing and cannot be added (a room, the character,
            or no destination and no free floor for it).
    """
    kb = kb or default_kb()
    rng = random.Random(seed)
    context = _Context(program, graph, kb)
    missing = context.missing + [ref for refs in context.refs_by_name.values() for ref in refs
                                 if ref.key in extra and ref not in context.missing]
    context.find_anchors({ref.key for ref in missing})
    missing = _anchors_first(missing, context)
    required, posture = _presupposed(program)
    states = _initial_states(graph, context, required, posture)
    if not missing and not states:
        return Prepared(graph, [])
    st = SimState(graph)
    changed = []
    for node_id, new in states.items():
        old = st.states(node_id)
        if new != old:
            st.set_states(node_id, new)
            changed.append((node_id, old, new))
    plan = FloorPlan(graph) if has_geometry(graph) else None
    added: list[Addition] = []
    by_key: dict[Key, int] = {}
    for ref in missing:
        addition = _add(st, ref, program, context, kb, rng, plan, added, by_key, pins or {})
        added.append(addition)
        by_key[ref.key] = addition.node_id
        groups = required.get(_first_of_class(required, ref.name), {})
        node = st.node(addition.node_id)
        new = _apply(node.states, node.properties, groups)
        if new != node.states:
            st.set_states(addition.node_id, new)
    prepared = st.to_graph()
    if plan is not None:
        # Let standing spots of the prepared home reuse those of this one (see FloorPlan).
        floor_rooms = frozenset(a.room for a in added if a.destination_id == a.room)
        note_prepared(prepared, graph, floor_rooms)
    return Prepared(prepared, added, changed)


Key = tuple[str, int]


class _Context:
    """What the program uses and where it needs each object to be.

    Anchors: the program moves the agent to objects and acts on objects within reach,
    so it implies which objects start near which. The context follows where each object
    is (near the object it was put on or in, or where it started) and where the agent is;
    when a step needs an object within reach and the agent is elsewhere, an object still
    to be added is anchored to the other place (walk to the freezer, find the food, open
    the freezer: the food starts near the freezer).
    """

    def __init__(self, program: Program, graph: EnvironmentGraph, kb: ObjectKnowledge):
        self.refs_by_name: dict[str, list[ObjectRef]] = {}
        self.names: dict[str, list[str]] = {}
        for ref in program.object_refs():
            self.refs_by_name.setdefault(ref.name, []).append(ref)
            if ref.name not in self.names:
                self.names[ref.name] = class_names_for(ref.name, kb)
        classes = {c for names in self.names.values() for c in names}
        self.classes = classes
        self.rooms = [r.id for r in graph.rooms() if r.class_name in classes]
        needs: dict[str, set[frozenset[str]]] = {}
        for step in program.steps:
            for pos, ref in enumerate(step.args):
                need = NEEDS.get((step.action.key, pos))
                if need is not None:
                    needs.setdefault(ref.name, set()).add(need)
        # Objects on a seat take its place (the simulator counts them), so nothing is put
        # on what the program sits or lies on.
        self.seats = {c for step in program.steps if step.action.key in ("SIT", "LIE")
                      for ref in step.args for c in self.names[ref.name]}
        # Clothes the program takes off before doing anything else with them (but walk
        # to them, look at them) are worn.
        self.worn: set[Key] = set()
        seen: set[Key] = set()
        for step in program.steps:
            if step.action.key in _LOOKING:
                continue
            for ref in step.args:
                if ref.key not in seen and step.action.key == "PUTOFF":
                    self.worn.add(ref.key)
                seen.add(ref.key)
        self.missing: list[ObjectRef] = []
        for name, refs in self.refs_by_name.items():
            ids = instances_of(graph, self.names[name])
            wanted = needs.get(name, set())
            if wanted and not any(all(not graph.nodes[i].properties.isdisjoint(w)
                                      for w in wanted) for i in ids):
                ids = []  # none can do what the program does with it (folded clothes)
            self.missing += [r for r in refs[len(ids):] if r.key not in self.worn]
        # A fresh instance of each, worn by the character (none of the home's is worn).
        self.missing += [r for refs in self.refs_by_name.values() for r in refs
                         if r.key in self.worn]
        room_classes = {r.class_name for r in graph.rooms()}
        self.is_room = {n: bool(room_classes.intersection(c)) for n, c in self.names.items()}
        self.used_before: dict[Key, set[str]] = {}
        self.opened_before: dict[Key, set[str]] = {}
        self.anchor: dict[Key, Key] = {}
        self.room_before: dict[Key, list[str]] = {}
        self._program = program

    def find_anchors(self, free: set[Key]) -> None:
        """Anchor each object of `free` (to be added) where the program needs it.

        Places are the starting places of the program's objects; `parent` joins a place
        to the place it must be near. An object is at its starting place until the
        program puts it somewhere else."""
        parent: dict[Key, Key] = {}
        pos: dict[Key, Key] = {}  # object -> the starting place it is at now
        held: set[Key] = set()
        first_at: dict[Key, Key] = {}
        used: set[str] = set()
        opened: set[str] = set()
        agent: Key | None = None  # the place the agent is at
        sitting = False  # a seated agent's Find does not walk: it needs reach
        room: list[str] = []  # classes of the room the agent last walked into

        def place(k: Key) -> Key:
            p = pos.get(k, k)
            while p in parent:
                p = parent[p]
            return p

        for step in self._program.steps:
            key = step.action.key
            for ref in step.args:
                self.used_before.setdefault(ref.key, set(used))
                self.opened_before.setdefault(ref.key, set(opened))
                self.room_before.setdefault(ref.key, room)
                if agent is not None and agent != ref.key:
                    first_at.setdefault(ref.key, agent)
            reach = key in NEEDS_REACH or (key == "FIND" and sitting)
            if key in ("SIT", "LIE"):
                sitting = True
            elif key in ("STANDUP", "WALK", "RUN"):
                sitting = False
            if key in MOVES and step.args and not reach:
                ref = step.args[0]
                if self.is_room[ref.name]:
                    agent, room = None, self.names[ref.name]
                elif ref.key not in held:
                    agent = place(ref.key)
            if reach and step.args and agent is not None:
                target = step.args[-1]
                if target.key not in held and not self.is_room[target.name]:
                    there = place(target.key)
                    if there != agent:
                        # Only a starting place of an object still to be added can move.
                        # Prefer moving the place the agent went to (the detergent it
                        # walked to goes near the washing machine it pours into).
                        if agent in free and agent not in self.anchor:
                            self.anchor[agent] = parent[agent] = there
                            agent = there
                        elif there in free and there not in self.anchor:
                            self.anchor[there] = parent[there] = agent
            for ref in step.args:
                used.update(self.names[ref.name])
                if key == "OPEN":
                    opened.update(self.names[ref.name])
                elif key == "CLOSE":  # open when the object is needed, not just once
                    opened.difference_update(self.names[ref.name])
            if key == "GRAB" and step.args:
                if step.args[0].key not in pos:
                    pos[step.args[0].key] = place(step.args[0].key)
                held.add(step.args[0].key)
            elif key in ("PUTBACK", "PUTIN") and len(step.args) == 2:
                held.discard(step.args[0].key)
                pos[step.args[0].key] = place(step.args[1].key)
            elif key in ("DROP", "RELEASE", "PUTOBJBACK") and step.args:
                held.discard(step.args[0].key)
                if agent is not None:
                    pos[step.args[0].key] = agent
        # Otherwise: near what the agent was at when the program first names it.
        for k, at in first_at.items():
            if k in free and k not in self.anchor and k not in parent:
                p = at
                while p in parent:
                    p = parent[p]
                if p != k:
                    self.anchor[k] = p


def _presupposed(program: Program) -> tuple[dict[Key, dict[str, str]], str | None]:
    """Per program object, the state of each group (switch, door, plug) its first steps
    presuppose; and the posture the character must start in, if any."""
    required: dict[Key, dict[str, str]] = {}
    posture: str | None = None
    posture_known = False
    for step in program.steps:
        key = step.action.key
        if not posture_known:
            if key in _POSTURE_NEEDED:
                posture, posture_known = _POSTURE_NEEDED[key], True
            elif key in _POSTURE_SET:
                posture_known = True
        rule = _PRESUPPOSES.get(key)
        if rule is None or not step.args:
            continue
        groups = required.setdefault(step.args[0].key, {})
        group, state = rule
        groups.setdefault(group, state)
        # Switching on needs power, opening needs the device off: presuppose those too
        # unless an earlier step already settled them.
        if key == "SWITCHON":
            groups.setdefault("plug?", S_PLUGGED_IN)
        if key == "OPEN":
            groups.setdefault("switch?", S_OFF)
    return required, posture


def _first_of_class(required: dict[Key, dict[str, str]], name: str) -> Key | None:
    return next((k for k in required if k[0] == name), None)


def _apply(states: frozenset[str], properties: frozenset[str],
           groups: dict[str, str]) -> frozenset[str]:
    out = set(states)
    for group, state in groups.items():
        if group == "plug?":
            if HAS_PLUG not in properties or "plug" in groups:
                continue
            group = "plug"
        elif group == "switch?":
            if HAS_SWITCH not in properties or "switch" in groups:
                continue
            group = "switch"
        out.difference_update(_GROUPS[group])
        out.add(state)
    return frozenset(out)


def _initial_states(graph: EnvironmentGraph, context: _Context,
                    required: dict[Key, dict[str, str]],
                    posture: str | None) -> dict[int, frozenset[str]]:
    """Node id -> the states the program presupposes for it (only nodes that change).

    Set on every instance of the object's classes; when one class has several program
    objects, the first one decides."""
    out: dict[int, frozenset[str]] = {}
    done: set[str] = set()
    for (name, _), groups in required.items():
        if name in done:
            continue
        done.add(name)
        for node_id in instances_of(graph, context.names[name]):
            node = graph.nodes[node_id]
            new = _apply(out.get(node_id, node.states), node.properties, groups)
            if new != node.states:
                out[node_id] = new
    char = graph.character_id
    if posture is not None and char is not None:
        states = graph.nodes[char].states
        if posture not in states:
            out[char] = (states - {S_SITTING, S_LYING}) | {posture}
    return out


def _anchors_first(refs: list[ObjectRef], context: _Context) -> list[ObjectRef]:
    """Order the objects to add so that an object's anchor is added before it."""
    pending = list(refs)
    ordered: list[ObjectRef] = []
    while pending:
        keys = {r.key for r in pending}
        ready = next((r for r in pending if context.anchor.get(r.key) not in keys), pending[0])
        pending.remove(ready)
        ordered.append(ready)
    return ordered


def _instances(st: SimState, classes: list[str], added: list[Addition]) -> list[int]:
    """Instances of `classes` in the home, including the objects added so far."""
    ids = instances_of(st.graph, classes)
    ids += [a.node_id for a in added if a.class_name in classes]
    return ids


def _add(st: SimState, ref: ObjectRef, program: Program, context: _Context,
         kb: ObjectKnowledge, rng: random.Random, plan: FloorPlan | None,
         added: list[Addition], by_key: dict[Key, int], pins: Mapping[Key, int]) -> Addition:
    graph = st.graph
    name = ref.name
    step_no, step_text = first_use(program, ref.key)
    where = f"step {step_no} {step_text}: " if step_no else ""
    names = context.names[name]
    lacks = (f"the home has {'too few' if _instances(st, names, added) else 'no'} "
             f"{' or '.join(names)} for <{name}> ({ref.instance})")
    if (name == CHARACTER_CLASS or ROOM_NAMES.intersection(names)
            or any(n.is_room for c in names for n in graph.nodes_of_class(c))):
        raise GroundingError(f"{where}{lacks}; rooms and characters cannot be added",
                             step_no, str(ref), "rooms")
    if not any(kb.properties(c) or kb.placements(c) or kb.prefab_size(c) for c in names):
        raise GroundingError(f"{where}{lacks}, and the knowledge base does not know "
                             f"{name!r}, so none can be added", step_no, str(ref), "")
    placements = []
    for c in names:
        placements = list(kb.placements(c))
        if placements:
            break
    used = context.used_before.get(ref.key, set())
    opened = context.opened_before.get(ref.key, set())
    # Where the agent is when the program needs the object: put it within reach.
    walked_into = context.room_before.get(ref.key, [])

    def room_rank(room: int | None) -> int:
        """0: the room the agent walked into before; 1: a room the program names; 2: other
        rooms and no room (a node outside every room, e.g. a second character)."""
        if room is None:
            return 2
        if graph.nodes[room].class_name in walked_into:
            return 0
        return 1 if room in context.rooms else 2

    char = graph.character_id
    if ref.key in context.worn and char is not None and st.room_of(char) is not None:
        # Worn: ON the character, in the room the program takes it off in, and within
        # reach of the other clothes it wears (finding one finds the others).
        rooms = [r for r in graph.room_ids if room_rank(r) == 0]
        room = min(rooms) if rooms else st.room_of(char)
        assert room is not None
        others = [by_key[k] for k in context.worn if k in by_key]
        return _put(st, ref, names, kb, None, char, ON, room, others)
    anchors: list[int] = []
    anchor = context.anchor.get(ref.key)
    if anchor is not None:
        exact = by_key.get(anchor, pins.get(anchor))
        if exact is not None:
            anchors = [exact]
        else:
            anchors = _best_anchor(st, _instances(st, context.names[anchor[0]], added),
                                   context, room_rank, rng)
    options = []
    for p in placements:
        relation = INSIDE if p.relation.upper() in ("IN", INSIDE) else ON
        room_classes = set(class_names_for(p.room, kb)) if p.room else None
        for dest in _instances(st, class_names_for(p.destination, kb), added):
            room = st.room_of(dest)
            if room is None or dest == room:
                continue
            if room_classes is not None and graph.nodes[room].class_name not in room_classes:
                continue
            cls = st.class_name(dest)
            if relation == ON and cls in context.seats:
                continue
            hidden = relation == INSIDE and S_CLOSED in st.states(dest) and cls not in opened
            near = 0 if dest in anchors else (
                1 if not st.targets(dest, CLOSE).isdisjoint(anchors) else 2)
            score = (hidden, near, cls not in used, room_rank(room), rng.random())
            options.append((score, dest, relation, room))
    # The program's own evidence beats the knowledge base: it walks to the coffee table
    # and grabs the novel there, so the novel may lie on the coffee table.
    listed = {(o[1], o[2]) for o in options}
    small = any(GRABBABLE in kb.properties(c) for c in names)
    for a in anchors if small else ():
        room = st.room_of(a)
        if room is None or a == room:
            continue
        props = st.properties(a)
        hidden = S_CLOSED in st.states(a) and st.class_name(a) not in opened
        seat = st.class_name(a) in context.seats
        for relation, prop, blocked in ((ON, SURFACES, seat), (INSIDE, CONTAINERS, hidden)):
            if prop in props and not blocked and (a, relation) not in listed:
                options.append(((False, 0, False, room_rank(room), rng.random()),
                                a, relation, room))
    options.sort()
    size = _size(names, kb) if plan is not None else None
    visible = [o for o in options if not o[0][0]]
    hidden = [o for o in options if o[0][0]]  # a last resort: grabbing it will fail
    floor_near = [(a, [a]) for a in anchors if st.room_of(a) not in (None, a)]
    floor_any = [(r, []) for r in sorted(graph.room_ids, key=lambda r: (room_rank(r),
                                                                      rng.random()))]
    # Within reach of the anchor beats a far shelf; a shelf beats the bare floor.
    attempts: list[tuple[str, Any]] = [("dest", o) for o in visible if o[0][1] < 2]
    attempts += [("floor", f) for f in floor_near]
    attempts += [("dest", o) for o in visible if o[0][1] == 2]
    attempts += [("floor", f) for f in floor_any]
    attempts += [("dest", o) for o in hidden]
    for kind, attempt in attempts:
        box = None
        if kind == "dest":
            _, dest, relation, room = attempt
            if size is not None:
                dest_box = st.node(dest).bounding_box
                if dest_box is None:
                    continue
                others = [b for b in (st.node(x).bounding_box
                                      for x in st.sources(dest, relation)) if b is not None]
                box = place_box(size, dest_box, relation, others, rng)
                if box is None:
                    continue
            near = [a for a in anchors if a == dest or a in st.targets(dest, CLOSE)]
            return _put(st, ref, names, kb, box, dest, relation, room, near)
        target, near = attempt
        room = st.room_of(target)
        assert room is not None
        if plan is not None and size is not None:
            target_box = st.node(target).bounding_box
            if near and target_box is not None:
                spot = plan.free_floor_near(room, target_box, size[0], size[2])
            else:
                spot = plan.free_floor(room, size[0], size[2], rng)
            if spot is None:
                continue
            box = BoundingBox((spot[0], size[1] / 2, spot[1]), size)
            plan.add_obstacle(room, box)
        return _put(st, ref, names, kb, box, room, INSIDE, room, near)
    tried = ", ".join(sorted({st.class_name(d) for _, d, _, _ in options}))
    raise GroundingError(f"{where}{lacks}, and there is no free space for one on or in "
                         f"{tried or 'any destination'} or on the floor of any room",
                         step_no, str(ref), tried)


def _best_anchor(st: SimState, candidates: list[int], context: _Context,
                 room_rank: Any, rng: random.Random) -> list[int]:
    """The one instance of the anchor's class grounding is likely to choose: in the room
    the agent walked into, close to most objects of the program's classes (the chair at
    the computer)."""
    classes = context.classes
    best = sorted(candidates, key=lambda n: (
        room_rank(st.room_of(n)),
        -sum(1 for x in st.targets(n, CLOSE) if st.class_name(x) in classes), rng.random()))
    return best[:1]


def _put(st: SimState, ref: ObjectRef, names: list[str], kb: ObjectKnowledge,
         box: BoundingBox | None, dest: int, relation: str, room: int,
         near: list[int]) -> Addition:
    node_id = max(st.next_node_id(), 1000)  # as the real data numbers added objects
    st.add_node(_new_node(node_id, ref.name, names, kb, box))
    st.add_edge(node_id, INSIDE, room)
    if dest != room:
        st.add_edge(node_id, relation, dest)
        st.add_pair(node_id, CLOSE, dest)
    for a in near:
        st.add_pair(node_id, CLOSE, a)
    return Addition(node_id, ref.name, dest, relation, room)


def _size(names: list[str], kb: ObjectKnowledge) -> tuple[float, float, float]:
    return _size_cached(kb, tuple(names))


@lru_cache(maxsize=4096)
def _size_cached(kb: ObjectKnowledge, names: tuple[str, ...]) -> tuple[float, float, float]:
    # Cached: the knowledge base's size lookup scans its classes for equivalent names.
    for c in names:
        size = kb.prefab_size(c)
        if size is not None:
            return (float(size[0]), float(size[1]), float(size[2]))
    return DEFAULT_SIZE


def _new_node(node_id: int, name: str, names: list[str], kb: ObjectKnowledge,
              box: BoundingBox | None) -> Node:
    properties: frozenset[str] = frozenset()
    for c in names:
        properties = frozenset(kb.properties(c))
        if properties:
            break
    return Node(node_id, name, "Props", properties, frozenset(kb.default_states(name)),
                None, box)
