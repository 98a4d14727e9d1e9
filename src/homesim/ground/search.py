"""Grounding: bind a program's objects to instances of a home by backtracking search.

A program names objects by class and per-program instance (``<cup> (1)``, ``<cup> (2)``).
Grounding finds node ids for them under which every step executes:

- one node per program object, different nodes for different objects (all-different);
- candidates are the home's nodes of the object's class or of an equivalent class name
  (``television`` -> ``tv``), see `homesim.knowledge.kbtypes.class_names_for`;
- the search walks the program step by step on one `SimState`; a step's unbound objects
  are bound when it is reached, trying candidates in order of preference, and the step
  is run by the simulator (its preconditions prune); on failure the state is rolled back
  with `SimState.undo` (no graph is copied);
- preference keeps interactions together: first candidates related to objects already
  bound (close to them, on or in them, on the same surface: the keyboard of the chosen
  computer), then candidates in the character's room, then in rooms the program already
  uses, then (with geometry) the nearest, then a seeded random order;
- backjumping: a failed step blames the objects of the step and those the character is
  close to, faces, sits on or holds; choices of other objects are skipped over;
- with geometry, each interaction also needs free floor next to its object for the agent
  to stand on (`homesim.world.standing`); the chosen spots come with the result.

>>> from homesim.program import parse_program
>>> from homesim.world import load_home
>>> p = parse_program("[Walk] <television> (1)\\n[SwitchOn] <television> (1)")
>>> g = ground(p, load_home("scene1_trimmed"))
>>> str(g.program.steps[1])
'[SwitchOn] <television> (1.409)'
"""

from __future__ import annotations

import bisect
import difflib
import math
import random
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from homesim.errors import GroundingError
from homesim.ground.prepare import Prepared, first_use, instances_of, prepare
from homesim.knowledge.kbtypes import ObjectKnowledge, class_names_for, default_kb
from homesim.program.bindings import Bindings
from homesim.program.model import ObjectRef, Program, Step
from homesim.sim.execute import run_step
from homesim.sim.failure import Failure, FailureKind
from homesim.sim.state import SimState
from homesim.world.graph import EnvironmentGraph
from homesim.world.standing import FloorPlan, Spot, has_geometry
from homesim.world.vocab import CLOSE, FACING, HOLDS_LH, HOLDS_RH, INSIDE, ON

Key = tuple[str, int]

_NO_FAILURE = Failure(FailureKind.MISSING, "")
DEFAULT_BUDGET = 5000
"""Step runs the search may spend before it gives up (real programs need ~1.1 per step)."""


@dataclass(frozen=True)
class Grounding:
    """The result of `ground`.

    Attributes:
        program: the program with every object ref bound to a node (``<cup> (1.417)``).
        bindings: (class name, instance) -> node id: the same binding as a map.
        standing: step index (0-based) -> (x, z) where the agent stands for that step,
            when the home has geometry; else None. Steps that act on what the agent holds
            keep the previous spot.
        step_runs: how many steps the search ran (its effort).
    """

    program: Program
    bindings: Bindings
    standing: dict[int, Spot] | None
    step_runs: int

    def to_dict(self) -> dict[str, Any]:
        """JSON view: grounded program, bindings, standing spots ({"0": [x, z]}), effort."""
        standing = None
        if self.standing is not None:
            standing = {str(i): [round(x, 3), round(z, 3)]
                        for i, (x, z) in sorted(self.standing.items())}
        return {"program": str(self.program), "bindings": self.bindings.to_list(),
                "standing": standing, "step_runs": self.step_runs}


class _OutOfBudget(Exception):
    pass


class _Points:
    """Points in the floor plane, sorted by x, for the nearest one to a point.

    Speed: the search walks out from the point's x in both directions and stops where
    the x gap alone is over the best squared distance so far, so a program with many
    objects does not compare every pair. The result is the exact minimum of
    `square_distance` (a skipped point is strictly farther)."""

    def __init__(self, centers: list[tuple[float, float, float]]):
        self.points = sorted((c[0], c[2]) for c in centers)
        self.xs = [p[0] for p in self.points]

    def __bool__(self) -> bool:
        return bool(self.points)

    def nearest(self, center: tuple[float, float, float]) -> float:
        """The smallest squared (x, z) distance from `center` to a point."""
        x, z = center[0], center[2]
        points, xs, n = self.points, self.xs, len(self.points)
        best = math.inf
        right = bisect.bisect_left(xs, x)
        left = right - 1
        while left >= 0 or right < n:
            # The next point is the one with the smaller x gap, on either side.
            if left >= 0 and (right >= n or x - xs[left] <= xs[right] - x):
                i, left = left, left - 1
            else:
                i, right = right, right + 1
            dx, dz = x - points[i][0], z - points[i][1]
            if dx * dx > best:
                break  # every point left is at least as far in x alone
            d = dx * dx + dz * dz
            if d < best:
                best = d
        return best


