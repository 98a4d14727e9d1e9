"""The text form of programs: the grammar, its limits and its error messages.

Accepted step forms: ``[WALK]`` or ``[Walk]``; ids as ``(1)`` or ``(1.417)`` (instance .
node id); any spacing between the parts; blank lines and ``#`` comment lines between
steps. A whole text is either steps alone or the ActivityPrograms file format: a title
line, a description line, a blank line, then the steps.

Every malformed line raises `ProgramError` (or its subclasses `UnknownActionError`,
`ArityError`) naming the line number, the text and what was expected there.

This module reads text into plain parts (an action and its objects' names and ids; a
title, a description and the step lines); the values are built from them by
`Step.parse` and `Program.parse` (`homesim.program.model`), which the functions of
`homesim.program.parse` call. So the values can parse themselves and the grammar needs
none of them.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from homesim import limits
from homesim.errors import ArityError, LimitError, ProgramError, UnknownActionError, excerpt
from homesim.program.actions import ActionSpec, lookup_action, suggest_action

_ACTION = re.compile(r"\s*\[([^\[\]]*)\]")
_NAME = re.compile(r"\s*<([^<>]*)>")
_ID = re.compile(r"\s*\(\s*(\d+)(?:\s*\.\s*(\d+))?\s*\)")
_OBJECT = re.compile(_NAME.pattern + _ID.pattern)
_EXAMPLE = "a step like '[Walk] <sofa> (1)'"

RefParts = tuple[str, int, int | None]
"""An object of a step as read: class name, instance, node id (None if not given)."""

# Speed: every match is anchored at the current position and nothing copies the rest of
# a line, so parsing is linear in the length of the text. An object is one match
# (`_OBJECT`); `_NAME` and `_ID` apart only say what is wrong with a bad one.


def normalize_name(name: str) -> str:
    """Canonical object class name: lower case, words joined by underscores."""
    return "_".join(name.strip().lower().split())


def read_step(line: str, lineno: int = 1, source: str | None = None
              ) -> tuple[ActionSpec, list[RefParts]]:
    """Read one step line such as ``[PutBack] <cup> (1) <table> (1.226)``: its action and
    its objects.

    >>> action, refs = read_step("  [SWITCHON]   <tv>(1.410) ")
    >>> action.name, refs
    ('SwitchOn', [('tv', 1, 410)])
    """

    def fail(expected: str, cls: type[ProgramError] = ProgramError) -> ProgramError:
        return cls(lineno, line, expected, source)

    m = _ACTION.match(line)
    if m is None:
        raise fail(f"expected {_EXAMPLE}")
    word = m.group(1).strip()
    if len(word) > limits.MAX_NAME_CHARS:
        raise fail(f"action name of {len(word)} characters, over the limit of "
                   f"{limits.MAX_NAME_CHARS} (MAX_NAME_CHARS)", UnknownActionError)
    action = lookup_action(word)
    if action is None:
        hint = suggest_action(word)
        extra = f" (did you mean {hint}?)" if hint else ""
        raise fail(f"unknown action {excerpt(word)!r}{extra}", UnknownActionError)
    pos = m.end()
    end = len(line.rstrip())  # same whitespace as the patterns' \s
    args: list[RefParts] = []
    while pos < end:
        om = _OBJECT.match(line, pos)
        if om is None:
            raise _object_error(line, pos, fail)
        raw, first, second = om.groups()
        if len(raw) > limits.MAX_NAME_CHARS:
            raise fail(_long_name(raw))
        name = normalize_name(raw)
        if not name:
            raise fail("expected an object name between '<' and '>'")
        args.append((name, _number(first, fail),
                     None if second is None else _number(second, fail)))
        pos = om.end()
    if len(args) != action.arity:
        raise fail(f"[{action.name}] takes {_objects(action.arity)}, got {len(args)}",
                   ArityError)
    return action, args


def _object_error(line: str, pos: int, fail: Callable[[str], ProgramError]) -> ProgramError:
    """What is wrong with the object at `pos`, which `_OBJECT` did not match."""
    nm = _NAME.match(line, pos)
    if nm is None:
        rest = excerpt(line[pos:pos + limits.EXCERPT_CHARS + 1].strip())
        return fail(f"expected an object like '<sofa> (1)' but found {rest!r}")
    raw = nm.group(1)
    if len(raw) > limits.MAX_NAME_CHARS:
        return fail(_long_name(raw))
    return fail(f"expected an id like '(1)' or '(1.417)' after <{raw}>")


def _long_name(raw: str) -> str:
    return (f"object name of {len(raw)} characters, over the limit of "
            f"{limits.MAX_NAME_CHARS} (MAX_NAME_CHARS)")


def _objects(n: int) -> str:
    return f"{n} object" if n == 1 else f"{n} objects"


def _number(digits: str, fail: Callable[[str], ProgramError]) -> int:
    """An instance or node id; over `MAX_ID_DIGITS` digits is an error (int() of a few
    thousand digits is refused by Python, and no home has that many nodes)."""
    if len(digits) > limits.MAX_ID_DIGITS:
        raise fail(f"id of {len(digits)} digits, over the limit of {limits.MAX_ID_DIGITS} "
                   "(MAX_ID_DIGITS)")
    return int(digits)


def _is_step(line: str) -> bool:
    return line.lstrip().startswith("[")


def _is_skippable(line: str) -> bool:
    stripped = line.strip()
    return not stripped or stripped.startswith("#")


def read_text(text: str, source: str | None = None) -> tuple[str, str, list[tuple[int, str]]]:
    """Read a program text, steps alone or title, description, blank line, steps: its
    title, its description and its step lines with their 1-based line numbers.

    >>> read_text("Watch TV\\nI watch TV.\\n\\n[Walk] <tv> (1)\\n# note\\n[SwitchOn] <tv> (1)")
    ('Watch TV', 'I watch TV.', [(4, '[Walk] <tv> (1)'), (6, '[SwitchOn] <tv> (1)')])
    """
    check_text(text, source)
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
    steps: list[tuple[int, str]] = []
    for lineno in range(i + 1, len(lines) + 1):
        line = lines[lineno - 1]
        if _is_skippable(line):
            continue
        if len(steps) == limits.MAX_STEPS:
            raise too_many_steps(source)
        steps.append((lineno, line))
    return title, description, steps


def check_text(text: str, source: str | None = None) -> None:
    """Raise `LimitError` for a program text over `MAX_PROGRAM_BYTES` and `ProgramError`
    for one that is not valid Unicode (a lone surrogate, which JSON strings may carry)."""
    where = f"{source}: " if source else ""
    if len(text) > limits.MAX_PROGRAM_BYTES:  # a character is at least one byte
        raise LimitError(f"{where}program text of {len(text)} characters, over the limit of "
                         f"{limits.MAX_PROGRAM_BYTES // 1024} KiB (MAX_PROGRAM_BYTES)",
                         "MAX_PROGRAM_BYTES")
    try:
        size = len(text.encode("utf-8"))
    except UnicodeEncodeError as e:
        lineno = text.count("\n", 0, e.start) + 1
        line = text[text.rfind("\n", 0, e.start) + 1:].split("\n", 1)[0]
        raise ProgramError(lineno, line.encode("utf-8", "replace").decode(),
                           f"not valid Unicode (a lone surrogate at character {e.start + 1})",
                           source) from None
    if size > limits.MAX_PROGRAM_BYTES:
        raise LimitError(f"{where}program text of {size} bytes, over the limit of "
                         f"{limits.MAX_PROGRAM_BYTES // 1024} KiB (MAX_PROGRAM_BYTES)",
                         "MAX_PROGRAM_BYTES")


def too_many_steps(source: str | None) -> LimitError:
    """The error for a program of more than `MAX_STEPS` steps."""
    where = f"{source}: " if source else ""
    most = limits.MAX_STEPS
    return LimitError(f"{where}more than {most} steps, over the limit of {most} steps "
                      "(MAX_STEPS)", "MAX_STEPS")


def step_lines(text: str) -> list[int]:
    """1-based line numbers of the step lines of a program text that parsed.

    After a successful parse every step line starts with ``[`` and no title or
    description line does, so the i-th such line is the i-th step.

    >>> step_lines("Title\\nDesc\\n\\n[Walk] <tv> (1)\\n# note\\n[Sit] <sofa> (1)")
    [4, 6]
    """
    return [n for n, line in enumerate(text.splitlines(), 1) if line.lstrip().startswith("[")]
