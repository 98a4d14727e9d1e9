"""Score plans written in EAI's action-sequencing output format.

A plan is the text an LLM answered for one program, a JSON object whose keys are actions
and whose values list ``name, id`` pairs, keys repeated as needed and kept in order::

    {"WALK": ["dining_room", "201"], "FIND": ["soap", "1002"], "GRAB": ["soap", "1002"],
     "PUTBACK": ["soap", "1002", "washing_machine", "1001"]}

`score_plan` judges it as EAI's evaluator does, in stages, each over the whole plan, and
stops at the first that fails: ``format`` (not such an object, or empty, an odd list,
nested deeper than `MAX_PLAN_DEPTH`, over `MAX_PLAN_STEPS` steps), ``hallucination`` (an
action homesim does not know in any step, then an object that is not one of the task's
objects in any step: those whose state or relations differ between the program's initial
and final graphs, as EAI defines them), ``arity`` (wrong number of objects), then
execution through `homesim.run_program` in the program's initial graph, as written (not
prepared, not repaired). A step that fails at run time is classified with EAI's error
kinds from the simulator's `FailureKind`:

- ``additional_step`` (kind ``already``): it would do what is already done (open the
  open, switch on the on, sit while sitting), or grab what is held, or (not in
  ``strict_eai``) repeat a step that already ran and now fails; the step is skipped and
  the plan goes on, as in EAI;
- ``affordance`` (kind ``affordance``): the object cannot take the action (not
  GRABBABLE, no switch, a room to wash, ...);
- ``wrong_order``: any other kind, where the step could have run in an earlier state of
  this run;
- ``missing_step``: any other kind (not close, not holding, inside a closed container).

``strict_eai`` gives EAI's verdict where EAI is lenient or strict by choice: EAI's plan
reader (each ``"KEY": [...]`` pair on its own: a trailing comma or a missing ``}`` pass,
empty lists are dropped), its action table (`EAI_ACTIONS`: no aliases such as PUT), ids
matched as text, a repeated step that fails is judged like any other (EAI: wrong order),
and additional steps counted per step in the summary. docs/goals.md lists each difference.

Task success: every goal of the program (`homesim.goals.eai`) holds on the run's trace.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from homesim.errors import DataError, HomesimError
from homesim.goals.check import GoalReport, Trajectory, check_goals
from homesim.goals.contexts import TaskContext, load_contexts
from homesim.ground.pipeline import Run, run_program
from homesim.limits import EXCERPT_CHARS, MAX_ID_DIGITS, MAX_PLAN_DEPTH, MAX_PLAN_STEPS, deeper_than
from homesim.program.actions import ActionSpec, lookup_action
from homesim.program.model import Program
from homesim.program.parse import parse_program
from homesim.sim.failure import FailureKind
from homesim.world.graph import EnvironmentGraph

__all__ = ["PlanReport", "PlanScore", "TaskContext", "load_contexts", "parse_plan",
           "score_plan", "score_plans"]

GRAMMAR_KINDS = ("format", "hallucination", "arity")
RUNTIME_KINDS = ("wrong_order", "missing_step", "affordance", "additional_step")

# EAI's run-time kind of each simulator failure kind; any other is a missing step (or a
# wrong order, when the step could run earlier).
_EAI_KIND = {FailureKind.ALREADY: "additional_step", FailureKind.AFFORDANCE: "affordance"}


@dataclass
class PlanScore:
    """The verdict on one plan.

    Attributes:
        identifier: EAI's program id (``27_2``).
        task: the task title.
        error: None, or one of `GRAMMAR_KINDS` and `RUNTIME_KINDS` (the first that stopped
            the plan; ``additional_step`` only when nothing else went wrong).
        reason: one line on why (homesim's step-level reason for run-time errors).
        failed_step: 1-based number of the plan step that failed, if any.
        additional: 1-based numbers of the plan's steps skipped as additional.
        executable: every step ran (skipped additional steps allowed).
        goals: the goal report (None when the plan never ran).
        steps: the plan as homesim program lines.
        totals: how many goals of each kind (state, relation, action) the task has.
    """

    identifier: str
    task: str
    error: str | None = None
    reason: str | None = None
    failed_step: int | None = None
    additional: list[int] = field(default_factory=list)
    executable: bool = False
    goals: GoalReport | None = None
    steps: list[str] = field(default_factory=list)
    totals: dict[str, int] = field(default_factory=dict)

    @property
    def success(self) -> bool:
        """Every goal met."""
        return self.goals is not None and self.goals.success

    def to_dict(self) -> dict[str, Any]:
        """JSON view (one entry of the per-plan report)."""
        return {"identifier": self.identifier, "task": self.task, "error": self.error,
                "reason": self.reason, "failed_step": self.failed_step,
                "additional_steps": self.additional, "executable": self.executable,
                "success": self.success,
                "goals": None if self.goals is None else self.goals.to_dict(),
                "steps": self.steps}


class _Reject(Exception):
    """A plan stopped before execution: (kind, reason)."""

    def __init__(self, kind: str, reason: str):
        self.kind = kind
        super().__init__(reason)


EAI_ACTIONS = frozenset({
    "DRINK", "EAT", "CUT", "TOUCH", "LOOKAT", "LOOKAT_SHORT", "LOOKAT_MEDIUM", "LOOKAT_LONG",
    "WATCH", "READ", "TYPE", "PUSH", "PULL", "MOVE", "SQUEEZE", "SLEEP", "WAKEUP", "RINSE",
    "SCRUB", "WASH", "GRAB", "SWITCHOFF", "SWITCHON", "CLOSE", "FIND", "WALK", "OPEN",
    "POINTAT", "PUTBACK", "PUTIN", "PUTOBJBACK", "RUN", "SIT", "STANDUP", "TURNTO", "WIPE",
    "PUTON", "PUTOFF", "GREET", "DROP", "LIE", "POUR"})
"""The action names EAI 1.0.5's hallucination check accepts (its ``valid_actions``);
``--strict-eai`` accepts only these (homesim's catalog also knows PLUGIN, PLUGOUT, RELEASE
and aliases such as PUT)."""

# EAI's plan reader: each ``"KEY": [...]`` pair with a non-empty list, wherever it stands.
_EAI_PAIR = re.compile(r'"(\w+)"\s*:\s*(\[[^\]]+\])')

Pairs = list[tuple[str, list[Any]]]


def parse_plan(text: str, strict_eai: bool = False) -> Pairs:
    """The (action, params) pairs of a plan text, in order; `_Reject` ``format`` if bad.

    By default the plan must be one JSON object (in a code fence or amid prose); with
    `strict_eai`, EAI's reader: every ``"KEY": [values]`` pair found in the text, each
    list parsed alone (so a trailing comma or a missing ``}`` passes, and empty lists and
    keys that are not one word are dropped). Either way a plan nested deeper than
    `MAX_PLAN_DEPTH` or longer than `MAX_PLAN_STEPS` steps is a format error.
    """
    if not isinstance(text, str):
        raise _Reject("format", "the plan is not text")
    pairs = _eai_pairs(text) if strict_eai else _json_pairs(text)
    if not pairs:
        raise _Reject("format", "the plan has no steps")
    if len(pairs) > MAX_PLAN_STEPS:
        raise _Reject("format", f"the plan has {len(pairs)} steps, over the limit of "
                                f"{MAX_PLAN_STEPS} (MAX_PLAN_STEPS)")
    for action, params in pairs:
        if not isinstance(params, list) or len(params) % 2:
            raise _Reject("format", f"{_excerpt(action)}: the value must list name, id pairs")
    return pairs


def _json_pairs(text: str) -> Pairs:
    body = text.strip()
    if body.startswith("```"):
        body = body.split("\n", 1)[1] if "\n" in body else body[3:]
        body = body.removeprefix("json").rsplit("```", 1)[0]
    start, end = body.find("{"), body.rfind("}")
    if start < 0 or end < start:
        raise _Reject("format", "no JSON object in the plan")
    pairs = _loads(body[start:end + 1].replace("'", '"'), object_pairs_hook=_pair_lists)
    if not isinstance(pairs, list):
        raise _Reject("format", "the plan is not a JSON object")
    return [(key, value) for key, value in pairs]


def _pair_lists(pairs: list[tuple[str, Any]]) -> list[list[Any]]:
    # An object as its [key, value] pairs, in order (keys repeat), as lists so that
    # `deeper_than` sees their depth.
    return [list(pair) for pair in pairs]


def _eai_pairs(text: str) -> Pairs:
    body = text[7:] if text.startswith("```json") else text
    body = body.strip().replace("\n", "").replace("'", '"')
    return [(key, _loads(value)) for key, value in _EAI_PAIR.findall(body)]


def _loads(text: str, **kwargs: Any) -> Any:
    """JSON of a plan; `_Reject` ``format`` when it is not JSON or nests too deep."""
    try:
        value = json.loads(text, **kwargs)
    except RecursionError:  # nested past the parser's own depth
        raise _Reject("format", f"nested deeper than {MAX_PLAN_DEPTH} levels "
                                "(MAX_PLAN_DEPTH)") from None
    except ValueError as e:
        raise _Reject("format", f"not JSON: {e}") from None
    if deeper_than(value, MAX_PLAN_DEPTH):
        raise _Reject("format", f"nested deeper than {MAX_PLAN_DEPTH} levels (MAX_PLAN_DEPTH)")
    return value


def _excerpt(value: object) -> str:
    text = str(value)
    return text if len(text) <= EXCERPT_CHARS else text[:EXCERPT_CHARS] + "..."


def _steps(pairs: Pairs, context: TaskContext, strict_eai: bool) -> list[str]:
    """Program lines of a parsed plan; `_Reject` for hallucination or arity errors.

    EAI's order, over the whole plan at each stage: every action is known, then every
    object is one of the task's, then every step has its number of objects."""
    actions = [_action(k, name, strict_eai) for k, (name, _) in enumerate(pairs, start=1)]
    refs: list[list[str]] = []
    instances: dict[tuple[str, int], int] = {}  # (name, node) -> instance number
    per_name: dict[str, int] = {}
    for k, (action, (_, params)) in enumerate(zip(actions, pairs, strict=True), start=1):
        step_refs = []
        for name, node in zip(params[::2], params[1::2], strict=True):
            key = (str(name), _node_id(node, strict_eai))
            if key not in context.objects:
                raise _Reject("hallucination", f"step {k} [{action.key}]: {_excerpt(name)} "
                                               f"{_excerpt(node)} is not an object of this task")
            if key not in instances:
                per_name[key[0]] = instances[key] = per_name.get(key[0], 0) + 1
            step_refs.append(f"<{key[0]}> ({instances[key]}.{key[1]})")
        refs.append(step_refs)
    for k, (action, step_refs) in enumerate(zip(actions, refs, strict=True), start=1):
        if len(step_refs) != action.arity:
            raise _Reject("arity", f"step {k} [{action.key}]: takes {action.arity} "
                                   f"object(s), not {len(step_refs)}")
    return [" ".join([f"[{a.key}]", *r]) for a, r in zip(actions, refs, strict=True)]


