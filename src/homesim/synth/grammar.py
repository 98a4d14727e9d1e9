"""A probabilistic grammar of programs that are executable by construction.

Glossary:
    task: a short sub-activity ("put the cup on the table") that expands to 1-6 steps over
        the 12 animated actions; a program is 1-4 tasks.
    expansion: the task's steps with concrete nodes of a home. Every step is run on the
        simulator state of the home as it is chosen (`run_step`); a step whose
        preconditions fail undoes the task (`SimState.undo`) and another task or object
        is drawn. What is kept therefore executes, in order, from the home's initial state.

The program is written ungrounded (``<cup> (1)``: instance numbers count distinct nodes of
a class within the program); it is an `ActivityProgram` whose `home` names the built-in home
and whose `bindings` keep the nodes it used.

Descriptions: ``"people"`` (the default) are written by the paraphrase grammar of
`homesim.synth.describe`, from a random source of their own seeded by the program id;
``"templates"`` are the fixed task phrases of `homesim.synth.templates` (the text of the
learning figures before the paraphrase grammar). The template phrases are drawn in both
styles, so one seed gives the same programs whichever style describes them.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterator
from dataclasses import dataclass, replace
from functools import cache

from homesim.knowledge.datasets import ActivityProgram
from homesim.program.actions import ACTIONS
from homesim.program.bindings import Bindings
from homesim.program.model import ObjectRef, Program, Step
from homesim.sim.execute import run_step
from homesim.sim.state import SimState
from homesim.synth import templates
from homesim.synth.describe import Act, Thing, describe
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import open_home
from homesim.world.vocab import (
    CAN_OPEN,
    FACING,
    GRABBABLE,
    HAS_SWITCH,
    INSIDE,
    LOOKABLE,
    ON,
    SITTABLE,
    SURFACES,
)

DEFAULT_HOMES: tuple[str, ...] = tuple(f"scene{i}_trimmed" for i in range(1, 6))
"""The five VirtualHome apartments, with the class names programs use (``television``)."""

_STRUCTURE = frozenset({"floor", "wall", "ceiling", "doorjamb", "closetdrawer", "character",
                        "window", "ceilinglamp", "walllamp"})
_SAYABLE = frozenset({GRABBABLE, SURFACES, SITTABLE, CAN_OPEN, HAS_SWITCH, LOOKABLE})

SOURCE = "synth"
"""The `ActivityProgram.source` of a synthetic program (its id is ``synth-<seed>-<index>``;
its `home` and `bindings` say where and on which nodes it executes)."""

StepSpec = tuple[str, tuple[int, ...]]
"""An action key and the node ids of its objects."""


@dataclass(frozen=True)
class Expansion:
    """A task made concrete: its phrase kind, slot nodes and steps."""

    kind: str
    slots: dict[str, int]
    steps: list[StepSpec]
    ends_program: bool = False  # sitting with no stand-up: nothing can follow


@cache
def _home(name: str) -> EnvironmentGraph:
    return open_home(name)


class _Context:
    """The home, the simulated state and the random source of one program being built."""

    def __init__(self, graph: EnvironmentGraph, rng: random.Random):
        self.graph = graph
        self.state = SimState(graph)
        self.rng = rng
        objects = [n for n in graph if n.class_name not in _STRUCTURE
                   and n.id not in graph.room_ids and n.properties & _SAYABLE]
        self.objects = objects

    def with_property(self, prop: str) -> list[int]:
        return [n.id for n in self.objects if prop in n.properties]

    def pick(self, ids: list[int]) -> int | None:
        return self.rng.choice(ids) if ids else None

    def closed_container(self, n: int) -> int | None:
        for x in self.state.targets(n, INSIDE):
            if x not in self.graph.room_ids and "CLOSED" in self.state.states(x):
                return x
        return None

    def step(self, key: str, ids: tuple[int, ...]) -> Step:
        refs = tuple(ObjectRef(self.state.class_name(i), 1, i) for i in ids)
        return Step(ACTIONS[key], refs)

    def apply(self, steps: list[StepSpec]) -> bool:
        """Run the steps; on the first failure undo them all and return False."""
        mark = self.state.mark()
        for key, ids in steps:
            if run_step(self.state, self.step(key, ids), ids) is not None:
                self.state.undo(mark)
                return False
        return True


# ----------------------------------------------------------------------- tasks
# A task draws its objects and returns an Expansion (or None when the home offers none).
Task = Callable[[_Context, bool], Expansion | None]


def _to_room(ctx: _Context, key: str, kind: str) -> Expansion | None:
    here = ctx.state.room_of(ctx.state.char)
    room = ctx.pick([r for r in ctx.graph.room_ids if r != here])
    return None if room is None else Expansion(kind, {"room": room}, [(key, (room,))])


def walk_room(ctx: _Context, last: bool) -> Expansion | None:
    return _to_room(ctx, "WALK", "walk_room")


def run_room(ctx: _Context, last: bool) -> Expansion | None:
    return _to_room(ctx, "RUN", "run_room")


def _switch(ctx: _Context, on: bool) -> Expansion | None:
    want = "OFF" if on else "ON"
    x = ctx.pick([i for i in ctx.with_property(HAS_SWITCH) if want in ctx.state.states(i)])
    if x is None:
        return None
    key = "SWITCHON" if on else "SWITCHOFF"
    return Expansion("switch_on" if on else "switch_off", {"x": x},
                     [("WALK", (x,)), (key, (x,))])


def switch_on(ctx: _Context, last: bool) -> Expansion | None:
    return _switch(ctx, True)


def switch_off(ctx: _Context, last: bool) -> Expansion | None:
    return _switch(ctx, False)


def fetch(ctx: _Context, last: bool) -> Expansion | None:
    x = ctx.pick(ctx.with_property(GRABBABLE))
    y = ctx.pick(ctx.with_property(SURFACES))
    if x is None or y is None or x == y:
        return None
    c = ctx.closed_container(x)
    put = [("WALK", (y,)), ("PUTBACK", (x, y))]
    if c is None:
        return Expansion("fetch", {"x": x, "y": y}, [("WALK", (x,)), ("GRAB", (x,)), *put])
    if ctx.rng.random() < 0.5:
        return Expansion("fetch_open", {"x": x, "y": y, "c": c},
                         [("WALK", (x,)), ("OPEN", (c,)), ("GRAB", (x,)), *put])
    return Expansion("fetch_open_close", {"x": x, "y": y, "c": c},
                     [("WALK", (x,)), ("OPEN", (c,)), ("GRAB", (x,)), ("CLOSE", (c,)), *put])


def grab(ctx: _Context, last: bool) -> Expansion | None:
    x = ctx.pick(ctx.with_property(GRABBABLE))
    if x is None:
        return None
    c = ctx.closed_container(x)
    if c is None:
        return Expansion("grab", {"x": x}, [("WALK", (x,)), ("GRAB", (x,))])
    return Expansion("grab_open", {"x": x, "c": c},
                     [("WALK", (x,)), ("OPEN", (c,)), ("GRAB", (x,))])


def touch(ctx: _Context, last: bool) -> Expansion | None:
    x = ctx.pick([n.id for n in ctx.objects])
    return None if x is None else Expansion("touch", {"x": x},
                                            [("WALK", (x,)), ("TOUCH", (x,))])


def open_container(ctx: _Context, last: bool) -> Expansion | None:
    x = ctx.pick([i for i in ctx.with_property(CAN_OPEN) if "CLOSED" in ctx.state.states(i)])
    if x is None:
        return None
    if ctx.rng.random() < 0.4:
        return Expansion("open_close", {"x": x},
                         [("WALK", (x,)), ("OPEN", (x,)), ("CLOSE", (x,))])
    return Expansion("open", {"x": x}, [("WALK", (x,)), ("OPEN", (x,))])


def close_container(ctx: _Context, last: bool) -> Expansion | None:
    x = ctx.pick([i for i in ctx.with_property(CAN_OPEN) if "OPEN" in ctx.state.states(i)])
    return None if x is None else Expansion("close", {"x": x},
                                            [("WALK", (x,)), ("CLOSE", (x,))])


def _seated(ctx: _Context, kind: str, slots: dict[str, int], steps: list[StepSpec],
            last: bool) -> Expansion:
    # Seated, the agent cannot walk: stand up, or end the program here.
    if not last and ctx.rng.random() < 0.6:
        return Expansion(kind, slots, [*steps, ("STANDUP", ())])
    return Expansion(kind, slots, steps, ends_program=True)


def sit(ctx: _Context, last: bool) -> Expansion | None:
    x = ctx.pick(ctx.with_property(SITTABLE))
    if x is None:
        return None
    steps: list[StepSpec] = [("WALK", (x,)), ("SIT", (x,))]
    faced = [y for y in ctx.state.targets(x, FACING) if LOOKABLE in ctx.state.properties(y)]
    if faced and ctx.rng.random() < 0.6:
        y = ctx.rng.choice(sorted(faced))
        return _seated(ctx, "sit_look", {"x": x, "y": y}, [*steps, ("LOOKAT", (y,))], last)
    return _seated(ctx, "sit", {"x": x}, steps, last)


def watch(ctx: _Context, last: bool) -> Expansion | None:
    screens = [i for i in ctx.with_property(LOOKABLE)
               if HAS_SWITCH in ctx.state.properties(i) and "OFF" in ctx.state.states(i)]
    x = ctx.pick(screens)
    if x is None:
        return None
    seats = [s for s in ctx.with_property(SITTABLE) if x in ctx.state.targets(s, FACING)]
    y = ctx.pick(seats)
    if y is None:
        return None
    steps: list[StepSpec] = [("WALK", (x,)), ("SWITCHON", (x,)), ("WALK", (y,)),
                             ("SIT", (y,)), ("LOOKAT", (x,))]
    return _seated(ctx, "watch", {"x": x, "y": y}, steps, last)


TASKS: dict[str, tuple[float, Task]] = {
    "walk_room": (1.0, walk_room), "run_room": (0.4, run_room),
    "switch_on": (1.5, switch_on), "switch_off": (0.8, switch_off),
    "fetch": (2.0, fetch), "grab": (1.0, grab), "touch": (0.8, touch),
    "open": (1.0, open_container), "close": (0.3, close_container),
    "sit": (1.0, sit), "watch": (1.0, watch),
}
"""Task name -> (weight, expansion function): the grammar's choices for one task."""

