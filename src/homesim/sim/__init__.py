"""Symbolic simulator: execute programs on homes with preconditions and effects."""

from homesim.sim.effects import EFFECTS
from homesim.sim.execute import ExecutionResult, StepRecord, execute, execute_on, run_step
from homesim.sim.failure import Failure, FailureKind
from homesim.sim.state import Changes, SimState

__all__ = [
    "EFFECTS",
    "Changes",
    "ExecutionResult",
    "Failure",
    "FailureKind",
    "SimState",
    "StepRecord",
    "execute",
    "execute_on",
    "run_step",
]
