"""Parse program text in every form the VirtualHome data uses.

Accepted step forms: ``[WALK]`` or ``[Walk]``; ids as ``(1)`` or ``(1.417)`` (instance .
node id); any spacing between the parts; blank lines and ``#`` comment lines between
steps. A whole text is either steps alone or the ActivityPrograms file format: a title
line, a description line, a blank line, then the steps.

Every malformed line raises `ProgramError` (or its subclasses `UnknownActionError`,
`ArityError`) naming the line number, the text and what was expected there.
"""

from __future__ import annotations

import re

from homesim.errors import ArityError, ProgramError, UnknownActionError
from homesim.program.actions import lookup_action, suggest_action
from homesim.program.model import ObjectRef, Program, Step, normalize_name

_ACTION = re.compile(r"\s*\[([^\[\]]*)\]")
_NAME = re.compile(r"\s*<([^<>]*)>")
_ID = re.compile(r"\s*\(\s*(\d+)(?:\s*\.\s*(\d+))?\s*\)")
_EXAMPLE = "a step like '[Walk] <sofa> (1)'"


def parse_step(line: str, lineno: int = 1, source: str | None = None) -> Step:
    """Parse one step line such as ``[PutBack] <cup> (1) <table> (1.226)``.

    >>> str(parse_step("  [SWITCHON]   <tv>(1.410) "))
    '[SwitchOn] <tv> (1.410)'
    """

    def fail(expected: str, cls: type[ProgramError] = ProgramError) -> ProgramError:
        return cls(lineno, line, expected, source)

    m = _ACTION.match(line)
    if m is None:
        raise fail(f"expected {_EXAMPLE}")
    word = m.group(1).strip()
    action = lookup_action(word)
    if action is None:
        hint = suggest_action(word)
        extra = f" (did you mean {hint}?)" if hint else ""
        raise fail(f"unknown action '{word}'{extra}", UnknownActionError)
    pos = m.end()
    args: list[ObjectRef] = []
    while pos < len(line) and line[pos:].strip():
        nm = _NAME.match(line, pos)
        if nm is None:
            rest = line[pos:].strip()
            raise fail(f"expected an object like '<sofa> (1)' but found {rest!r}")
        name = normalize_name(nm.group(1))
        if not name:
            raise fail("expected an object name between '<' and '>'")
        im = _ID.match(line, nm.end())
        if im is None:
            raise fail(f"expected an id like '(1)' or '(1.417)' after <{nm.group(1)}>")
        instance = int(im.group(1))
        node_id = int(im.group(2)) if im.group(2) is not None else None
        args.append(ObjectRef(name, instance, node_id))
        pos = im.end()
    if len(args) != action.arity:
        plural = "object" if action.arity == 1 else "objects"
        raise fail(
            f"[{action.name}] takes {action.arity} {plural}, got {len(args)}", ArityError
        )
    return Step(action, tuple(args))


def _is_step(line: str) -> bool:
    return line.lstrip().startswith("[")


def _is_skippable(line: str) -> bool:
    stripped = line.strip()
    return not stripped or stripped.startswith("#")


def parse_program(text: str, source: str | None = None) -> Program:
    """Parse a program: steps alone, or title, description, blank line, steps.

    >>> p = parse_program("Watch TV\\nI watch TV.\\n\\n[Walk] <tv> (1)\\n[SwitchOn] <tv> (1)")
    >>> p.title, len(p.steps)
    ('Watch TV', 2)
    """
    lines = text.splitlines()
    i = 0
    while i < len(lines) and _is_skippable(lines[i]):
        i += 1
    title = description = ""
    if i < len(lines) and not _is_step(lines[i]):
        title = lines[i].strip()
        i += 1
        # The description runs to the first blank line or step; join wrapped lines.
        desc_lines = []
        while i < len(lines) and lines[i].strip() and not _is_step(lines[i]):
            desc_lines.append(lines[i].strip())
            i += 1
        description = " ".join(desc_lines)
    steps = []
    for lineno in range(i + 1, len(lines) + 1):
        line = lines[lineno - 1]
        if _is_skippable(line):
            continue
        steps.append(parse_step(line, lineno, source))
    return Program(tuple(steps), title, description)


def parse_steps(lines: list[str], source: str | None = None) -> Program:
    """Parse a list of step lines (no title or description), e.g. from a JSON data set."""
    steps = [parse_step(line, n, source) for n, line in enumerate(lines, 1) if line.strip()]
    return Program(tuple(steps))
