"""Symbolic simulator: execute programs on homes with preconditions and effects."""

from homesim.sim.effects import EFFECTS
from homesim.sim.execute import ExecutionResult, StepRecord, execute, execute_on, run_step
from homesim.sim.ground import Grounding, ground, prepare_and_ground, unground
from homesim.sim.prepare import Addition, Prepared, prepare
from homesim.sim.state import Changes, SimState

__all__ = [
    "EFFECTS",
    "Addition",
    "Changes",
    "ExecutionResult",
    "Grounding",
    "Prepared",
    "SimState",
    "StepRecord",
    "execute",
    "execute_on",
    "ground",
    "prepare",
    "prepare_and_ground",
    "run_step",
    "unground",
]
