"""Execute a program on a home, step by step, and say why a step cannot run.

>>> from homesim.program import parse_program
>>> from homesim.world.graph import EnvironmentGraph
>>> g = EnvironmentGraph.from_dict({
...     "nodes": [{"id": 1, "class_name": "kitchen", "category": "Rooms"},
...               {"id": 2, "class_name": "character"},
...               {"id": 3, "class_name": "fridge", "properties": ["CAN_OPEN"],
...                "states": ["CLOSED"]},
...               {"id": 4, "class_name": "cup", "properties": ["GRABBABLE"]}],
...     "edges": [{"from_id": 2, "relation_type": "INSIDE", "to_id": 1},
...               {"from_id": 3, "relation_type": "INSIDE", "to_id": 1},
...               {"from_id": 4, "relation_type": "INSIDE", "to_id": 3}]})
>>> r = execute(parse_program("[Walk] <fridge> (1.3)\\n[Grab] <cup> (1.4)"), g)
>>> r.executable, r.message
(False, 'step 2 [Grab] <cup> (1.4): cup 4 is inside closed fridge 3')
>>> text = "[Walk] <fridge> (3)\\n[Open] <fridge> (3)\\n[Find] <cup> (4)\\n[Grab] <cup> (4)"
>>> r = execute(parse_program(text), g, reference=True)  # (N) read as node N
>>> r.executable, sorted(r.final_graph.node(3).states)
(True, ['OPEN'])

A program runs under one binding of its objects to nodes (`homesim.program.Bindings`):
the node ids its refs carry (``<cup> (1.4)``) or a `Bindings` map given beside it.
`execute` refuses a ref that names no node or a node of another class (`BindingError`),
unless ``reference=True`` asks for the reference simulator's reading of ``(N)`` as node N.
To run a program written for no particular home, use `homesim.run_program`, which
prepares the home and grounds the program first.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from homesim.errors import BindingError
from homesim.program.bindings import Bindings, unbound_error
from homesim.program.model import ObjectRef, Program, Step
from homesim.sim.effects import EFFECTS
from homesim.sim.failure import Failure, FailureKind
from homesim.sim.state import Changes, SimState
from homesim.world.classes import ClassKnowledge, class_names_for, default_kb
from homesim.world.graph import EnvironmentGraph


@dataclass(frozen=True, slots=True)
class StepRecord:
    """The outcome of one step in a trace.

    Attributes:
        index: 0-based position of the step in the program.
        step: the step.
        nodes: the node ids its objects were bound to.
        ok: whether it ran.
        reason: why it could not run (None when it ran).
        changes: what it changed (empty when it failed).
        kind: what kind of precondition failed (None when it ran).
    """

    index: int
    step: Step
    nodes: tuple[int, ...]
    ok: bool
    reason: str | None
    changes: Changes
    kind: FailureKind | None = None

    def to_dict(self, label: Callable[[int], str] | None = None,
                line: int | None = None) -> dict[str, Any]:
        """JSON view; ``summary`` is `Changes.describe` with `label` (or the reason)."""
        summary = self.reason
        if self.ok:
            summary = self.changes.describe(label or str)
        return {"index": self.index, "line": line, "step": str(self.step),
                "nodes": list(self.nodes), "ok": self.ok, "reason": self.reason,
                "kind": None if self.kind is None else self.kind.value,
                "changes": self.changes.to_dict(), "summary": summary}


@dataclass(eq=False)
class ExecutionResult:
    """What `execute` found.

    Attributes:
        program: the program executed.
        executable: True when every step ran.
        failed_index: 0-based index of the step that could not run, or None.
        reason: why that step could not run, or None.
        trace: one `StepRecord` per step attempted, when asked for; else None.
        state: the simulator state after the last step that ran.
        kind: what kind of precondition that step failed, or None.
    """

    program: Program
    executable: bool
    failed_index: int | None
    reason: str | None
    trace: list[StepRecord] | None
    state: SimState = field(repr=False)
    kind: FailureKind | None = None

    @property
    def failed_step(self) -> int | None:
        """1-based number of the failing step (as in `message`), or None."""
        return None if self.failed_index is None else self.failed_index + 1

    @property
    def message(self) -> str:
        """One line: ``step 4 [Grab] <cup> (12): cup 12 is inside closed fridge 9``."""
        if self.failed_index is None:
            return f"executable: all {len(self.program.steps)} steps ran"
        step = self.program.steps[self.failed_index]
        return f"step {self.failed_index + 1} {step}: {self.reason}"

    @property
    def steps_run(self) -> int:
        """How many steps ran."""
        return len(self.program.steps) if self.failed_index is None else self.failed_index

    @cached_property
    def final_graph(self) -> EnvironmentGraph:
        """The home after the last step that ran (built on first access)."""
        return self.state.to_graph()

    @cached_property
    def changes(self) -> Changes:
        """Net changes of the whole run against the input graph."""
        return self.state.changes_since(0)

    def to_dict(self, lines: Sequence[int | None] | None = None) -> dict[str, Any]:
        """JSON view: verdict, message, each attempted step and the steps not run.

        `lines` gives the text line of each step (``line`` fields are None without it).
        """
        def line(i: int | None) -> int | None:
            return None if lines is None or i is None else lines[i]

        label = self.state.label
        steps = [rec.to_dict(label, line(rec.index)) for rec in self.trace or []]
        done = len(steps)  # without a trace: the steps after the failed one are not run
        if self.trace is None:
            done = len(self.program.steps) if self.failed_index is None else self.failed_index + 1
        return {
            "program": str(self.program),
            "executable": self.executable,
            "failed_step": self.failed_step,
            "failed_line": line(self.failed_index),
            "reason": self.reason,
            "kind": None if self.kind is None else self.kind.value,
            "message": self.message,
            "steps": steps,
            "not_run": [{"index": i, "line": line(i), "step": str(self.program.steps[i])}
                        for i in range(done, len(self.program.steps))],
        }


def node_ids(step: Step, bindings: Bindings | None = None
             ) -> tuple[int, ...]:
    """The node ids a step's objects refer to, read as the reference simulator does.

    Without bindings a ref's node id is its grounded id (``(1.417)`` -> 417), else its
    instance number (``(417)`` -> 417); bindings, when given, win.
    """
    if bindings is None:
        return step.nodes
    return tuple([bindings.get(ref.key, ref.node) for ref in step.args])


def binding_problems(program: Program, graph: EnvironmentGraph,
                     bindings: Bindings | None = None,
                     kb: ClassKnowledge | None = None) -> list[BindingError]:
    """Every object ref of `program` that names no node of `graph`, or one of another class.

    A ref names the node `bindings` gives it, else its node id (``<tv> (1.410)``).
    Classes match as grounding matches them: by the knowledge base's equivalent names
    (``television`` and ``tv``, see `homesim.world.classes.class_names_for`).
    One error per object, at the first step that uses it, in step order.
    """
    def class_of(node: int) -> str | None:
        n = graph.nodes.get(node)
        return None if n is None else n.class_name

    return _problems(program, bindings or _NONE, class_of, kb, stop=False)


_NONE = Bindings()


def _problems(program: Program, given: Bindings,
              class_of: Callable[[int], str | None], kb: ClassKnowledge | None,
              stop: bool) -> list[BindingError]:
    problems: list[BindingError] = []
    first: dict[tuple[str, int], int | None] = {}  # each object's node at its first use
    for index, step in enumerate(program.steps):
        for ref in step.args:
            key = ref.key
            node = given.get(key, ref.node_id)
            if key in first:
                if first[key] == node:
                    continue
                problem = BindingError(
                    f"step {index + 1} {step}: <{ref.name}> ({ref.instance}) is node {node} "
                    f"here but node {first[key]} at an earlier step; one object is one node",
                    index + 1, f"<{ref.name}> ({ref.instance})", node)
            else:
                first[key] = node
                cls = None if node is None else class_of(node)
                if cls == ref.name:  # the common case, without the knowledge base
                    continue
                kb, names = _class_names(ref.name, kb)
                if cls is not None and cls in names:
                    continue
                problem = _ref_problem(index, step, ref, node, cls, names)
            problems.append(problem)
            if stop:
                return problems
    return problems


def _class_names(name: str, kb: ClassKnowledge | None
                 ) -> tuple[ClassKnowledge, list[str]]:
    """The knowledge base (the default one if None) and the home classes `name` may stand
    for. The simulator sits below the knowledge base; it asks through the protocol of
    `homesim.world.classes`, which the package's knowledge base answers."""
    kb = kb or default_kb()
    return kb, class_names_for(name, kb)


