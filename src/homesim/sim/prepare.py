"""Scene preparation: make a home ready for a program before grounding it.

Two things are prepared, on a copy of the home (the input graph is never changed):

1. **Missing objects.** A program names objects by class and a per-program instance
   number. When it uses more instances of a class than the home has (counting the
   class's equivalent names), the missing ones are added at a destination the placement
   knowledge base allows for the class (``cup``: ON a table, INSIDE a cupboard, ...).
   Destinations are preferred in this order: not hidden inside a closed container the
   program does not open first; one the program uses before it needs the object (it walks
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
from collections import Counter
from dataclasses import dataclass, field

from homesim.errors import GroundingError
from homesim.program.model import ObjectRef, Program
from homesim.sim.kbtypes import ObjectKnowledge, class_names_for, default_kb
from homesim.sim.placement import place_box
from homesim.sim.standing import FloorPlan, has_geometry
from homesim.sim.state import SimState
from homesim.world.graph import BoundingBox, EnvironmentGraph, Node
from homesim.world.vocab import (
    CHARACTER_CLASS,
    CLOSE,
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
)

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
            kb: ObjectKnowledge | None = None) -> Prepared:
    """Add the objects `program` needs and set the initial states it presupposes.

    Args:
        program: the program (grounded or not; only class names and instances matter).
        graph: the home; never modified.
        seed: breaks ties between equally good destinations and picks spots on them.
        kb: the object knowledge base (default: `homesim.knowledge.load_kb()`).

    Returns:
        `Prepared`: the new graph, the additions and the state changes.

    Raises:
        GroundingError: an object is missing and cannot be added (a room, the character,
            or no destination and no free floor for it).
    """
    kb = kb or default_kb()
    rng = random.Random(seed)
    context = _Context(program, graph, kb)
    missing: list[ObjectRef] = []
    for name, refs in context.refs_by_name.items():
        have = len(instances_of(graph, context.names[name]))
        missing += refs[have:]
    states = _initial_states(program, graph, context, kb)
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
    added = [_add(st, ref, program, context, kb, rng, plan) for ref in missing]
    return Prepared(st.to_graph(), added, changed)


class _Context:
    """What the program uses: per class name its refs and home class names, the rooms
    it names, and which classes it uses and opens before each object's first use."""

    def __init__(self, program: Program, graph: EnvironmentGraph, kb: ObjectKnowledge):
        self.refs_by_name: dict[str, list[ObjectRef]] = {}
        self.names: dict[str, list[str]] = {}
        for ref in program.object_refs():
            self.refs_by_name.setdefault(ref.name, []).append(ref)
            if ref.name not in self.names:
                self.names[ref.name] = class_names_for(ref.name, kb)
        classes = {c for names in self.names.values() for c in names}
        self.rooms = [r.id for r in graph.rooms() if r.class_name in classes]
        self.used_before: dict[tuple[str, int], set[str]] = {}
        self.opened_before: dict[tuple[str, int], set[str]] = {}
        used: set[str] = set()
        opened: set[str] = set()
        for step in program.steps:
            for ref in step.args:
                self.used_before.setdefault(ref.key, set(used))
                self.opened_before.setdefault(ref.key, set(opened))
            for ref in step.args:
                used.update(self.names[ref.name])
                if step.action.key == "OPEN":
                    opened.update(self.names[ref.name])


def _initial_states(program: Program, graph: EnvironmentGraph, context: _Context,
                    kb: ObjectKnowledge) -> dict[int, frozenset[str]]:
    """Node id -> the states the program presupposes for it (only nodes that change)."""
    required: dict[tuple[str, int], dict[str, str]] = {}
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
    out: dict[int, frozenset[str]] = {}
    done: set[str] = set()
    for (name, _), groups in required.items():
        if name in done:  # one class, several objects: the first one decides
            continue
        done.add(name)
        for node_id in instances_of(graph, context.names[name]):
            node = graph.nodes[node_id]
            states = set(out.get(node_id, node.states))
            for group, state in groups.items():
                if group == "plug?":
                    if HAS_PLUG not in node.properties or "plug" in groups:
                        continue
                    group = "plug"
                elif group == "switch?":
                    if HAS_SWITCH not in node.properties or "switch" in groups:
                        continue
                    group = "switch"
                states.difference_update(_GROUPS[group])
                states.add(state)
            if frozenset(states) != node.states:
                out[node_id] = frozenset(states)
    char = graph.character_id
    if posture is not None and char is not None:
        states = graph.nodes[char].states
        if posture not in states:
            out[char] = (states - {S_SITTING, S_LYING}) | {posture}
    return out


