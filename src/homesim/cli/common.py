"""Shared pieces of the command line: the console and input loading with clear errors."""

from __future__ import annotations

import sys

from rich.console import Console

from homesim.errors import HomesimError
from homesim.files import read_text_limited
from homesim.limits import MAX_PROGRAM_BYTES
from homesim.program.model import Program
from homesim.program.parse import parse_program
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import open_home

# soft_wrap: a message stays one line however narrow the terminal (no hard wrapping).
console = Console(highlight=False, soft_wrap=True)
err_console = Console(stderr=True, highlight=False, soft_wrap=True)


def read_program(path: str) -> Program:
    """Read a program file (or ``-`` for standard input), within `homesim.limits`."""
    if path == "-":
        source = "<stdin>"
        try:
            text = sys.stdin.read(MAX_PROGRAM_BYTES + 1)  # parse_program refuses more
        except UnicodeDecodeError:
            raise HomesimError(f"{source}: not UTF-8 text") from None
    else:
        text = read_text_limited(path, MAX_PROGRAM_BYTES, "MAX_PROGRAM_BYTES", "program")
        source = path
    return parse_program(text, source=source)


def read_graph(graph: str | None, home: str | None,
               default_home: str) -> tuple[EnvironmentGraph, str]:
    """The graph named by ``--graph FILE`` or ``--home NAME``, and a name for it."""
    if graph and home:
        raise HomesimError("give either --graph or --home, not both")
    if graph:
        return EnvironmentGraph.load(graph), graph
    name = home or default_home
    return open_home(name), name


def demo_program(home: str) -> Program:
    """The demo program (``watch_tv``) as written for `DEMO_HOME`, ungrounded (``<tv>
    (1)``) for any other home, where preparation and grounding fit it."""
    from homesim.examples import DEMO_HOME, load_example
    from homesim.ground.search import unground

    program = load_example("watch_tv")
    return program if home == DEMO_HOME else unground(program)