STYLES: tuple[str, ...] = ("people", "templates")
"""Description styles: the paraphrase grammar (default), or the fixed templates."""

_TASK_COUNTS = (1, 2, 2, 3, 3, 4)
_TRIES_PER_TASK = 12
_STAND_UP_PHRASE = "stand_up"


class Grammar:
    """Draws programs over the animated actions in a set of homes.

    >>> import random
    >>> sp = Grammar().sample(random.Random(0), "synth-0-0")
    >>> from homesim.sim import execute
    >>> from homesim.world import load_home
    >>> execute(sp.program, load_home(sp.home), bindings=sp.bindings).executable
    True
    """

    def __init__(self, homes: tuple[str, ...] = DEFAULT_HOMES, style: str = "people"):
        if style not in STYLES:
            raise ValueError(f"description style {style!r}: choose one of {', '.join(STYLES)}")
        self.homes = homes
        self.style = style

    def sample(self, rng: random.Random, program_id: str) -> ActivityProgram:
        """One program; every random choice comes from `rng`."""
        while True:
            home = rng.choice(self.homes)
            ctx = _Context(_home(home), rng)
            chosen = self._expand(ctx, rng.choice(_TASK_COUNTS))
            if chosen:
                sp = _write(program_id, home, chosen, ctx, rng)
                if self.style == "templates":
                    return sp
                return _redescribe(sp, chosen, ctx)

    def _expand(self, ctx: _Context, n_tasks: int) -> list[Expansion]:
        names = list(TASKS)
        weights = [TASKS[n][0] for n in names]
        chosen: list[Expansion] = []
        for i in range(n_tasks):
            last = i == n_tasks - 1
            for _ in range(_TRIES_PER_TASK):
                name = ctx.rng.choices(names, weights)[0]
                exp = TASKS[name][1](ctx, last)
                if exp is not None and ctx.apply(exp.steps):
                    chosen.append(exp)
                    break
            else:
                break
            if chosen[-1].ends_program:
                break
        return chosen


