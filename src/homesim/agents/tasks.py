"""The environment of an EAI task: its annotated program's initial home and its goals.

`eai_env("27_2")` is a `HomeEnv` that starts in the stored initial graph of EAI program
``27_2`` (the home EAI's evaluator runs that task's plans in) and rewards `TaskGoal`: the
program's goals from EAI's annotations (`homesim.goals.load_eai_goals`), met as
`homesim eval plans` judges task success. An agent evaluated in it is judged on the same
tasks, in the same homes, as a planner scored by EAI's action-sequencing metrics.

    env = eai_env("27_2", max_steps=30)               # Wash clothes
    obs, info = env.reset(seed=0)      # obs["text"] ends with the goal in words
    obs, reward, terminated, truncated, info = env.step("[Walk] <washing_machine> (1001)")
"""

from __future__ import annotations

from typing import Any

from homesim.agents.env import HomeEnv
from homesim.agents.goal import TaskGoal
from homesim.errors import DataError


def eai_env(identifier: str, *, formula: bool = False, **options: Any) -> HomeEnv:
    """A `HomeEnv` for EAI program `identifier` (``27_2``; ``file27_2`` works too).

    Args:
        identifier: the program's EAI identifier.
        formula: also require the task's temporal formula (`TaskGoal.formula`).
        options: other `HomeEnv` arguments (``max_steps``, ``failure_penalty``, ...).

    Raises:
        DataError: the real data set is not fetched, or no annotated program has that id.
    """
    from homesim.goals.contexts import load_contexts
    from homesim.goals.eai import eai_id

    key = eai_id(identifier)
    context = load_contexts([key]).get(key)
    if context is None:
        raise DataError(f"no EAI-annotated program {identifier!r} "
                        "(EAI identifiers look like '27_2')")
    return HomeEnv(context.home, TaskGoal.from_task(context.goals, formula), **options)
