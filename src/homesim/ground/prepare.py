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

import difflib
import random
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from functools import lru_cache
from typing import Any

from homesim.errors import GroundingError
from homesim.ground.placement import place_box
from homesim.knowledge.kbtypes import ObjectKnowledge, class_names_for, default_kb
from homesim.program.bindings import Bindings
from homesim.program.model import ObjectRef, Program, Step
from homesim.sim.failure import FailureKind
from homesim.sim.state import SimState
from homesim.world.class_table import class_row
from homesim.world.graph import BoundingBox, EnvironmentGraph, Node
from homesim.world.standing import FloorPlan, has_geometry, note_prepared
from homesim.world.vocab import (
    BODY_PART,
    CAN_OPEN,
    CHARACTER_CLASS,
    CLOSE,
    CONTAINERS,
    GRABBABLE,
    HAS_PLUG,
    HAS_SWITCH,
    INSIDE,
    ON,
    ROOM_NAMES,
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

DEFAULT_SIZE = (0.15, 0.15, 0.15)
"""Box size (m) for an added object whose class has no prefab dimensions."""

# Every per-action fact (presupposed states, posture, needed properties, reach, moves)
# is a column of the action catalog (`homesim.program.actions`); here only the state
# groups: a presupposed state replaces the other states of its group.
_GROUPS = {"switch": (S_ON, S_OFF), "door": (S_OPEN, S_CLOSED),
           "plug": (S_PLUGGED_IN, S_PLUGGED_OUT)}
_GROUP_OF = {state: group for group, states in _GROUPS.items() for state in states}
_ABLE = {"switch": HAS_SWITCH, "plug": HAS_PLUG, "door": CAN_OPEN}
"""The property an object needs for a state of the group to be presupposed "if able"."""
_SEATED = frozenset({S_SITTING, S_LYING})
STANDING = "STANDING"
"""`ActionSpec.posture_after` of steps that leave the character on its feet."""


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
            pins: Bindings | None = None) -> Prepared:
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
    changed = _set_states(st, states)
    adder = _Adder(st, program, context, kb, random.Random(seed), pins or Bindings())
    for ref in missing:
        addition = adder.add(ref)
        groups = _groups_of_class(required, ref.name)
        node = st.node(addition.node_id)
        new = _apply(node.states, node.properties, groups)
        if new != node.states:
            st.set_states(addition.node_id, new)
    prepared = st.to_graph()
    if adder.plan is not None:
        # Let standing spots of the prepared home reuse those of this one (see FloorPlan).
        added = adder.added
        floor_rooms = frozenset(a.room for a in added if a.destination_id == a.room)
        note_prepared(prepared, graph, floor_rooms)
    return Prepared(prepared, adder.added, changed)


def _set_states(st: SimState, states: dict[int, frozenset[str]]
                ) -> list[tuple[int, frozenset[str], frozenset[str]]]:
    """Set the presupposed states; (node, before, after) for those that change."""
    changed = []
    for node_id, new in states.items():
        old = st.states(node_id)
        if new != old:
            st.set_states(node_id, new)
            changed.append((node_id, old, new))
    return changed


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
        # Objects on a seat take its place (the simulator counts them), so nothing is put
        # on what the program sits or lies on.
        self.seats = {c for step in program.steps if step.action.posture_after in _SEATED
                      for ref in step.args for c in self.names[ref.name]}
        self.worn = _worn(program)
        self.missing = self._missing(program, graph)
        room_classes = {r.class_name for r in graph.rooms()}
        self.is_room = {n: bool(room_classes.intersection(c)) for n, c in self.names.items()}
        self.used_before: dict[Key, set[str]] = {}
        self.opened_before: dict[Key, set[str]] = {}
        self.anchor: dict[Key, Key] = {}
        self.room_before: dict[Key, list[str]] = {}
        self._program = program

    def _missing(self, program: Program, graph: EnvironmentGraph) -> list[ObjectRef]:
        """The program objects the home has no instance left for, worn clothes last."""
        needs = _needs_by_name(program)
        missing: list[ObjectRef] = []
        for name, refs in self.refs_by_name.items():
            ids = instances_of(graph, self.names[name])
            wanted = needs.get(name, set())
            if wanted:  # only those that can do what the program does with it (eat it)
                ids = [i for i in ids if all(not graph.nodes[i].properties.isdisjoint(w)
                                             for w in wanted)]
            missing += [r for r in refs[len(ids):] if r.key not in self.worn]
        # A fresh instance of each, worn by the character (none of the home's is worn).
        missing += [r for refs in self.refs_by_name.values() for r in refs
                    if r.key in self.worn]
        return missing

    def find_anchors(self, free: set[Key]) -> None:
        """Anchor each object of `free` (to be added) where the program needs it.

        Places are the starting places of the program's objects; `parent` joins a place
        to the place it must be near. An object is at its starting place until the
        program puts it somewhere else."""
        walk = _AnchorWalk(self, free)
        for step in self._program.steps:
            walk.step(step)
        walk.anchor_where_first_named()