class _Anchors:
    """Objects already chosen (or fixed), indexed by the surfaces they are on.

    Speed: a candidate's related anchors are a few set lookups, not a loop over every
    anchor, so a program with many objects (1000 cups) does not compare every pair."""

    def __init__(self, st: SimState, anchors: list[int]):
        self.weight = Counter(anchors)  # an anchor may come twice (two objects, one node)
        self.single = len(self.weight) == len(anchors)
        self.on_surface: dict[int, set[int]] = {}
        for b in self.weight:
            for surface in st.targets(b, ON):
                self.on_surface.setdefault(surface, set()).add(b)

    def __bool__(self) -> bool:
        return bool(self.weight)

    def count(self, near: frozenset[int] | set[int], under: frozenset[int] | set[int]) -> int:
        """How many anchors are in `near` or `under`, or on a surface in `under`."""
        hit = self.weight.keys() & (near | under)
        shared = [self.on_surface[s] for s in under if s in self.on_surface]
        if self.single and len(shared) == 1:  # the usual case, without copying the set
            return len(shared[0]) + sum(1 for b in hit if b not in shared[0])
        for anchors_there in shared:
            hit.update(anchors_there)
        return len(hit) if self.single else sum(self.weight[b] for b in hit)


@dataclass(slots=True)
class _Ran:
    """A step that ran; undone (to `mark`) when the steps after it fail."""

    mark: int


@dataclass(slots=True)
class _Choice:
    """Candidates for the first unbound object of step `step`; `pos` is the next one to
    try, `node` the one bound now, `blame` what the tries so far blamed."""

    step: int
    ref: ObjectRef
    candidates: list[int]
    pos: int = 0
    node: int = -1
    blame: set[Key] = field(default_factory=set)


