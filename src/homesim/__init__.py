"""homesim: simulate household activities described as programs.

>>> import homesim
>>> p = homesim.parse_program("[Walk] <sofa> (1)")
>>> str(p.steps[0])
'[Walk] <sofa> (1)'
"""

from homesim.errors import (
    ArityError,
    BindingError,
    DataError,
    ExecutionError,
    GraphError,
    GroundingError,
    HomesimError,
    ProgramError,
    UnknownActionError,
)
from homesim.ground import Run, prepare, prepare_and_ground, run_program, unground
from homesim.program import Bindings, ObjectRef, Program, Step, parse_program
from homesim.sim import ExecutionResult, execute
from homesim.world import EnvironmentGraph, load_home

__version__ = "0.1.0"

__all__ = [
    "ArityError",
    "BindingError",
    "Bindings",
    "DataError",
    "EnvironmentGraph",
    "ExecutionError",
    "ExecutionResult",
    "GraphError",
    "GroundingError",
    "HomesimError",
    "ObjectRef",
    "Program",
    "ProgramError",
    "Run",
    "Step",
    "UnknownActionError",
    "execute",
    "load_home",
    "parse_program",
    "prepare",
    "prepare_and_ground",
    "run_program",
    "unground",
]
