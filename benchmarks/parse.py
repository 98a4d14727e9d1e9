"""Program parsing: time per MiB at 1x, 4x and 16x input sizes, against the old parser.

Two shapes of text: one long line of objects (``[Walk] <tv> (1) <tv> (1) ...``, which the
parser rejects with an ArityError after reading it all; issue 12 measured 4.5 s for
500 KiB of it) and many ordinary step lines. A linear parser takes the same time per MiB
at every size; the reference, the parser before issue 12 (kept below, verbatim in what it
does), copied the rest of the line for each object and grows with the size.

The limits (MAX_PROGRAM_BYTES, MAX_STEPS) are lifted for the run, to time the parser on
texts larger than the CLI and API accept.

    python benchmarks/parse.py [--base-kib 32] [--repeat 3]
"""

from __future__ import annotations

import argparse
import contextlib
import re
import time
from collections.abc import Callable

from homesim import limits
from homesim.errors import ArityError, ProgramError, UnknownActionError
from homesim.program.actions import lookup_action, suggest_action
from homesim.program.model import ObjectRef, Step
from homesim.program.parse import parse_program, parse_step
from homesim.program.syntax import normalize_name

_ACTION = re.compile(r"\s*\[([^\[\]]*)\]")
_NAME = re.compile(r"\s*<([^<>]*)>")
_ID = re.compile(r"\s*\(\s*(\d+)(?:\s*\.\s*(\d+))?\s*\)")


def reference_parse_step(line: str, lineno: int = 1) -> Step:
    """The step parser before issue 12 (quadratic: ``line[pos:].strip()`` per object)."""

    def fail(expected: str, cls: type[ProgramError] = ProgramError) -> ProgramError:
        return cls(lineno, line, expected)

    m = _ACTION.match(line)
    if m is None:
        raise fail("expected a step")
    word = m.group(1).strip()
    action = lookup_action(word)
    if action is None:
        suggest_action(word)
        raise fail(f"unknown action '{word}'", UnknownActionError)
    pos = m.end()
    args: list[ObjectRef] = []
    while pos < len(line) and line[pos:].strip():
        nm = _NAME.match(line, pos)
        if nm is None:
            raise fail(f"expected an object but found {line[pos:].strip()!r}")
        name = normalize_name(nm.group(1))
        if not name:
            raise fail("expected an object name")
        im = _ID.match(line, nm.end())
        if im is None:
            raise fail("expected an id")
        node_id = int(im.group(2)) if im.group(2) is not None else None
        args.append(ObjectRef(name, int(im.group(1)), node_id))
        pos = im.end()
    if len(args) != action.arity:
        raise fail(f"takes {action.arity}, got {len(args)}", ArityError)
    return Step(action, tuple(args))


def reference_parse(text: str) -> None:
    """Old `parse_program` on steps-only text (the header handling is the same)."""
    for n, line in enumerate(text.splitlines(), 1):
        if line.strip() and not line.strip().startswith("#"):
            reference_parse_step(line, n)


def ours(text: str) -> None:
    if "\n" in text:
        parse_program(text)
    else:
        parse_step(text)  # parse_program would first refuse the size


def _time(parse: Callable[[str], None], text: str, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        with contextlib.suppress(ProgramError):  # the long line is an ArityError
            parse(text)
        best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base-kib", type=int, default=32, help="size of the 1x text")
    parser.add_argument("--repeat", type=int, default=3, help="best of N runs")
    args = parser.parse_args()
    limits.MAX_PROGRAM_BYTES = 1 << 40
    limits.MAX_STEPS = 1 << 40
    shapes = {"one line of objects": "[Walk] " + "<tv> (1) " * (1 << 20),
              "step lines": "[PutBack] <cup> (1.417) <table> (1.226)\n" * (1 << 16)}
    print(f"{'shape':22} {'size':>9} {'ours s/MiB':>11} {'ref s/MiB':>10} {'ref/ours':>9}")
    for shape, long_text in shapes.items():
        for factor in (1, 4, 16):
            size = args.base_kib * 1024 * factor
            text = long_text[:size]
            text = text[:text.rfind("\n" if "\n" in text else " ") + 1]  # whole objects
            mib = len(text) / 2**20
            t_ours = _time(ours, text, args.repeat) / mib
            t_ref = _time(reference_parse, text, args.repeat) / mib
            print(f"{shape:22} {len(text) // 1024:>6} KiB {t_ours:>11.3f} {t_ref:>10.3f} "
                  f"{t_ref / t_ours:>8.1f}x")


if __name__ == "__main__":
    main()