def _ref_problem(index: int, step: Step, ref: ObjectRef, node: int | None, cls: str | None,
                 names: list[str]) -> BindingError:
    if node is None:
        return unbound_error(index, step, ref)
    obj = f"<{ref.name}> ({ref.instance})"
    where = f"step {index + 1} {step}"
    if cls is None:
        return BindingError(f"{where}: the home has no node {node} for {obj}",
                            index + 1, obj, node)
    return BindingError(f"{where}: {obj} is node {node}, a {cls}, not a {' or '.join(names)}",
                        index + 1, obj, node)


def _missing(st: SimState, step: Step, ids: tuple[int, ...]) -> Failure | None:
    for ref, nid in zip(step.args, ids, strict=True):
        if nid not in st:
            return Failure(FailureKind.MISSING,
                           f"the home has no node {nid} for <{ref.name}> ({ref.instance})")
    return None


def run_step(st: SimState, step: Step, ids: tuple[int, ...]) -> Failure | None:
    """Run one step on `st`; return why it cannot run (a `Failure`: its kind and reason),
    leaving `st` as it was, or None."""
    return _missing(st, step, ids) or EFFECTS[step.action.key](st, *ids)


def execute(program: Program, graph: EnvironmentGraph, trace: bool = False,
            bindings: Bindings | None = None, *,
            reference: bool = False, kb: ClassKnowledge | None = None) -> ExecutionResult:
    """Execute `program` on `graph`; the graph is not changed.

    Args:
        program: the program: grounded (``<tv> (1.410)``), or bound by `bindings`.
        graph: the home.
        trace: record each step's outcome and changes (as deltas, not graph copies).
        bindings: program objects -> node ids (a `Bindings`, e.g. from grounding); they
            win over node ids the refs carry.
        reference: read the program as the reference simulator does: a ref without a
            node id names node N by its instance ``(N)``, and nothing is checked.
        kb: the knowledge base for equivalent class names (default: the package's,
            `homesim.world.classes.default_kb`).

    Returns:
        An `ExecutionResult`; `executable` is False at the first step whose preconditions
        fail, and `message` says which and why.

    Raises:
        BindingError: (unless `reference`) a ref names no node, a node the home lacks, or
            a node of another class (``<tv>`` bound to a bathroom).
    """
    st = SimState(graph)
    return execute_on(program, st, trace=trace, bindings=bindings, reference=reference, kb=kb)