def _add(st: SimState, ref: ObjectRef, program: Program, context: _Context,
         kb: ObjectKnowledge, rng: random.Random, plan: FloorPlan | None) -> Addition:
    graph = st.graph
    name = ref.name
    step_no, step_text = first_use(program, ref.key)
    where = f"step {step_no} {step_text}: " if step_no else ""
    names = context.names[name]
    lacks = f"the home has too few {' or '.join(names)} for <{name}> ({ref.instance})"
    if name == CHARACTER_CLASS or any(n.is_room for c in names for n in graph.nodes_of_class(c)):
        raise GroundingError(f"{where}{lacks}; rooms and characters cannot be added",
                             step_no, str(ref), "rooms")
    placements = []
    for c in names:
        placements = list(kb.placements(c))
        if placements:
            break
    used = context.used_before.get(ref.key, set())
    opened = context.opened_before.get(ref.key, set())
    options = []
    for p in placements:
        relation = INSIDE if p.relation.upper() in ("IN", INSIDE) else ON
        room_classes = set(class_names_for(p.room, kb)) if p.room else None
        for dest in instances_of(graph, class_names_for(p.destination, kb)):
            room = graph.room_of(dest)
            if room is None or dest == room:
                continue
            if room_classes is not None and graph.nodes[room].class_name not in room_classes:
                continue
            cls = graph.nodes[dest].class_name
            hidden = relation == INSIDE and S_CLOSED in st.states(dest) and cls not in opened
            score = (hidden, cls not in used, room not in context.rooms, rng.random())
            options.append((score, dest, relation, room))
    options.sort()
    size = _size(names, kb) if plan is not None else None
    for _, dest, relation, room in options:
        box = None
        if size is not None:
            dest_box = graph.nodes[dest].bounding_box
            if dest_box is None:
                continue
            others = [b for b in (st.node(x).bounding_box for x in st.sources(dest, relation))
                      if b is not None]
            box = place_box(size, dest_box, relation, others, rng)
            if box is None:
                continue
        return _put(st, ref, names, kb, box, dest, relation, room)
    # No destination in the home (or none with space): stand it on the floor of a room.
    rooms = context.rooms or sorted(graph.room_ids)
    rooms = sorted(rooms, key=lambda r: (r not in context.rooms, rng.random()))
    for room in rooms:
        box = None
        if plan is not None and size is not None:
            spot = plan.free_floor(room, size[0], size[2], rng)
            if spot is None:
                continue
            box = BoundingBox((spot[0], size[1] / 2, spot[1]), size)
            plan.add_obstacle(room, box)
        return _put(st, ref, names, kb, box, room, INSIDE, room)
    tried = ", ".join(sorted({graph.nodes[d].class_name for _, d, _, _ in options}))
    raise GroundingError(f"{where}{lacks}, and there is no free space for one on or in "
                         f"{tried or 'any destination'} or on the floor of any room",
                         step_no, str(ref), tried)


def _put(st: SimState, ref: ObjectRef, names: list[str], kb: ObjectKnowledge,
         box: BoundingBox | None, dest: int, relation: str, room: int) -> Addition:
    node_id = max(st.next_node_id(), 1000)  # as the real data numbers added objects
    st.add_node(_new_node(node_id, ref.name, names, kb, box))
    st.add_edge(node_id, INSIDE, room)
    if dest != room:
        st.add_edge(node_id, relation, dest)
        st.add_pair(node_id, CLOSE, dest)
    return Addition(node_id, ref.name, dest, relation, room)


def _size(names: list[str], kb: ObjectKnowledge) -> tuple[float, float, float]:
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