def _needs_by_name(program: Program) -> dict[str, set[frozenset[str]]]:
    """Program object name -> the property requirements its steps put on it."""
    needs: dict[str, set[frozenset[str]]] = {}
    for step in program.steps:
        for pos, ref in enumerate(step.args):
            for need in step.action.needs_of(pos):
                needs.setdefault(ref.name, set()).add(need)
    return needs


def _worn(program: Program) -> set[Key]:
    """Clothes the program takes off before doing anything else with them (but walk to
    them, look at them): they are worn."""
    worn: set[Key] = set()
    seen: set[Key] = set()
    for step in program.steps:
        if not step.action.handles:
            continue
        for ref in step.args:
            if ref.key not in seen and step.action.worn_before:
                worn.add(ref.key)
            seen.add(ref.key)
    return worn


class _AnchorWalk:
    """Follows the agent and the program's objects through the steps (`find_anchors`)."""

    def __init__(self, context: _Context, free: set[Key]):
        self.context, self.free = context, free
        self.parent: dict[Key, Key] = {}
        self.pos: dict[Key, Key] = {}  # object -> the starting place it is at now
        self.held: set[Key] = set()
        self.first_at: dict[Key, Key] = {}
        self.used: set[str] = set()
        self.opened: set[str] = set()
        self.agent: Key | None = None  # the place the agent is at
        self.sitting = False
        self.room: list[str] = []  # classes of the room the agent last walked into

    def place(self, k: Key) -> Key:
        p = self.pos.get(k, k)
        while p in self.parent:
            p = self.parent[p]
        return p

    def step(self, step: Step) -> None:
        action = step.action
        self.note_first_use(step)
        # A seated agent's Find does not walk: it needs the object within reach.
        reach = action.reach or (action.moves and action.posture_after != STANDING
                                 and self.sitting)
        if action.posture_after is not None:
            self.sitting = action.posture_after in _SEATED
        if action.moves and step.args and not reach:
            self.move_agent(step.args[0])
        if reach and step.args and self.agent is not None:
            self.join_places(step.args[-1])
        self.note_use(step)
        self.move_held(step)

    def note_first_use(self, step: Step) -> None:
        """What was used and opened, and where the agent was, when an object first comes."""
        c = self.context
        for ref in step.args:
            c.used_before.setdefault(ref.key, set(self.used))
            c.opened_before.setdefault(ref.key, set(self.opened))
            c.room_before.setdefault(ref.key, self.room)
            if self.agent is not None and self.agent != ref.key:
                self.first_at.setdefault(ref.key, self.agent)

    def move_agent(self, ref: ObjectRef) -> None:
        if self.context.is_room[ref.name]:
            self.agent, self.room = None, self.context.names[ref.name]
        elif ref.key not in self.held:
            self.agent = self.place(ref.key)

    def join_places(self, target: ObjectRef) -> None:
        """The agent acts on `target` within reach: its place and the agent's are one."""
        c = self.context
        if target.key in self.held or c.is_room[target.name]:
            return
        there = self.place(target.key)
        agent = self.agent
        if there == agent or agent is None:
            return
        # Only a starting place of an object still to be added can move. Prefer moving
        # the place the agent went to (the detergent it walked to goes near the washing
        # machine it pours into).
        if agent in self.free and agent not in c.anchor:
            c.anchor[agent] = self.parent[agent] = there
            self.agent = there
        elif there in self.free and there not in c.anchor:
            c.anchor[there] = self.parent[there] = agent

    def note_use(self, step: Step) -> None:
        sets = step.action.sets_states
        for ref in step.args:
            names = self.context.names[ref.name]
            self.used.update(names)
            if S_OPEN in sets:
                self.opened.update(names)
            elif S_CLOSED in sets:  # open when the object is needed, not just once
                self.opened.difference_update(names)

    def move_held(self, step: Step) -> None:
        """Follow what the step takes, puts or lets go of."""
        hands, args = step.action.hands, step.args
        if hands == "take" and args:
            if args[0].key not in self.pos:
                self.pos[args[0].key] = self.place(args[0].key)
            self.held.add(args[0].key)
        elif hands == "put" and len(args) == 2:
            self.held.discard(args[0].key)
            self.pos[args[0].key] = self.place(args[1].key)
        elif hands == "let_go" and args:
            self.held.discard(args[0].key)
            if self.agent is not None:
                self.pos[args[0].key] = self.agent

    def anchor_where_first_named(self) -> None:
        """Otherwise: near what the agent was at when the program first names it."""
        c = self.context
        for k, at in self.first_at.items():
            if k in self.free and k not in c.anchor and k not in self.parent:
                p = at
                while p in self.parent:
                    p = self.parent[p]
                if p != k:
                    c.anchor[k] = p


