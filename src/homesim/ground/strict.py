"""The strict run of a program in a home: prepare, ground, execute; nothing inserted.

`homesim.run_program` (`homesim.ground.pipeline`) starts with this run and repairs the
program when a step cannot run; repair's own trials (`homesim.ground.repair`) and
whoever needs the program's verdict as written (plan scoring, the learning reward) run
it strictly (`run_program(..., repair=False)`).

- An ungrounded program (``<cup> (1)``) is prepared for the home (objects it lacks are
  added, presupposed states set; `homesim.ground.prepare`) and grounded (each object bound
  to a node; `homesim.ground.search`), then executed in the prepared home.
- A grounded program (every ref carries a node id, ``<cup> (1.417)``) is checked (each
  ref names a node of the home of its class, equivalent names allowed) and executed as is.
  A partly grounded program counts as ungrounded: its node ids are ignored. So does a
  program without objects (``[StandUp]`` is prepared: the character starts seated).
- ``reference=True`` runs the program as the reference simulator does: no preparation or
  grounding, ``(N)`` read as node N, nothing checked.

Contract: a program that cannot run in the home is an answer, not an error. Grounding
failures and refused bindings give a `Run` with ``executable`` False, ``stage``
``"grounding"`` and the grounding's one-line message; a step whose preconditions fail
gives ``stage`` ``"execution"``. It raises only on a broken home (e.g. one without a
character: `ExecutionError`).

>>> from homesim.program import parse_program
>>> from homesim.world import load_home
>>> p = parse_program("[Walk] <dining_room> (1)\\n[Find] <wine_glass> (1)\\n"
...                   "[Grab] <wine_glass> (1)")
>>> run = run_strict(p, load_home("scene1_trimmed"))
>>> run.executable, run.message, [a.class_name for a in run.prepared.added]
(True, 'executable: all 3 steps ran', ['wine_glass'])
>>> run = run_strict(p, load_home("scene1_trimmed"), prepare=False)
>>> run.executable, run.stage, run.failed_step, run.kind.value
(False, 'grounding', 2, 'missing')
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from homesim.errors import BindingError, GroundingError
from homesim.ground.prepare import Prepared
from homesim.ground.search import Grounding, ground, prepare_and_ground
from homesim.knowledge.kbtypes import ObjectKnowledge, default_kb
from homesim.program.bindings import Bindings
from homesim.program.model import Program, Step
from homesim.program.parse import parse_program
from homesim.sim.execute import ExecutionResult, execute
from homesim.sim.failure import FailureKind
from homesim.world.graph import EnvironmentGraph

Stage = Literal["grounding", "execution"]


@dataclass(frozen=True, slots=True)
class Insertion:
    """One step repair inserted.

    Attributes:
        index: 0-based position of the step in the repaired program.
        step: the inserted step.
        reason: why it is needed, in words.
        before: 0-based index of the original step it precedes.
    """

    index: int
    step: Step
    reason: str
    before: int

    def to_dict(self) -> dict[str, Any]:
        return {"index": self.index, "step": str(self.step), "reason": self.reason,
                "before": self.before}


@dataclass(frozen=True, eq=False)
class Run:
    """What `run_program` did.

    Attributes:
        program: the program as given.
        executable: True when the program was grounded (or accepted) and every step ran.
        message: one line: ``executable: all 5 steps ran``, or where and why it failed.
        failed_step: 1-based number of the step that failed (grounding or execution);
            None when executable or when no step is to blame.
        stage: ``"grounding"`` or ``"execution"``: where it failed; None when executable.
        result: the execution (None when grounding failed, so nothing ran).
        prepared: what preparation added and set (None for grounded programs, without
            preparation, or when it failed).
        grounding: the grounded program, its bindings and standing spots (for a program
            that came grounded: itself, its bindings, no spots); None when it failed.
        graph: the home the program ran in (the prepared one when prepared).
        kind: what kind of precondition failed (`FailureKind`; ``missing`` for objects
            the home lacks); None when executable.
        insertions: the steps repair inserted, each with its reason (empty when the
            program ran as written, or when repair found no fix).
        strict: the run of the program as written, when repair changed it; else None.
    """

    program: Program
    executable: bool
    message: str
    failed_step: int | None
    stage: Stage | None
    result: ExecutionResult | None
    prepared: Prepared | None
    grounding: Grounding | None
    graph: EnvironmentGraph
    kind: FailureKind | None = None
    insertions: tuple[Insertion, ...] = ()
    strict: Run | None = None

    @property
    def bindings(self) -> Bindings | None:
        """Program objects -> node ids of `graph`, when grounded."""
        return None if self.grounding is None else self.grounding.bindings

    @property
    def repaired(self) -> Program | None:
        """The program that ran, with the inserted steps (ungrounded as given), or None."""
        return insert_steps(self.program, self.insertions) if self.insertions else None

    def to_dict(self, lines: Sequence[int | None] | None = None) -> dict[str, Any]:
        """JSON view, the one shape of ``homesim run --json`` and ``/api/execute``.

        The keys of `ExecutionResult.to_dict` (with no steps run when grounding failed),
        plus ``stage``, ``kind``, ``preparation`` (`Prepared.to_dict`), ``grounding``
        (`Grounding.to_dict`) and ``repair`` (None, or the repaired program, each
        inserted step with its reason and the verdict as written). `lines`: the text line
        of each step of `program`, for ``line`` fields (None for inserted steps).
        """
        if lines is not None and self.insertions:
            lines = _with_inserted(lines, self.insertions)
        if self.result is not None:
            data = self.result.to_dict(lines)
        else:
            index = None if self.failed_step is None else self.failed_step - 1
            data = {
                "program": str(self.program),
                "executable": False,
                "failed_step": self.failed_step,
                "failed_line": None if lines is None or index is None else lines[index],
                "reason": self.message,
                "kind": None if self.kind is None else self.kind.value,
                "message": self.message,
                "steps": [],
                "not_run": [{"index": i, "line": None if lines is None else lines[i],
                             "step": str(s)} for i, s in enumerate(self.program.steps)],
            }
        data["message"] = self.message
        data["stage"] = self.stage
        data["preparation"] = None if self.prepared is None else self.prepared.to_dict()
        data["grounding"] = None if self.grounding is None else self.grounding.to_dict()
        data["repair"] = None
        if self.strict is not None:
            data["repair"] = {
                "program": str(self.repaired), "insertions": [i.to_dict() for i in self.insertions],
                "executable_before": self.strict.executable,
                "message_before": self.strict.message}
        return data


def insert_steps(program: Program, insertions: Sequence[Insertion]) -> Program:
    """`program` with the inserted steps at their places."""
    steps = list(program.steps)
    for ins in insertions:
        steps.insert(ins.index, ins.step)
    return program.with_steps(steps)


def _with_inserted(lines: Sequence[int | None], insertions: Sequence[Insertion]
                   ) -> list[int | None]:
    """The line of each step of the repaired program: None for inserted steps."""
    out: list[int | None] = list(lines)
    for ins in insertions:
        out.insert(ins.index, None)
    return out


def as_inputs(program: Program | str, home: EnvironmentGraph | str
              ) -> tuple[Program, EnvironmentGraph]:
    """A program given as text parsed, and a home given by name loaded."""
    if isinstance(program, str):
        program = parse_program(program)
    if isinstance(home, str):
        from homesim.world.homes import load_home

        home = load_home(home)
    return program, home


def run_strict(program: Program | str, home: EnvironmentGraph | str, *,
               prepare: bool = True, seed: int = 0, trace: bool = False,
               kb: ObjectKnowledge | None = None, reference: bool = False) -> Run:
    """Run `program` in `home` as written: prepare and ground it when it is not grounded,
    execute it.

    Args:
        program: a `Program` or program text.
        home: an environment graph or the name of a built-in home.
        prepare: add the objects the program needs and the home lacks, and set the states
            it presupposes, before grounding (and retry with extra instances where
            grounding fails, see `prepare_and_ground`). Without it, only ground.
        seed: seed of preparation and grounding (same seed, same run).
        trace: record each step's outcome and changes in ``result.trace``.
        kb: the object knowledge base (default: `homesim.knowledge.load_kb()`).
        reference: run as the reference simulator does, ``(N)`` read as node N.

    Returns:
        A `Run`; see the module docstring for what fails how.
    """
    program, home = as_inputs(program, home)
    if reference:
        result = execute(program, home, trace=trace, reference=True)
        return _finished(program, result, None, None, home)
    kb = kb or default_kb()
    prepared: Prepared | None = None
    graph = home
    try:
        prepared, grounding = _ground(program, home, prepare, seed, kb)
        if prepared is not None:
            graph = prepared.graph
        result = execute(grounding.program, graph, trace=trace, kb=kb)
    except (GroundingError, BindingError) as e:
        return _failed(program, e, e.step or None, graph)
    return _finished(program, result, prepared, grounding, graph)


def runs(program: Program, home: EnvironmentGraph, *, prepare: bool = True, seed: int = 0,
         kb: ObjectKnowledge | None = None) -> bool:
    """``run_strict(program, home, ...).executable``, for a program that is not grounded,
    without the final execution (grounding's search has run every step already): the
    check constrained decoding makes for each candidate step."""
    if _grounded(program):
        return run_strict(program, home, prepare=prepare, seed=seed, kb=kb).executable
    try:
        _ground(program, home, prepare, seed, kb or default_kb())
    except GroundingError:
        return False
    return True


def _ground(program: Program, home: EnvironmentGraph, prepare: bool, seed: int,
            kb: ObjectKnowledge) -> tuple[Prepared | None, Grounding]:
    """Preparation (if asked) and grounding; a grounded program is taken as it is."""
    if _grounded(program):
        return None, Grounding(program, Bindings.of(program), None, 0)
    if prepare:
        return prepare_and_ground(program, home, seed=seed, kb=kb)
    return None, ground(program, home, seed=seed, kb=kb)


def _grounded(program: Program) -> bool:
    # A program without objects (``[StandUp]``) is prepared too: it may presuppose states.
    return program.is_grounded and any(step.args for step in program.steps)


def _finished(program: Program, result: ExecutionResult, prepared: Prepared | None,
              grounding: Grounding | None, graph: EnvironmentGraph) -> Run:
    return Run(program, result.executable, result.message, result.failed_step,
               None if result.executable else "execution", result, prepared, grounding, graph,
               result.kind)


def _failed(program: Program, error: GroundingError | BindingError, step: int | None,
            graph: EnvironmentGraph) -> Run:
    message = " ".join(str(error).split())  # one line, whatever the error held
    kind = FailureKind.MISSING
    if isinstance(error, GroundingError) and error.kind is not None:
        kind = FailureKind(error.kind)
    return Run(program, False, message, step, "grounding", None, None, None, graph, kind)
