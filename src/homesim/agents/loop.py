"""The agent loop, and a scripted policy that reaches `StateGoal` goals.

>>> from homesim.agents.env import HomeEnv
>>> env = HomeEnv("scene1_trimmed", goal=StateGoal(states=((42, "ON"),)))
>>> episode = run_episode(env, ScriptedPolicy(env.goal, env.home))
>>> episode.success, episode.actions
(True, ['[Walk] <faucet> (42)', '[SwitchOn] <faucet> (42)'])
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import gymnasium as gym

from homesim.agents.goal import StateGoal
from homesim.program.actions import ACTIONS, ActionSpec
from homesim.world.graph import EnvironmentGraph

Policy = Callable[[dict[str, Any], dict[str, Any]], str]
"""``policy(observation, info) -> action``: info is the last step's (reset's at first)."""


@dataclass
class Episode:
    """One episode: the actions taken, the rewards, each step's info, and the verdict."""

    actions: list[str] = field(default_factory=list)
    rewards: list[float] = field(default_factory=list)
    infos: list[dict[str, Any]] = field(default_factory=list)
    success: bool = False
    truncated: bool = False


def run_episode(env: gym.Env, policy: Policy, *, seed: int = 0) -> Episode:
    """Reset `env` with `seed` and let `policy` act until the episode ends."""
    obs, info = env.reset(seed=seed)
    reset = getattr(policy, "reset", None)
    if callable(reset):
        reset()
    episode = Episode()
    done = False
    while not done:
        action = policy(obs, info)
        obs, reward, terminated, truncated, info = env.step(action)
        episode.actions.append(action)
        episode.rewards.append(float(reward))
        episode.infos.append(info)
        episode.success = bool(info.get("success"))
        episode.truncated = bool(truncated)
        done = terminated or truncated
    return episode


def _setter(state: str) -> ActionSpec | None:
    """The one-object catalog action that ``sets_states`` `state` (ON: SwitchOn)."""
    return next((a for a in ACTIONS.values() if a.arity == 1 and state in a.sets_states),
                None)


@dataclass
class ScriptedPolicy:
    """Reaches a `StateGoal` by a fixed plan: for each node state, walk to the node and
    apply the catalog action that sets that state; for each ``(a, ON|INSIDE, b)``
    relation, walk to a, grab it, walk to b and put it on or in b. A failed step is not
    retried: the plan goes on (an example of the loop, not a planner).

    Attributes:
        goal: the goal.
        home: the home (for the class names of the goal's nodes).
    """

    goal: StateGoal
    home: EnvironmentGraph
    _next: int = 0

    def plan(self) -> list[str]:
        """The whole plan, one step per line."""
        def ref(n: int) -> str:
            return f"<{self.home.node(n).class_name}> ({n})"

        steps: list[str] = []
        for node, state in self.goal.states:
            action = _setter(state)
            if action is not None:
                steps += [f"[Walk] {ref(node)}", f"[{action.name}] {ref(node)}"]
        for a, relation, b in self.goal.relations:
            put = {"ON": "PutBack", "INSIDE": "PutIn"}.get(relation)
            if put is not None:
                steps += [f"[Walk] {ref(a)}", f"[Grab] {ref(a)}", f"[Walk] {ref(b)}",
                          f"[{put}] {ref(a)} {ref(b)}"]
        return steps

    def __call__(self, observation: dict[str, Any], info: dict[str, Any]) -> str:
        plan = self.plan()
        self._next += 1
        if not plan:
            return "[StandUp]"  # nothing to do; the environment says why it cannot run
        return plan[min(self._next, len(plan)) - 1]  # past the plan: its last step again

    def reset(self) -> None:
        """Start the plan again (a new episode)."""
        self._next = 0