def _presupposed(program: Program) -> tuple[dict[Key, dict[str, str]], str | None]:
    """Per program object, the state of each group (switch, door, plug) its first steps
    presuppose; and the posture the character must start in, if any."""
    required: dict[Key, dict[str, str]] = {}
    posture = _start_posture(program)
    for step in program.steps:
        action = step.action
        if not step.args or not action.presupposes:
            continue
        groups = required.setdefault(step.args[0].key, {})
        for state in action.presupposes:
            groups.setdefault(_GROUP_OF[state], state)
        # Switching on needs power, opening needs the device off: presuppose those too
        # unless an earlier step already settled them.
        for state in action.presupposes_if_able:
            groups.setdefault(_GROUP_OF[state] + "?", state)
    return required, posture


def _start_posture(program: Program) -> str | None:
    """The posture the first step that needs or sets one needs (None: it sets one)."""
    for step in program.steps:
        if step.action.posture_needed is not None:
            return step.action.posture_needed
        if step.action.posture_after is not None:
            return None
    return None


def _groups_of_class(required: dict[Key, dict[str, str]], name: str) -> dict[str, str]:
    """The groups the first program object of class `name` presupposes ({} if none)."""
    return next((groups for key, groups in required.items() if key[0] == name), {})


def _apply(states: frozenset[str], properties: frozenset[str],
           groups: dict[str, str]) -> frozenset[str]:
    out = set(states)
    for group, state in groups.items():
        if group.endswith("?"):  # only if able, and not set by the object's own steps
            group = group[:-1]
            if _ABLE[group] not in properties or group in groups:
                continue
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


Option = tuple[tuple[bool, int, bool, int, float], int, str, int]
"""(score, destination, relation, room) of one place to put an added object."""


