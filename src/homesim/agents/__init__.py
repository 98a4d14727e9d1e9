"""Closed-loop agents: a Gymnasium environment over the simulator, goals, an LLM adapter.

Glossary: *observation* (text and structure, `homesim.agents.observation`), *action* (one
program step as text), *goal* (``goal(state) -> bool``, or ``on_trace(home, steps)`` for
EAI's goals, `homesim.agents.goal`; `eai_env` for an EAI task), *policy* (``policy(
observation, info) -> action``, `homesim.agents.loop`), *model* (``prompt -> reply``,
`homesim.agents.llm`). Needs the ``agents`` extra (gymnasium). Registered as
``gymnasium.make("homesim/Home-v0", home=..., goal=...)``.
"""

import gymnasium as gym

from homesim.agents.env import HomeEnv
from homesim.agents.goal import Goal, StateGoal, TaskGoal, TraceGoal
from homesim.agents.llm import FakeModel, LLMPolicy, build_prompt, parse_reply
from homesim.agents.loop import Episode, ScriptedPolicy, run_episode
from homesim.agents.observation import observe
from homesim.agents.tasks import eai_env

if "homesim/Home-v0" not in gym.registry:
    gym.register("homesim/Home-v0", entry_point="homesim.agents.env:HomeEnv")

__all__ = ["Episode", "FakeModel", "Goal", "HomeEnv", "LLMPolicy", "ScriptedPolicy",
           "StateGoal", "TaskGoal", "TraceGoal", "build_prompt", "eai_env", "observe",
           "parse_reply", "run_episode"]
