"""JSON views of parsed programs, with the text line of every step.

Runs are encoded by the library (`homesim.ground.pipeline.Run.to_dict`), in the same shape
as ``homesim run --json``.
"""

from __future__ import annotations

from typing import Any

from homesim.program.model import Program, Step


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