def _action(k: int, name: object, strict_eai: bool) -> ActionSpec:
    """The catalog action a plan step names; `_Reject` ``hallucination`` if none (with
    `strict_eai`, also when EAI's table lacks the name)."""
    text = str(name)
    action = lookup_action(text)
    if action is None or (strict_eai and text.upper() not in EAI_ACTIONS):
        raise _Reject("hallucination", f"step {k}: unknown action {_excerpt(text)!r}"
                      + (" (not in EAI's action table)" if action is not None else ""))
    return action


def _node_id(node: object, strict_eai: bool) -> int:
    """The node id a plan names (-1: none); EAI matches the id's text exactly (``"014"``
    is not 14), homesim reads the number."""
    text = str(node)
    if not text.isdigit() or len(text) > MAX_ID_DIGITS or (strict_eai and text != str(int(text))):
        return -1  # names no node: a hallucination
    return int(text)


def score_plan(identifier: str, text: str, context: TaskContext, *,
               strict_eai: bool = False) -> PlanScore:
    """Judge one plan text for the program of `context` (see the module docstring);
    `strict_eai`: EAI's verdict where EAI is lenient or strict by choice (docs/goals.md)."""
    goals = context.goals.goals
    score = PlanScore(identifier, context.goals.task, totals={
        "state": len(goals.states), "relation": len(goals.relations),
        "action": len(goals.actions)})
    try:
        score.steps = _steps(parse_plan(text, strict_eai), context, strict_eai)
    except _Reject as e:
        score.error, score.reason = e.kind, str(e)
        return score
    _execute(score, context, strict_eai)
    return score


