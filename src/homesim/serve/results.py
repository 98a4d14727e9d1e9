"""JSON views of parsed programs, with the text line of every step.

Runs are encoded by the library (`homesim.ground.pipeline.Run.to_dict`), in the same shape
as ``homesim run --json``.
"""

from __future__ import annotations

from typing import Any

from homesim.program.model import Program, Step
from homesim.program.parse import step_lines

__all__ = ["program_json", "step_json", "step_lines"]


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
