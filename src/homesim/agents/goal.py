"""Goals the environment rewards: any callable ``goal(state) -> bool``.

`Goal` is the whole interface: the environment calls it on the simulator state
(`homesim.sim.SimState`) after every step, rewards 1 and ends the episode when it returns
True. `StateGoal` is the built-in kind: node states and relations that must all hold.
A goal may also have ``describe(state) -> str`` (English, for the observation text and
an LLM's prompt); without it the observation names the goal by its ``repr``.

Goal formulas of `homesim.goals` plug in through a small callable that judges the formula
on the state (see docs/agents.md).

>>> from homesim.sim import SimState
>>> from homesim.world import load_home
>>> st = SimState(load_home("scene1_trimmed"))
>>> goal = StateGoal(states=((247, "ON"),))
>>> goal(st), goal.describe(st)
(False, 'television 247 is ON')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

from homesim.sim.state import SimState


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