def _execute(score: PlanScore, context: TaskContext, strict_eai: bool) -> None:
    """Run the plan, skipping additional steps; fill in error, reason, goals."""
    try:
        program = parse_program("\n".join(score.steps))
    except HomesimError as e:  # e.g. a class name the parser refuses
        score.error, score.reason = "hallucination", " ".join(str(e).split())
        return
    kept = list(range(len(program.steps)))
    while True:
        run = _run(program.with_steps([program.steps[i] for i in kept]), context.home,
                   trace=True)
        again = _regrab(run)
        if again is not None:
            score.additional.append(kept.pop(again) + 1)
            continue
        if run.executable or run.failed_step is None:
            break
        at = run.failed_step - 1
        kind = _EAI_KIND.get(run.kind, "missing_step") if run.kind else "missing_step"
        if kind == "missing_step" and not strict_eai and _repeats(run, at):
            kind = "additional_step"  # the same step already ran: doing it again fails
        if kind == "additional_step":
            score.additional.append(kept.pop(at) + 1)
            continue
        if kind == "missing_step" and _ran_earlier(program, kept, at, context.home):
            kind = "wrong_order"
        score.error, score.reason, score.failed_step = kind, run.message, kept[at] + 1
        break
    score.executable = run.executable
    if score.error is None and score.additional:
        score.error = "additional_step"
        score.reason = "skipped steps " + ", ".join(map(str, score.additional))
    records = run.result.trace if run.result is not None and run.result.trace else []
    score.goals = check_goals(context.goals.goals, Trajectory(run.graph, records))