def _write(program_id: str, home: str, chosen: list[Expansion], ctx: _Context,
           rng: random.Random) -> ActivityProgram:
    """The ungrounded program, its description and bindings from the chosen expansions."""
    instance: dict[int, tuple[str, int]] = {}
    counts: dict[str, int] = {}

    def ref(node: int) -> ObjectRef:
        if node not in instance:
            name = ctx.state.class_name(node)
            counts[name] = counts.get(name, 0) + 1
            instance[node] = (name, counts[name])
        return ObjectRef(*instance[node])

    steps: list[Step] = []
    phrases: list[str] = []
    for exp in chosen:
        for key, ids in exp.steps:
            steps.append(Step(ACTIONS[key], tuple(ref(i) for i in ids)))
        slots = {k: ctx.state.class_name(v) for k, v in exp.slots.items()}
        text = templates.phrase(exp.kind, rng, **slots)
        if exp.steps[-1][0] == "STANDUP":
            text += " " + templates.phrase(_STAND_UP_PHRASE, rng)
        phrases.append(text)
    first = chosen[0].kind
    title = next(t for k, t in templates.TITLES.items() if first.startswith(k))
    program = Program(tuple(steps), title, templates.join(phrases, rng))
    bindings = Bindings({key: node for node, key in instance.items()})
    return ActivityProgram(program_id, program, SOURCE, home=home, bindings=bindings)


