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
>>> r = execute(parse_program("[Walk] <fridge> (3)\\n[Grab] <cup> (4)"), g)
>>> r.executable, r.message
(False, 'step 2 [Grab] <cup> (4): cup 4 is inside closed fridge 3')
>>> text = "[Walk] <fridge> (3)\\n[Open] <fridge> (3)\\n[Find] <cup> (4)\\n[Grab] <cup> (4)"
>>> r = execute(parse_program(text), g)
>>> r.executable, sorted(r.final_graph.node(3).states)
(True, ['OPEN'])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property

from homesim.program.model import Program, Step
from homesim.sim.effects import EFFECTS
from homesim.sim.state import Changes, SimState
from homesim.world.graph import EnvironmentGraph

Bindings = Mapping[tuple[str, int], int]
"""Program object (class name, instance) -> node id of the home."""


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
    """

    index: int
    step: Step
    nodes: tuple[int, ...]
    ok: bool
    reason: str | None
    changes: Changes


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
    """

    program: Program
    executable: bool
    failed_index: int | None
    reason: str | None
    trace: list[StepRecord] | None
    state: SimState = field(repr=False)

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


def node_ids(step: Step, bindings: Bindings | None = None) -> tuple[int, ...]:
    """The node ids a step's objects refer to.

    Without bindings a ref's node id is its grounded id (``(1.417)`` -> 417), else its
    instance number, as the reference simulator reads ``(417)``.
    """
    if bindings is None:
        return step.nodes
    return tuple([bindings.get(ref.key, ref.node) for ref in step.args])


def _missing(st: SimState, step: Step, ids: tuple[int, ...]) -> str | None:
    for ref, nid in zip(step.args, ids, strict=True):
        if nid not in st:
            return f"the home has no node {nid} for <{ref.name}> ({ref.instance})"
    return None


def run_step(st: SimState, step: Step, ids: tuple[int, ...]) -> str | None:
    """Run one step on `st`; return why it cannot run (leaving `st` as it was) or None."""
    return _missing(st, step, ids) or EFFECTS[step.action.key](st, *ids)


def execute(program: Program, graph: EnvironmentGraph, trace: bool = False,
            bindings: Bindings | None = None) -> ExecutionResult:
    """Execute `program` on `graph`; the graph is not changed.

    Args:
        program: the program; its refs name nodes by id (see `node_ids`).
        graph: the home.
        trace: record each step's outcome and changes (as deltas, not graph copies).
        bindings: optional map from program objects to node ids (from grounding).

    Returns:
        An `ExecutionResult`; `executable` is False at the first step whose preconditions
        fail, and `message` says which and why.
    """
    st = SimState(graph)
    return execute_on(program, st, trace=trace, bindings=bindings)


def execute_on(program: Program, st: SimState, trace: bool = False,
               bindings: Bindings | None = None) -> ExecutionResult:
    """Like `execute`, but continue from an existing state (which it modifies)."""
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
                reason = _missing(st, step, ids)
                break
        else:
            reason = effects[step.action.key](st, *ids)
        if records is not None:
            changes = Changes() if reason else st.changes_since(mark)
            records.append(StepRecord(index, step, ids, reason is None, reason, changes))
        if reason is not None:
            return ExecutionResult(program, False, index, reason, records, st)
    return ExecutionResult(program, True, None, None, records, st)