class _Adder:
    """Adds the missing objects one by one (`prepare`): near their anchor, on or in a
    destination the knowledge base allows, else on free floor."""

    def __init__(self, st: SimState, program: Program, context: _Context,
                 kb: ObjectKnowledge, rng: random.Random, pins: Bindings):
        self.st, self.program, self.context, self.kb, self.rng = st, program, context, kb, rng
        self.pins = pins
        self.plan = FloorPlan(st.graph) if has_geometry(st.graph) else None
        self.added: list[Addition] = []
        self.by_key: dict[Key, int] = {}

    def add(self, ref: ObjectRef) -> Addition:
        """Add one instance for `ref`; GroundingError if it cannot be added."""
        addition = self._add(ref)
        self.added.append(addition)
        self.by_key[ref.key] = addition.node_id
        return addition

    def _add(self, ref: ObjectRef) -> Addition:
        st, context = self.st, self.context
        names = context.names[ref.name]
        self._check_addable(ref, names)
        rank = _RoomRank(st.graph, context, ref.key)
        char = st.graph.character_id
        if ref.key in context.worn and char is not None and st.room_of(char) is not None:
            return self._add_worn(ref, names, rank, char)
        if char is not None and st.room_of(char) is not None and _body_part(ref.name, names):
            return self._add_body_part(ref, names, char)
        anchors = self._anchors(ref, rank)
        options = self._kb_options(ref, names, anchors, rank)
        options += self._evidence_options(ref, names, anchors, rank, options)
        options.sort()
        size = _size(names, self.kb) if self.plan is not None else None
        for kind, attempt in self._attempts(options, anchors, rank):
            if kind == "dest":
                addition = self._try_dest(ref, names, attempt, size, anchors)
            else:
                addition = self._try_floor(ref, names, attempt, size)
            if addition is not None:
                return addition
        tried = ", ".join(sorted({st.class_name(d) for _, d, _, _ in options}))
        raise GroundingError(f"{self._where(ref)}{self._lacks(ref, names)}, and there is no "
                             f"free space for one on or in {tried or 'any destination'} or "
                             "on the floor of any room", first_use(self.program, ref.key)[0],
                             str(ref), tried, FailureKind.MISSING)

    def _where(self, ref: ObjectRef) -> str:
        step_no, step_text = first_use(self.program, ref.key)
        return f"step {step_no} {step_text}: " if step_no else ""

    def _lacks(self, ref: ObjectRef, names: list[str]) -> str:
        few = "too few" if _instances(self.st, names, self.added) else "no"
        return f"the home has {few} {' or '.join(names)} for <{ref.name}> ({ref.instance})"

    def _check_addable(self, ref: ObjectRef, names: list[str]) -> None:
        """Rooms, the character and classes the knowledge base does not know cannot be
        added."""
        graph, kb = self.st.graph, self.kb
        step_no = first_use(self.program, ref.key)[0]
        if (ref.name == CHARACTER_CLASS or ROOM_NAMES.intersection(names)
                or any(n.is_room for c in names for n in graph.nodes_of_class(c))):
            raise GroundingError(f"{self._where(ref)}{self._lacks(ref, names)}; rooms and "
                                 "characters cannot be added", step_no, str(ref), "rooms",
                                 FailureKind.MISSING)
        if not any(kb.properties(c) or kb.placements(c) or kb.prefab_size(c)
                   or kb.default_states(c) for c in names):
            raise GroundingError(f"{self._where(ref)}{self._lacks(ref, names)}, and the "
                                 f"knowledge base does not know {ref.name!r}, so none can be "
                                 f"added{_suggest(ref.name, kb)}", step_no, str(ref), "",
                                 FailureKind.MISSING)

    def _add_worn(self, ref: ObjectRef, names: list[str], rank: _RoomRank,
                  char: int) -> Addition:
        """Worn: ON the character, in the room the program takes it off in, and within
        reach of the other clothes it wears (finding one finds the others)."""
        st = self.st
        rooms = [r for r in st.graph.room_ids if rank(r) == 0]
        room = min(rooms) if rooms else st.room_of(char)
        assert room is not None
        others = [self.by_key[k] for k in self.context.worn if k in self.by_key]
        return _put(st, ref, names, self.kb, None, char, ON, room, others)

    def _add_body_part(self, ref: ObjectRef, names: list[str], char: int) -> Addition:
        """A part of the agent's body (teeth, hair): no prop on a counter but a
        ``BODY_PART`` node without a box, in the character's room and close to it (the
        simulator keeps body parts close; render acts at the body)."""
        st = self.st
        room = st.room_of(char)
        assert room is not None
        node_id = max(st.next_node_id(), 1000)
        node = _new_node(node_id, ref.name, names, self.kb, None)
        st.add_node(Node(node.id, node.class_name, node.category,
                         node.properties | {BODY_PART}, node.states, None, None))
        st.add_edge(node_id, INSIDE, room)
        st.add_pair(node_id, CLOSE, char)
        return Addition(node_id, ref.name, room, INSIDE, room)

    def _anchors(self, ref: ObjectRef, rank: _RoomRank) -> list[int]:
        """The node(s) the object should be near: its anchor's node when known."""
        anchor = self.context.anchor.get(ref.key)
        if anchor is None:
            return []
        exact = self.by_key.get(anchor, self.pins.get(anchor))
        if exact is not None:
            return [exact]
        candidates = _instances(self.st, self.context.names[anchor[0]], self.added)
        return _best_anchor(self.st, candidates, self.context, rank, self.rng)

    def _kb_options(self, ref: ObjectRef, names: list[str], anchors: list[int],
                    rank: _RoomRank) -> list[Option]:
        """Destinations the placement knowledge base allows, scored (lower is better)."""
        st, context, kb = self.st, self.context, self.kb
        used = context.used_before.get(ref.key, set())
        opened = context.opened_before.get(ref.key, set())
        options: list[Option] = []
        for p in _placements(names, kb):
            relation = INSIDE if p.relation.upper() in ("IN", INSIDE) else ON
            room_classes = set(class_names_for(p.room, kb)) if p.room else None
            for dest in _instances(st, class_names_for(p.destination, kb), self.added):
                room = st.room_of(dest)
                if room is None or dest == room:
                    continue
                if room_classes is not None and st.class_name(room) not in room_classes:
                    continue
                cls = st.class_name(dest)
                if relation == ON and cls in context.seats:
                    continue
                hidden = relation == INSIDE and S_CLOSED in st.states(dest) and cls not in opened
                near = 0 if dest in anchors else (
                    1 if not st.targets(dest, CLOSE).isdisjoint(anchors) else 2)
                score = (hidden, near, cls not in used, rank(room), self.rng.random())
                options.append((score, dest, relation, room))
        return options

    def _evidence_options(self, ref: ObjectRef, names: list[str], anchors: list[int],
                          rank: _RoomRank, listed_options: list[Option]) -> list[Option]:
        """The program's own evidence beats the knowledge base: it walks to the coffee
        table and grabs the novel there, so the novel may lie on the coffee table."""
        st, kb = self.st, self.kb
        if not any(GRABBABLE in kb.properties(c) for c in names):
            return []
        listed = {(o[1], o[2]) for o in listed_options}
        opened = self.context.opened_before.get(ref.key, set())
        options: list[Option] = []
        for a in anchors:
            room = st.room_of(a)
            if room is None or a == room:
                continue
            props = st.properties(a)
            hidden = S_CLOSED in st.states(a) and st.class_name(a) not in opened
            seat = st.class_name(a) in self.context.seats
            for relation, prop, blocked in ((ON, SURFACES, seat),
                                            (INSIDE, CONTAINERS, hidden)):
                if prop in props and not blocked and (a, relation) not in listed:
                    options.append(((False, 0, False, rank(room), self.rng.random()),
                                    a, relation, room))
        return options

    def _attempts(self, options: list[Option], anchors: list[int],
                  rank: _RoomRank) -> list[tuple[str, Any]]:
        """Places to try, in order: within reach of the anchor beats a far shelf; a shelf
        beats the bare floor; a hidden place is a last resort (grabbing it will fail)."""
        st, rng = self.st, self.rng
        visible = [o for o in options if not o[0][0]]
        hidden = [o for o in options if o[0][0]]
        floor_near = [(a, [a]) for a in anchors if st.room_of(a) not in (None, a)]
        floor_any: list[tuple[int, list[int]]] = [
            (r, []) for r in sorted(st.graph.room_ids, key=lambda r: (rank(r), rng.random()))]
        attempts: list[tuple[str, Any]] = [("dest", o) for o in visible if o[0][1] < 2]
        attempts += [("floor", f) for f in floor_near]
        attempts += [("dest", o) for o in visible if o[0][1] == 2]
        attempts += [("floor", f) for f in floor_any]
        attempts += [("dest", o) for o in hidden]
        return attempts

    def _try_dest(self, ref: ObjectRef, names: list[str], option: Option,
                  size: tuple[float, float, float] | None,
                  anchors: list[int]) -> Addition | None:
        """Put the object on or in a destination, if there is room for its box."""
        st = self.st
        _, dest, relation, room = option
        if not self._standable(dest):
            return None
        box = None
        if size is not None:
            dest_box = st.node(dest).bounding_box
            if dest_box is None:
                return None
            others = [b for b in (st.node(x).bounding_box
                                  for x in st.sources(dest, relation)) if b is not None]
            box = place_box(size, dest_box, relation, others, self.rng)
            if box is None:
                return None
        near = [a for a in anchors if a == dest or a in st.targets(dest, CLOSE)]
        return _put(st, ref, names, self.kb, box, dest, relation, room, near)

    def _standable(self, dest: int) -> bool:
        """Whether the agent can stand next to `dest`, or next to what holds it (as
        grounding asks: `homesim.ground.search`); True without geometry."""
        plan, st = self.plan, self.st
        if plan is None:
            return True
        seen: set[int] = set()
        while dest not in seen and dest not in st.graph.room_ids:
            if dest not in plan.graph.nodes:
                return True  # added by this preparation: placed where it can be reached
            seen.add(dest)
            if st.node(dest).bounding_box is None or plan.spot_near(dest) is not None:
                return True
            holders = sorted((st.targets(dest, ON) | st.targets(dest, INSIDE))
                             - st.graph.room_ids)
            if not holders:
                return False
            dest = holders[0]
        return True

    def _try_floor(self, ref: ObjectRef, names: list[str], attempt: tuple[int, list[int]],
                   size: tuple[float, float, float] | None) -> Addition | None:
        """Stand the object on free floor next to `target` (or anywhere in its room)."""
        st, plan = self.st, self.plan
        target, near = attempt
        room = st.room_of(target)
        assert room is not None
        box = None
        if plan is not None and size is not None:
            target_box = st.node(target).bounding_box
            if near and target_box is not None:
                spot = plan.free_floor_near(room, target_box, size[0], size[2])
            else:
                spot = plan.free_floor(room, size[0], size[2], self.rng)
            if spot is None:
                return None
            box = BoundingBox((spot[0], size[1] / 2, spot[1]), size)
            plan.add_obstacle(room, box)
        return _put(st, ref, names, self.kb, box, room, INSIDE, room, near)


