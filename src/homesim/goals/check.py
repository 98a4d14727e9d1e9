"""Check goals on an execution trace.

A `Trajectory` is the states a run went through: ``s_0`` (the home before the first step)
to ``s_n`` (after the n-th step that ran), with the action of each step between them.

Formulas (`homesim.goals.formula`) are judged on a segment ``[i, j]`` of it; the whole run
satisfies a formula when the segment ``[0, n]`` does:

- a state or relation atom holds on ``[i, j]`` when it holds in ``s_j`` (where it ends);
- an action atom holds when one of the steps ``i+1 .. j`` is that action on that object;
- ``A then B`` holds when some ``k`` in ``[i, j]`` has A on ``[i, k]`` and B on ``[k, j]``;
- ``exists``/``forall``/``forn`` range over the home's nodes (``exists`` and ``forn`` over
  the nodes the run acted on when the variable appears only in action atoms: no other node
  can satisfy them).

A `GoalSet` is EAI's flat form of the same goals: node states and relations that must hold
at the end, and actions that must have been done in the given order.
"""

from __future__ import annotations

from bisect import bisect_right
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from homesim.goals.formula import RELATION_PREDICATES, Arg, Atom, Formula, Not, Quantified
from homesim.program.actions import lookup_action
from homesim.sim.execute import StepRecord
from homesim.sim.state import SimState
from homesim.world.graph import EnvironmentGraph


class Trajectory:
    """The states and actions of a run: `initial` plus the steps of `records` that ran."""

    def __init__(self, initial: EnvironmentGraph, records: Iterable[StepRecord]):
        self.initial = initial
        self._start = SimState(initial)  # read only: the states and edges of s_0
        self.steps = [r for r in records if r.ok]
        self.length = len(self.steps)
        # Timelines: node -> ([t...], [states after t...]); edge -> ([t...], [present...]),
        # so a fact at time t is one bisect, without building any state.
        self._states: dict[int, tuple[list[int], list[frozenset[str]]]] = {}
        self._edges: dict[tuple[int, str, int], tuple[list[int], list[bool]]] = {}
        for t, record in enumerate(self.steps, start=1):
            changes = record.changes
            for node, _, after in changes.states:
                times, values = self._states.setdefault(node, ([], []))
                times.append(t)
                values.append(after)
            for present, edges in ((True, changes.added), (False, changes.removed)):
                for edge in edges:
                    times, flags = self._edges.setdefault(edge, ([], []))
                    times.append(t)
                    flags.append(present)

    def has_state(self, node: int, state: str, t: int) -> bool:
        """Whether `node` has `state` in ``s_t``."""
        line = self._states.get(node)
        if line is not None:
            k = bisect_right(line[0], t)
            if k:
                return state in line[1][k - 1]
        return node in self._start and state in self._start.states(node)

    def has_edge(self, a: int, relation: str, b: int, t: int) -> bool:
        """Whether the edge ``a relation b`` is in ``s_t``."""
        line = self._edges.get((a, relation, b))
        if line is not None:
            k = bisect_right(line[0], t)
            if k:
                return line[1][k - 1]
        return a in self._start and b in self._start and self._start.has_edge(a, relation, b)

    def acted(self, key: str, node: int | None, t: int) -> bool:
        """Whether step t (1-based) is action `key` (on `node`, when given)."""
        step = self.steps[t - 1]
        if step.step.action.key != key:
            return False
        return node is None or (bool(step.nodes) and step.nodes[0] == node)

    def name(self, node: int) -> str:
        """``class.id`` of a node (``?.id`` when the home lacks it)."""
        cls = self._start.class_name(node) if node in self._start else "?"
        return f"{cls}.{node}"

    def node_ids(self) -> list[int]:
        """Every node of the home (and nodes the run added)."""
        added = [n for r in self.steps for n in r.changes.nodes]
        return [*self.initial.nodes, *added]

    def acted_on(self) -> list[int]:
        """The nodes some step acted on, in first-use order."""
        return list(dict.fromkeys(n for r in self.steps for n in r.nodes))


def holds(formula: Formula, trajectory: Trajectory) -> bool:
    """Whether the run satisfies `formula` (on the whole trajectory)."""
    return _Judge(trajectory).holds(formula, 0, trajectory.length, ())


