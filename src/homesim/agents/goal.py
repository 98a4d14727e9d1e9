"""Goals the environment rewards: any callable ``goal(state) -> bool``.

`Goal` is the whole interface: the environment calls it on the simulator state
(`homesim.sim.SimState`) after every step, rewards 1 and ends the episode when it returns
True. `StateGoal` is the built-in kind: node states and relations that must all hold.
A goal may also have ``describe(state) -> str`` (English, for the observation text and
an LLM's prompt); without it the observation names the goal by its ``repr``.

Goals that need the episode's steps as well as its state (EAI's action goals, temporal
formulas) have ``on_trace(home, steps)`` (`TraceGoal`); `TaskGoal` is the one for the goals
of `homesim.goals`, and `homesim.agents.tasks` builds the environment of an EAI task.

>>> from homesim.sim import SimState
>>> from homesim.world import load_home
>>> st = SimState(load_home("scene1_trimmed"))
>>> goal = StateGoal(states=((247, "ON"),))
>>> goal(st), goal.describe(st)
(False, 'television 247 is ON')
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol, runtime_checkable

from homesim.goals.check import GoalSet, Trajectory, check_goals, holds
from homesim.goals.formula import Formula
from homesim.sim.execute import StepRecord
from homesim.sim.state import SimState
from homesim.world.graph import EnvironmentGraph

if TYPE_CHECKING:
    from homesim.goals.eai import TaskGoals


@runtime_checkable
class Goal(Protocol):
    """Whether the goal holds in a simulator state."""

    def __call__(self, state: SimState) -> bool: ...


@dataclass(frozen=True, slots=True)
class StateGoal:
    """Node states and relations that must all hold.

    Attributes:
        states: (node id, state) pairs: the node must be in that state (``(247, "ON")``).
        relations: (from id, relation, to id) edges that must exist (``(12, "ON", 13)``);
            the character is named by its node id too.
    """

    states: tuple[tuple[int, str], ...] = ()
    relations: tuple[tuple[int, str, int], ...] = ()

    def __call__(self, state: SimState) -> bool:
        return (all(n in state and s in state.states(n) for n, s in self.states)
                and all(a in state and b in state and state.has_edge(a, r, b)
                        for a, r, b in self.relations))

    def describe(self, state: SimState) -> str:
        """The conditions in English: ``tv 14 is ON; cup 12 ON table 13``."""
        def label(n: int) -> str:
            return state.label(n) if n in state else f"node {n}"

        parts = [f"{label(n)} is {s}" for n, s in self.states]
        parts += [f"{label(a)} {r} {label(b)}" for a, r, b in self.relations]
        return "; ".join(parts) or "nothing"


@runtime_checkable
class TraceGoal(Protocol):
    """A goal judged on the whole episode, not only its last state: action goals ("the
    character watched the TV") and temporal formulas need the steps that ran. The
    environment calls ``on_trace(home, steps)`` (the home the episode started from and
    the `StepRecord` of every step that ran) instead of ``goal(state)``."""

    def on_trace(self, initial: EnvironmentGraph, steps: Sequence[StepRecord]) -> bool: ...


@dataclass(frozen=True)
class TaskGoal:
    """The goals of `homesim.goals` (EAI's annotations) as an environment goal.

    It holds when every goal of `goals` is met (node states and relations at the end,
    action goals in order), as `homesim.goals.plans` judges a plan's task success, and,
    with `formula`, when the temporal formula holds on the episode too.

    Attributes:
        goals: the flat goals (`homesim.goals.GoalSet`).
        formula: a temporal formula also required, or None.
        title: the task's title, for the observation text ("" when none).
    """

    goals: GoalSet
    formula: Formula | None = None
    title: str = ""

    @classmethod
    def from_task(cls, task: TaskGoals, formula: bool = False) -> TaskGoal:
        """The goal of one EAI-annotated program (`homesim.goals.load_eai_goals`); its
        formula too when `formula`."""
        return cls(task.goals, task.formula if formula else None, task.task)

    def on_trace(self, initial: EnvironmentGraph, steps: Sequence[StepRecord]) -> bool:
        trajectory = Trajectory(initial, steps)
        return check_goals(self.goals, trajectory).success and (
            self.formula is None or holds(self.formula, trajectory))

    def __call__(self, state: SimState) -> bool:
        """The state and relation goals on `state` alone (no action goal is met without
        the episode's steps: `on_trace` judges those)."""
        return not self.goals.actions and self.formula is None and all(
            n in state and s in state.states(n) for n, _, s in self.goals.states) and all(
            a in state and b in state and state.has_edge(a, r, b)
            for a, r, b in self.goals.relations)

    def describe(self, state: SimState) -> str:
        """The goals in words: ``Watch TV: television 410 is ON; do LOOKAT or WATCH``."""
        def label(n: int) -> str:
            return state.label(n) if n in state else f"node {n}"

        parts = [f"{label(n)} is {s}" for n, _, s in self.goals.states]
        parts += [f"{label(a)} {r} {label(b)}" for a, r, b in self.goals.relations]
        parts += ["do " + " or ".join(alts) for alts in self.goals.actions]
        if self.formula is not None:
            parts.append(f"and {self.formula}")
        text = "; ".join(parts) or "nothing"
        return f"{self.title}: {text}" if self.title else text
