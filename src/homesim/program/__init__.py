"""Program language: parse, print and describe programs (`[Walk] <television> (1)`)."""

from homesim.program.actions import (
    ACTIONS,
    ANIMATED,
    ActionSpec,
    Category,
    actions_in,
    lookup_action,
)
from homesim.program.bindings import Bindings
from homesim.program.model import ObjectRef, Program, Step
from homesim.program.parse import parse_program, parse_step, parse_steps
from homesim.program.syntax import normalize_name

__all__ = [
    "ACTIONS",
    "ANIMATED",
    "ActionSpec",
    "Bindings",
    "Category",
    "ObjectRef",
    "Program",
    "Step",
    "actions_in",
    "lookup_action",
    "normalize_name",
    "parse_program",
    "parse_step",
    "parse_steps",
]
