"""Procedurally generated homes: floor plans, furniture and objects drawn from
statistics of the five built-in apartments (see generate.py)."""

from homesim.world.procedural.checks import check_home
from homesim.world.procedural.generate import generate_home, write_home
from homesim.world.procedural.stats import KINDS

__all__ = ["KINDS", "check_home", "generate_home", "write_home"]