class _RoomRank:
    """Where the agent is when the program needs an object: 0 for the room it walked into
    before, 1 for a room the program names, 2 for any other (and for no room)."""

    def __init__(self, graph: EnvironmentGraph, context: _Context, key: Key):
        self.graph, self.rooms = graph, context.rooms
        self.walked_into = context.room_before.get(key, [])

    def __call__(self, room: int | None) -> int:
        if room is None or room not in self.graph.nodes:
            return 2
        if self.graph.nodes[room].class_name in self.walked_into:
            return 0
        return 1 if room in self.rooms else 2


def _suggest(name: str, kb: ObjectKnowledge) -> str:
    """``" (did you mean television?)"``: known classes spelled like `name`, if any."""
    close = difflib.get_close_matches(name, kb.classes(), n=3, cutoff=0.75)
    return f" (did you mean {' or '.join(close)}?)" if close else ""


def _placements(names: list[str], kb: ObjectKnowledge) -> list[Any]:
    """The knowledge base's placements of the first of `names` that has any."""
    for c in names:
        placements = list(kb.placements(c))
        if placements:
            return placements
    return []


def _best_anchor(st: SimState, candidates: list[int], context: _Context,
                 room_rank: _RoomRank, rng: random.Random) -> list[int]:
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


def _body_part(name: str, names: list[str]) -> bool:
    """Whether a program's object is a part of the agent's body (the class table's size
    ``body``): such things are never added as objects of their own."""
    return any((row := class_row(c)) is not None and row.is_body_part for c in [name, *names])


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