class _Search:
    """One backtracking search; see the module docstring."""

    def __init__(self, program: Program, graph: EnvironmentGraph, seed: int,
                 kb: ObjectKnowledge, budget: int, geometry: bool):
        self.program = program
        self.steps = program.steps
        self.st = SimState(graph)
        self.graph = graph
        self.budget = budget
        self.runs = 0
        self.rng = random.Random(seed)
        self.tie: dict[int, float] = {}
        self.assign: dict[Key, int] = {}
        self.owner: dict[int, Key] = {}
        self.domains: dict[Key, list[int]] = {}
        self.tried: dict[Key, list[int]] = {}
        self.deepest: tuple[int, Failure] = (-1, _NO_FAILURE)
        self.deepest_bindings: dict[Key, int] = {}
        self.plan = FloorPlan.for_graph(graph, rotation=seed) if geometry else None
        self.needs: dict[Key, list[frozenset[str]]] = {}
        for step in program.steps:
            for pos, ref in enumerate(step.args):
                self.needs.setdefault(ref.key, []).extend(step.action.needs_of(pos))
        self.spots: list[Spot | None] = [None] * len(self.steps)
        for ref in program.object_refs():
            classes = class_names_for(ref.name, kb)
            ids = instances_of(graph, classes)
            if not ids:
                n, text = first_use(program, ref.key)
                raise GroundingError(
                    f"step {n} {text}: the home has no {' or '.join(classes)} for "
                    f"<{ref.name}> ({ref.instance}){_similar(ref.name, graph)}",
                    n, str(ref), ", ".join(classes), FailureKind.MISSING)
            self.domains[ref.key] = ids
        # Nodes that can only be one program object (often one scene preparation added
        # where the program needs it): candidates next to them are preferred too.
        self.fixed = [d[0] for d in self.domains.values() if len(d) == 1]

    # ------------------------------------------------------------------ search
    # The search is depth-first over steps and choices; it keeps its frames on an explicit
    # stack (not Python's), so a program of any length grounds without a recursion limit.
    # `_enter(i)` starts "solve steps i..": it returns the next step index to enter, or a
    # result (None: solved; a set: the objects to blame) for the frame on top of the stack.

    def solve(self) -> set[Key] | None:
        """Bind and run every step; None on success, else the objects to blame."""
        stack: list[_Ran | _Choice] = []
        action = self._enter(0, stack)
        while True:
            if isinstance(action, int):
                action = self._enter(action, stack)
            elif not stack:
                return action
            else:
                action = self._resume(stack.pop(), action, stack)

    def _enter(self, i: int, stack: list[_Ran | _Choice]) -> int | set[Key] | None:
        """Start solving steps i..: bind the step's first unbound object, or run it."""
        if i == len(self.steps):
            return None
        step = self.steps[i]
        for ref in step.args:
            if ref.key not in self.assign:
                self.tried.setdefault(ref.key, [])
                return self._next_choice(_Choice(i, ref, self.order(ref.key)), stack)
        ids = tuple([self.assign[ref.key] for ref in step.args])
        self.runs += 1
        if self.runs > self.budget:
            raise _OutOfBudget
        st = self.st
        mark = st.mark()
        if self.plan is None:
            reason = run_step(st, step, ids)
        else:
            held = set(st.targets(st.char, HOLDS_RH)) | set(st.targets(st.char, HOLDS_LH))
            reason = run_step(st, step, ids) or self.stand(i, ids, held)
        if reason is not None:
            if i > self.deepest[0]:
                self.deepest = (i, reason)
                self.deepest_bindings = dict(self.assign)
            st.undo(mark)
            return self.blame(step)
        stack.append(_Ran(mark))
        return i + 1

    def _resume(self, frame: _Ran | _Choice, result: set[Key] | None,
                stack: list[_Ran | _Choice]) -> int | set[Key] | None:
        """Hand the result of the steps after `frame` back to it."""
        if isinstance(frame, _Ran):
            if result is not None:
                self.st.undo(frame.mark)
            return result
        if result is None:
            return None
        key = frame.ref.key
        del self.assign[key]
        del self.owner[frame.node]
        if key not in result:
            return result  # backjump: this object's choice is not to blame
        frame.blame |= result
        return self._next_choice(frame, stack)

    def _next_choice(self, frame: _Choice, stack: list[_Ran | _Choice]) -> int | set[Key]:
        """Bind the frame's object to its next free candidate, or give up with the blame."""
        key = frame.ref.key
        tried = self.tried[key]
        while frame.pos < len(frame.candidates):
            node = frame.candidates[frame.pos]
            frame.pos += 1
            other = self.owner.get(node)
            if other is not None:
                frame.blame.add(other)
                continue
            if node not in tried:
                tried.append(node)
            self.assign[key] = node
            self.owner[node] = key
            frame.node = node
            stack.append(frame)
            return frame.step
        if self.owner.keys() >= set(self.domains[key]) and frame.step >= self.deepest[0]:
            taken = len(self.domains[key])
            self.deepest = (frame.step, Failure(
                FailureKind.MISSING, f"all {taken} instances of <{frame.ref.name}> in the "
                                     "home are bound to other objects of the program"))
        frame.blame.discard(key)
        return frame.blame

    def blame(self, step: Step) -> set[Key]:
        """The objects a failed step may depend on: its own and those the character is
        close to, faces, sits on or holds (where it went and what it did last)."""
        st, owner = self.st, self.owner
        keys = {ref.key for ref in step.args}
        c = st.char
        for rel in (CLOSE, FACING, ON, HOLDS_RH, HOLDS_LH):
            for x in st.targets(c, rel):
                k = owner.get(x)
                if k is not None:
                    keys.add(k)
        return keys

    # ------------------------------------------------------------------ preference
    def order(self, key: Key) -> list[int]:
        """Candidates for `key`, best first (see the module docstring); those lacking a
        property the program's steps need come last."""
        st = self.st
        bound = [n for n in self.assign.values() if n not in st.rooms]
        anchors = bound + [n for n in self.fixed if n not in self.owner and n not in st.rooms]
        rooms = (st.room_of(st.char), {st.room_of(n) for n in self.assign.values()})
        boxes = _Points([b.center for b in (self.graph.nodes[n].bounding_box for n in bound
                                            if n in self.graph.nodes) if b is not None])
        needs = self.needs.get(key, ())
        index = _Anchors(st, anchors)
        scored = [self._score(node, needs, index, rooms, boxes) for node in self.domains[key]]
        scored.sort()
        return [s[-1] for s in scored]

    def _score(self, node: int, needs: Sequence[frozenset[str]], anchors: _Anchors,
               rooms: tuple[int | None, set[int | None]], boxes: _Points
               ) -> tuple[int, int, int, float, float, int]:
        """The sort key of one candidate (lower is better)."""
        st = self.st
        props = st.properties(node)
        lacking = sum(1 for need in needs if props.isdisjoint(need))
        room = st.room_of(node)
        room_rank = 0 if room == rooms[0] else (1 if room in rooms[1] else 2)
        tie = self.tie.get(node)
        if tie is None:
            tie = self.tie[node] = self.rng.random()
        return (lacking, -self._related(node, anchors), room_rank,
                self._distance(node, boxes), tie, node)

    def _related(self, node: int, anchors: _Anchors) -> int:
        """How many anchors `node` is close to, on or in, or shares a surface with."""
        if not anchors:
            return 0
        st = self.st
        under = st.targets(node, ON) | st.targets(node, INSIDE)
        return anchors.count(st.targets(node, CLOSE), under)

    def _distance(self, node: int, boxes: _Points) -> float:
        """Squared floor distance from `node` to the nearest bound object (0 without)."""
        box = self.graph.nodes[node].bounding_box if node in self.graph.nodes else None
        if not boxes or box is None:
            return 0.0
        return boxes.nearest(box.center)

    # ------------------------------------------------------------------ standing
    def stand(self, i: int, ids: tuple[int, ...], holding_before: set[int]) -> Failure | None:
        """Choose where the agent stands for step i; a reason if there is no free floor."""
        previous = self.spots[i - 1] if i > 0 else None
        if not ids:
            self.spots[i] = previous
            return None
        target = ids[-1]
        st = self.st
        if (target in holding_before or target == st.char or target in st.body_parts
                or st.char in st.targets(target, ON)  # worn
                or self.graph.nodes[target].bounding_box is None):
            self.spots[i] = previous
            return None
        spot = self._spot(target)
        if spot is None:
            return Failure(FailureKind.UNREACHABLE, f"no free floor next to {st.label(target)} "
                                                    "for the agent to stand on")
        self.spots[i] = spot
        return None

    def _spot(self, node: int) -> Spot | None:
        """Free floor next to `node`, else next to what it is on or in (a cup in a
        cupboard: stand at the cupboard)."""
        plan = self.plan
        assert plan is not None
        g = self.graph
        seen = set()
        while node not in seen:
            seen.add(node)
            if node not in g.nodes or g.nodes[node].bounding_box is None:
                return None
            spot = plan.spot_near(node)
            if spot is not None:
                return spot
            holders = sorted((g.targets(node, ON) | g.targets(node, INSIDE)) - g.room_ids)
            if not holders:
                return None
            node = holders[0]
        return None