def _repeats(run: Any, at: int) -> bool:
    """Whether the failed step at `at` is a step that already ran (same action, same
    nodes), e.g. a second PutBack of what the first put back."""
    records = run.result.trace if run.result is not None and run.result.trace else []
    failed = run.grounding.program.steps[at] if run.grounding is not None else None
    if failed is None or not records:
        return False
    nodes = tuple(r.node_id for r in failed.args)
    return any(r.ok and r.step.action.key == failed.action.key and r.nodes == nodes
               for r in records[:at])


def _regrab(run: Any) -> int | None:
    """Index of the first step that grabs what the character already holds, if any.

    The simulator lets it run (the object is then held in both hands, as the reference
    simulator does), but as a plan step it redoes what is done: an additional step.
    """
    records = run.result.trace if run.result is not None and run.result.trace else []
    char = run.graph.character_id
    held: set[int] = {n for r in ("HOLDS_RH", "HOLDS_LH")
                      for n in run.graph.index.out.get(r, {}).get(char, ())}
    for record in records:
        if not record.ok:
            break
        if record.step.action.key == "GRAB" and record.nodes and record.nodes[0] in held:
            return record.index
        for a, relation, b in record.changes.added:
            if a == char and relation in ("HOLDS_RH", "HOLDS_LH"):
                held.add(b)
        for a, relation, b in record.changes.removed:
            if a == char and relation in ("HOLDS_RH", "HOLDS_LH"):
                held.discard(b)
    return None