def execute_on(program: Program, st: SimState, trace: bool = False,
               bindings: Bindings | None = None, *,
               reference: bool = False, kb: ClassKnowledge | None = None) -> ExecutionResult:
    """Like `execute`, but continue from an existing state (which it modifies)."""
    if not reference:
        base_nodes, new_nodes = st._base_nodes, st._new_nodes

        def class_of(node: int) -> str | None:
            n = new_nodes.get(node) or base_nodes.get(node)
            return None if n is None else n.class_name

        problems = _problems(program, bindings or _NONE, class_of, kb, stop=True)
        if problems:
            raise problems[0]
    records: list[StepRecord] | None = [] if trace else None
    journal = st.journal
    effects = EFFECTS
    base_nodes, new_nodes = st._base_nodes, st._new_nodes
    mark = 0
    for index, step in enumerate(program.steps):
        ids = step.nodes if bindings is None else node_ids(step, bindings)
        if records is not None:
            mark = len(journal)
        for nid in ids:
            if nid not in base_nodes and nid not in new_nodes:
                failure = _missing(st, step, ids)
                break
        else:
            failure = effects[step.action.key](st, *ids)
        if records is not None:
            if failure is None:
                records.append(StepRecord(index, step, ids, True, None, st.changes_since(mark)))
            else:
                records.append(StepRecord(index, step, ids, False, failure.reason, Changes(),
                                          failure.kind))
        if failure is not None:
            return ExecutionResult(program, False, index, failure.reason, records, st,
                                   failure.kind)
    return ExecutionResult(program, True, None, None, records, st)