def _redescribe(sp: ActivityProgram, chosen: list[Expansion], ctx: _Context
                ) -> ActivityProgram:
    """The program described by the paraphrase grammar (seeded by its id)."""
    graph = ctx.graph
    things = {i: Thing(i, graph.node(i).class_name, i in graph.room_ids, _where(graph, i))
              for exp in chosen for _, ids in exp.steps for i in ids}
    acts: list[Act] = [(key, tuple(things[i] for i in ids))
                       for exp in chosen for key, ids in exp.steps]
    text = describe(acts, random.Random(f"describe:{sp.id}"), sp.program.title).text
    return replace(sp, program=replace(sp.program, description=text))


def _where(graph: EnvironmentGraph, node: int) -> tuple[str, str] | None:
    """Where a node is in the home: on or in a piece of furniture, else in its room."""
    if node in graph.room_ids:
        return None
    for relation, preposition in ((ON, "on"), (INSIDE, "in")):
        holders = sorted(h for h in graph.targets(node, relation) - graph.room_ids
                         if graph.node(h).class_name not in _STRUCTURE)
        if holders:
            return preposition, graph.node(holders[0]).class_name
    room = graph.room_of(node)
    return None if room is None else ("in", graph.node(room).class_name)


def generate(n: int, seed: int, homes: tuple[str, ...] = DEFAULT_HOMES,
             style: str = "people") -> Iterator[ActivityProgram]:
    """`n` programs described in `style` (`STYLES`); the same seed gives the same
    programs, and the same programs in either style."""
    rng = random.Random(seed)
    grammar = Grammar(homes, style)
    for i in range(n):
        yield grammar.sample(rng, f"synth-{seed}-{i}")