def _ran_earlier(program: Any, kept: list[int], at: int, home: EnvironmentGraph) -> bool:
    """Whether the step at `at` could have run right after some earlier prefix of the run."""
    step = program.steps[kept[at]]
    for k in range(at):
        prefix = [program.steps[i] for i in kept[:k]]
        if _run(program.with_steps([*prefix, step]), home).executable:
            return True
    return False


def _run(program: Program, home: EnvironmentGraph, trace: bool = False) -> Run:
    """A plan runs as written in the task's initial graph: not prepared, not repaired."""
    return run_program(program, home, prepare=False, repair=False, trace=trace)


@dataclass
class PlanReport:
    """Every plan's score and EAI's summary metrics.

    The additional step rate is the share of plans with a skipped step (at most 100 %);
    EAI counts skipped steps, not plans, over the number of plans, which `strict_eai`
    reproduces (a plan that repeats one step 997 times reads 99 700 % there).
    """

    scores: list[PlanScore]
    strict_eai: bool = False

    def summary(self) -> dict[str, Any]:
        """EAI's metrics (percent of plans; goal rates over all goals of scored plans)."""
        n = len(self.scores) or 1
        kinds = {k: sum(s.error == k for s in self.scores) for k in GRAMMAR_KINDS}
        runtime = {k: sum(s.error == k for s in self.scores) for k in RUNTIME_KINDS[:3]}
        runtime["additional_step"] = sum(
            len(s.additional) if self.strict_eai else bool(s.additional) for s in self.scores)
        met = {"state": [0, 0], "relation": [0, 0], "action": [0, 0]}
        for s in self.scores:
            for kind in met:
                met[kind][1] += s.totals.get(kind, 0)
                met[kind][0] += 0 if s.goals is None else s.goals.counts[kind][0]
        all_met = sum(m for m, _ in met.values())
        all_goals = sum(t for _, t in met.values()) or 1

        def pct(x: int, d: int) -> float:
            return round(100.0 * x / (d or 1), 2)

        return {
            "plans": len(self.scores),
            "goal_evaluation": {
                "task_success_rate": pct(sum(s.success for s in self.scores), n),
                "state_goal": pct(*met["state"]), "relation_goal": pct(*met["relation"]),
                "action_goal": pct(*met["action"]), "total_goal": pct(all_met, all_goals)},
            "trajectory_evaluation": {
                "execution_success_rate": pct(sum(s.executable for s in self.scores), n),
                "grammar_error": {"parsing": pct(kinds["format"], n),
                                  "hallucination": pct(kinds["hallucination"], n),
                                  "predicate_argument_number": pct(kinds["arity"], n)},
                "runtime_error": {"wrong_order": pct(runtime["wrong_order"], n),
                                  "missing_step": pct(runtime["missing_step"], n),
                                  "affordance_error": pct(runtime["affordance"], n),
                                  "additional_step": pct(runtime["additional_step"], n)}},
        }


def score_plans(plans: Iterable[dict[str, Any]], contexts: dict[str, TaskContext], *,
                strict_eai: bool = False) -> PlanReport:
    """Score EAI output records (``{"identifier": "27_2", "llm_output": "..."}``)."""
    scores = []
    for k, record in enumerate(plans):
        identifier = str(record.get("identifier", "")) if isinstance(record, dict) else ""
        context = contexts.get(identifier)
        if context is None:
            raise DataError(f"plan {k + 1}: no annotated program {identifier!r} "
                            "(EAI identifiers look like '27_2')")
        scores.append(score_plan(identifier, record.get("llm_output", ""), context,
                                 strict_eai=strict_eai))
    return PlanReport(scores, strict_eai)


def gold_plan(context_program: Any) -> str:
    """A program as a plan in EAI's output format (keys repeat, in order)."""
    parts = []
    for step in context_program.steps:
        params = []
        for ref in step.args:
            params += [ref.name, str(ref.node_id)]
        parts.append(f"{json.dumps(step.action.key)}: {json.dumps(params)}")
    return "{" + ", ".join(parts) + "}"
