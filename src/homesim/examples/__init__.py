"""Example programs shipped with homesim (the demo of `homesim run`)."""

from __future__ import annotations

from importlib import resources

from homesim.program.model import Program
from homesim.program.parse import parse_program

DEMO_HOME = "scene1"
"""The built-in home the demo program is written for."""


def example_names() -> list[str]:
    return sorted(p.name.removesuffix(".txt") for p in resources.files(__name__).iterdir()
                  if p.name.endswith(".txt"))


def load_example(name: str = "watch_tv") -> Program:
    """An example program by name (``watch_tv`` is the paper's Fig. 1 program)."""
    path = resources.files(__name__) / f"{name}.txt"
    return parse_program(path.read_text(encoding="utf-8"), source=f"example {name}")