class _Judge:
    """Evaluates formulas on segments, memoised per (formula, segment, bindings)."""

    def __init__(self, trajectory: Trajectory):
        self.tr = trajectory
        self.holds = lru_cache(maxsize=None)(self._holds)

    def _holds(self, f: Formula, i: int, j: int, env: tuple[tuple[str, int], ...]) -> bool:
        if isinstance(f, Atom):
            return self._atom(f, i, j, dict(env))
        if isinstance(f, Not):
            return not self.holds(f.body, i, j, env)
        if isinstance(f, Quantified):
            return self._quantified(f, i, j, env)
        if f.op == "and":
            return all(self.holds(p, i, j, env) for p in f.parts)
        if f.op == "or":
            return any(self.holds(p, i, j, env) for p in f.parts)
        return self._then(f.parts, i, j, env)

    def _then(self, parts: tuple[Formula, ...], i: int, j: int,
              env: tuple[tuple[str, int], ...]) -> bool:
        # Forward over the parts: the set of times where the parts so far can end
        # (parts x segment² checks at most, and no recursion per part).
        ends = {i}
        for part in parts[:-1]:
            ends = {k for k in range(min(ends), j + 1)
                    if any(s <= k and self.holds(part, s, k, env) for s in ends)}
            if not ends:
                return False
        return any(self.holds(parts[-1], s, j, env) for s in ends)

    def _quantified(self, f: Quantified, i: int, j: int,
                    env: tuple[tuple[str, int], ...]) -> bool:
        narrow = f.quantifier != "forall" and _only_in_actions(f.body, f.var)
        domain = self.tr.acted_on() if narrow else self.tr.node_ids()
        found = 0
        for node in domain:
            if self.holds(f.body, i, j, (*env, (f.var, node))):
                found += 1
                if f.quantifier != "forall" and found >= f.count:
                    return True
            elif f.quantifier == "forall":
                return False
        return f.quantifier == "forall"

    def _atom(self, a: Atom, i: int, j: int, env: dict[str, int]) -> bool:
        nodes = [_node(arg, env) for arg in a.args]
        if a.kind == "state":
            return self.tr.has_state(nodes[0], a.predicate, j)
        if a.kind == "relation":
            relation = RELATION_PREDICATES[a.predicate]
            return self.tr.has_edge(nodes[0], relation, nodes[1], j)
        action = lookup_action(a.predicate)
        key = action.key if action is not None else a.predicate
        node = nodes[0] if nodes else None
        return any(self.tr.acted(key, node, t) for t in range(i + 1, j + 1))


def _node(arg: Arg, env: dict[str, int]) -> int:
    return arg.node if arg.node is not None else env[arg.name]


def _only_in_actions(f: Formula, var: str) -> bool:
    """Whether every atom mentioning `var` in `f` is an action atom."""
    if isinstance(f, Atom):
        return f.kind == "action" or all(a.name != var or a.node is not None for a in f.args)
    if isinstance(f, Not | Quantified):
        return _only_in_actions(f.body, var)
    return all(_only_in_actions(p, var) for p in f.parts)


@dataclass(frozen=True)
class GoalSet:
    """EAI's flat goals: node states and relations at the end, actions in order.

    Attributes:
        states: (node id, class name, state) that must hold at the end.
        relations: (from id, relation, to id) edges that must be in the final graph.
        actions: action goals in order, each a set of alternatives (``"LOOKAT|WATCH"``).
    """

    states: tuple[tuple[int, str, str], ...] = ()
    relations: tuple[tuple[int, str, int], ...] = ()
    actions: tuple[tuple[str, ...], ...] = ()

    @property
    def size(self) -> int:
        """How many goals."""
        return len(self.states) + len(self.relations) + len(self.actions)

    def to_dict(self) -> dict[str, Any]:
        """JSON view in EAI's ``vh_goal`` shape."""
        goal: list[dict[str, Any]] = [
            {"id": n, "class_name": c, "state": s} for n, c, s in self.states]
        goal += [{"from_id": a, "relation_type": r, "to_id": b} for a, r, b in self.relations]
        return {"actions": ["|".join(alts) for alts in self.actions], "goal": goal}


@dataclass(frozen=True)
class GoalReport:
    """Which goals of a `GoalSet` a run met; `success` when all of them."""

    met: tuple[str, ...] = ()
    unmet: tuple[str, ...] = ()
    counts: dict[str, tuple[int, int]] = field(default_factory=dict)

    @property
    def success(self) -> bool:
        """Every goal met."""
        return not self.unmet

    def to_dict(self) -> dict[str, Any]:
        """JSON view."""
        return {"success": self.success, "met": list(self.met), "unmet": list(self.unmet),
                "counts": {k: {"met": m, "total": n} for k, (m, n) in self.counts.items()}}


def check_goals(goals: GoalSet, trajectory: Trajectory) -> GoalReport:
    """Judge `goals` on the end of `trajectory` (states, relations) and its actions."""
    end = trajectory.length
    met: list[str] = []
    unmet: list[str] = []
    counts = {}
    done = 0
    for node, cls, state in goals.states:
        ok = trajectory.has_state(node, state, end)
        (met if ok else unmet).append(f"{state}({cls}.{node})")
        done += ok
    counts["state"] = (done, len(goals.states))
    done = 0
    for a, relation, b in goals.relations:
        ok = trajectory.has_edge(a, relation, b, end)
        (met if ok else unmet).append(
            f"{relation}({trajectory.name(a)}, {trajectory.name(b)})")
        done += ok
    counts["relation"] = (done, len(goals.relations))
    done = _ordered_actions(goals.actions, trajectory.steps)
    for k, alts in enumerate(goals.actions):
        (met if k < done else unmet).append("|".join(alts))
    counts["action"] = (done, len(goals.actions))
    return GoalReport(tuple(met), tuple(unmet), counts)


def _action_key(name: str) -> str:
    """The catalog key of an action name, or the name itself when the catalog lacks it."""
    spec = lookup_action(name)
    return name if spec is None else spec.key


def _ordered_actions(goals: Sequence[tuple[str, ...]], steps: Sequence[StepRecord]) -> int:
    """How many action goals, in order, the steps meet (each by a later step than the last)."""
    done, t = 0, 0
    keys = [s.step.action.key for s in steps]
    for alts in goals:
        wanted = {_action_key(a) for a in alts}
        while t < len(keys) and keys[t] not in wanted:
            t += 1
        if t == len(keys):
            break
        done += 1
        t += 1
    return done
