"""Parse program text in every form the VirtualHome data uses.

Accepted step forms: ``[WALK]`` or ``[Walk]``; ids as ``(1)`` or ``(1.417)`` (instance .
node id); any spacing between the parts; blank lines and ``#`` comment lines between
steps. A whole text is either steps alone or the ActivityPrograms file format: a title
line, a description line, a blank line, then the steps.

Every malformed line raises `ProgramError` (or its subclasses `UnknownActionError`,
`ArityError`) naming the line number, the text and what was expected there. The grammar
is `homesim.program.syntax`; these functions are the values' `parse` methods, as
functions.
"""

from __future__ import annotations

from homesim import limits
from homesim.program.model import Program, Step
from homesim.program.syntax import check_text, step_lines, too_many_steps

__all__ = ["check_text", "parse_program", "parse_step", "parse_steps", "step_lines"]


def parse_step(line: str, lineno: int = 1, source: str | None = None) -> Step:
    """Parse one step line such as ``[PutBack] <cup> (1) <table> (1.226)``.

    >>> str(parse_step("  [SWITCHON]   <tv>(1.410) "))
    '[SwitchOn] <tv> (1.410)'
    """
    return Step.parse(line, lineno, source)


def parse_program(text: str, source: str | None = None) -> Program:
    """Parse a program: steps alone, or title, description, blank line, steps.

    >>> p = parse_program("Watch TV\\nI watch TV.\\n\\n[Walk] <tv> (1)\\n[SwitchOn] <tv> (1)")
    >>> p.title, len(p.steps)
    ('Watch TV', 2)
    """
    return Program.parse(text, source)


def parse_steps(lines: list[str], source: str | None = None) -> Program:
    """Parse a list of step lines (no title or description), e.g. from a JSON data set."""
    check_text("\n".join(lines), source)
    steps = [Step.parse(line, n, source) for n, line in enumerate(lines, 1) if line.strip()]
    if len(steps) > limits.MAX_STEPS:
        raise too_many_steps(source)
    return Program(tuple(steps))