def _similar(name: str, graph: EnvironmentGraph) -> str:
    """``"; did you mean television?"``: the home's classes spelled like `name`, if any."""
    close = difflib.get_close_matches(name, sorted(graph.class_names()), n=3, cutoff=0.6)
    return f"; did you mean {' or '.join(close)}?" if close else ""


def ground(program: Program, graph: EnvironmentGraph, seed: int = 0,
           kb: ObjectKnowledge | None = None, budget: int = DEFAULT_BUDGET) -> Grounding:
    """Bind every object of `program` to a node of `graph` so that the program executes.

    Args:
        program: the program; node ids it may carry are ignored (use `unground` to see
            it as the search does).
        graph: the home, with every object the program needs (`prepare` adds missing
            ones; this search only binds what is there).
        seed: breaks ties between equally preferred candidates and picks standing spots.
        kb: the object knowledge base, for name equivalences (default: `load_kb()`).
        budget: how many step runs the search may spend.

    Returns:
        A `Grounding` (grounded program, bindings, standing spots with geometry).

    Raises:
        GroundingError: no assignment works (or the budget ran out); the message names
            the deepest step the search could not pass, why, and the instances it tried.
    """
    kb = kb or default_kb()
    if not program.steps:
        return Grounding(program, Bindings(), None, 0)
    geometry = has_geometry(graph)
    search = _Search(program, graph, seed, kb, budget, geometry)
    stopped = False
    try:
        result = search.solve()
    except _OutOfBudget:
        result, stopped = set(), True
    if result is not None:
        raise _failure(search, stopped)
    bindings = Bindings(search.assign)
    grounded = program.with_steps([
        Step(step.action, tuple(ref.ground(bindings[ref.key]) for ref in step.args))
        for step in program.steps])
    standing = None
    if geometry:
        standing = {i: s for i, s in enumerate(search.spots) if s is not None}
    return Grounding(grounded, bindings, standing, search.runs)


