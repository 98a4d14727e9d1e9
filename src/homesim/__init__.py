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
from homesim.knowledge.objects import load_kb as _load_kb
from homesim.program import Bindings, ObjectRef, Program, Step, parse_program
from homesim.sim import ExecutionResult, execute
from homesim.version import __version__ as __version__
from homesim.world import EnvironmentGraph, load_home
from homesim.world.classes import use_default_kb as _use_default_kb

# Homes and the simulator ask the object knowledge base through a protocol of their own
# layer (homesim.world.classes); here, at the top, the package's knowledge base is plugged
# in. Python runs this file before any homesim.* module, so every caller finds it.
_use_default_kb(_load_kb)

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
