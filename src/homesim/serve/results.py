"""JSON views of parsed programs and execution traces, with the text line of every step."""

from __future__ import annotations

from typing import Any

from homesim.program.model import Program, Step
from homesim.sim.execute import ExecutionResult
from homesim.sim.state import Changes


def step_lines(text: str) -> list[int]:
    """1-based line numbers of the step lines of a program text that parsed.

    After a successful parse every step line starts with ``[`` and no title or
    description line does, so the i-th such line is the i-th step.

    >>> step_lines("Title\\nDesc\\n\\n[Walk] <tv> (1)\\n# note\\n[Sit] <sofa> (1)")
    [4, 6]
    """
    return [n for n, line in enumerate(text.splitlines(), 1) if line.lstrip().startswith("[")]


def step_json(step: Step) -> dict[str, Any]:
    return {
        "text": str(step),
        "action": step.action.key,
        "args": [{"name": r.name, "instance": r.instance, "node_id": r.node_id}
                 for r in step.args],
    }


def program_json(program: Program, lines: list[int]) -> dict[str, Any]:
    """The parsed program: canonical text, title, description, steps with their lines."""
    return {
        "program": str(program),
        "title": program.title,
        "description": program.description,
        "grounded": program.is_grounded,
        "steps": [{"index": i, "line": lines[i], **step_json(s)}
                  for i, s in enumerate(program.steps)],
    }


def changes_json(changes: Changes) -> dict[str, Any]:
    return {
        "added": [list(e) for e in changes.added],
        "removed": [list(e) for e in changes.removed],
        "states": [{"node": n, "before": sorted(a), "after": sorted(b)}
                   for n, a, b in changes.states],
        "nodes": list(changes.nodes),
    }


def execution_json(result: ExecutionResult, lines: list[int]) -> dict[str, Any]:
    """Each attempted step ✓/✗ with its reason and changes; the steps after a failure."""
    label = result.state.label
    steps = []
    for rec in result.trace or []:
        steps.append({
            "index": rec.index,
            "line": lines[rec.index],
            "step": str(rec.step),
            "nodes": list(rec.nodes),
            "ok": rec.ok,
            "reason": rec.reason,
            "changes": changes_json(rec.changes),
            "summary": rec.changes.describe(label) if rec.ok else rec.reason,
        })
    program = result.program
    not_run = [{"index": i, "line": lines[i], "step": str(program.steps[i])}
               for i in range(len(steps), len(program.steps))]
    return {
        "executable": result.executable,
        "failed_step": result.failed_step,
        "failed_line": None if result.failed_index is None else lines[result.failed_index],
        "reason": result.reason,
        "message": result.message,
        "program": str(program),
        "steps": steps,
        "not_run": not_run,
    }