def _failure(search: _Search, stopped: bool) -> GroundingError:
    index, reason = search.deepest
    if index < 0:
        return GroundingError("no assignment of objects to instances was tried")
    step = search.steps[index]
    tried = []
    for ref in step.args:
        ids = search.tried.get(ref.key, [])
        label = search.graph.nodes[ids[0]].class_name if ids else ref.name
        shown = ", ".join(map(str, ids[:8])) + (", ..." if len(ids) > 8 else "")
        tried.append(f"<{ref.name}> ({ref.instance}) as {label} {shown}")
    tail = f" (search stopped after {search.runs} step runs)" if stopped else ""
    what = "; ".join(tried) or "no objects"
    obj = str(step.args[0]) if step.args else None
    error = GroundingError(f"step {index + 1} {step}: cannot be grounded: {reason}; "
                           f"tried {what}{tail}", index + 1, obj, what, reason.kind)
    error.bindings = Bindings(search.deepest_bindings)
    return error


def unground(program: Program) -> Program:
    """The program with node ids replaced by per-class counters, as a person writes it.

    Refs that named the same node get the same instance; instances count from 1 per
    class in order of first use.

    >>> from homesim.program import parse_program
    >>> p = parse_program("[Walk] <cup> (1.40)\\n[Walk] <cup> (1.12)\\n[Grab] <cup> (1.40)")
    >>> print(unground(p))
    [Walk] <cup> (1)
    [Walk] <cup> (2)
    [Grab] <cup> (1)
    """
    numbers: dict[tuple[str, int | tuple[int]], int] = {}
    counts: dict[str, int] = {}

    def renumber(ref: ObjectRef) -> ObjectRef:
        ident = (ref.name, ref.node_id if ref.node_id is not None else (ref.instance,))
        n = numbers.get(ident)
        if n is None:
            n = numbers[ident] = counts[ref.name] = counts.get(ref.name, 0) + 1
        return ObjectRef(ref.name, n)

    return program.with_steps([Step(s.action, tuple(renumber(r) for r in s.args))
                               for s in program.steps])


def prepare_and_ground(program: Program, graph: EnvironmentGraph, seed: int = 0,
                       kb: ObjectKnowledge | None = None, repairs: int = 4,
                       budget: int = DEFAULT_BUDGET) -> tuple[Prepared, Grounding]:
    """Prepare the home for `program`, then ground it; add instances when that fails.

    When grounding fails at a step because no instance of one of its objects can be used
    there (every phone of the home is far from the table the program grabs it at), a
    fresh instance of that object is added where the program needs it (next to the
    instances the search had chosen when it failed) and the search runs again, at most
    `repairs` times.

    Returns:
        (the preparation, the grounding in the prepared home).

    Raises:
        GroundingError: the last failure, when preparing or every attempt fails.
    """
    kb = kb or default_kb()
    extra: list[Key] = []
    pins = Bindings()
    rooms = {n.class_name for n in graph.rooms()}
    failure: GroundingError | None = None
    while True:
        try:
            prepared = prepare(program, graph, seed=seed, kb=kb, extra=extra, pins=pins)
        except GroundingError:
            if failure is None:
                raise
            raise failure from None  # the extra instance did not fit: report the search
        try:
            return prepared, ground(program, prepared.graph, seed=seed, kb=kb, budget=budget)
        except GroundingError as e:
            failure = failure or e
            if repairs <= 0 or not e.step:
                raise failure from None
            step = program.steps[e.step - 1]
            new = [ref.key for ref in step.args if ref.key not in extra
                   and not rooms.intersection(class_names_for(ref.name, kb))]
            if not new:
                raise failure from None
            extra += new
            # Put the new instances next to what the search had chosen when it failed.
            pins = Bindings({k: n for k, n in e.bindings.items() if n in graph})
            repairs -= 1
