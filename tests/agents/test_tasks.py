"""EAI goals in the environment: TaskGoal judged on the episode, eai_env on real tasks."""

from __future__ import annotations

import pytest

pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env

from homesim.agents import HomeEnv, TaskGoal, TraceGoal, eai_env
from homesim.goals.check import GoalSet
from homesim.goals.formula import parse_formula

WATCH_TV = TaskGoal(GoalSet(states=((14, "tv", "ON"),), actions=(("LOOKAT", "WATCH"),)),
                    title="Watch TV")


def test_action_goals_need_the_steps_not_only_the_state(tiny_home):
    env = HomeEnv(tiny_home, goal=WATCH_TV)
    env.reset(seed=0)
    assert isinstance(WATCH_TV, TraceGoal)
    assert env.step("[Walk] <tv> (14)")[1:3] == (0.0, False)
    _, reward, terminated, _, info = env.step("[SwitchOn] <tv> (14)")
    assert (reward, terminated, info["success"]) == (0.0, False, False)  # not watched yet
    assert not WATCH_TV(env.state)  # the state alone cannot say
    assert env.step("[TurnTo] <tv> (14)")[1] == 0.0
    _, reward, terminated, _, info = env.step("[Watch] <tv> (14)")
    assert (reward, terminated, info["success"]) == (1.0, True, True)
    assert [str(r.step) for r in env.history] == [
        "[Walk] <tv> (14)", "[SwitchOn] <tv> (14)", "[TurnTo] <tv> (14)",
        "[Watch] <tv> (14)"]


def test_an_action_goal_met_early_stays_met(tiny_home):
    env = HomeEnv(tiny_home, goal=WATCH_TV, max_steps=5)
    env.reset(seed=0)
    for action in ("[Walk] <tv> (14)", "[TurnTo] <tv> (14)", "[Watch] <tv> (14)",
                   "[SwitchOn] <tv> (14)"):
        *_, info = env.step(action)
    assert info["success"]  # the action goal is met by a step that ran; the state at the end
    env.reset(seed=0)
    assert env.history == [] and not env.step("[SwitchOn] <tv> (14)")[-1]["ok"]
    assert env.history == []  # failed steps are not part of the episode's trace


def test_a_formula_is_judged_on_the_episode(tiny_home):
    goal = TaskGoal(GoalSet(), parse_formula("ON(tv.14) then OFF(tv.14)"))
    env = HomeEnv(tiny_home, goal=goal)
    env.reset(seed=0)
    env.step("[Walk] <tv> (14)")
    assert not env.step("[SwitchOn] <tv> (14)")[2]
    assert env.step("[SwitchOff] <tv> (14)")[2]  # OFF at the start alone does not do


def test_the_goal_is_in_the_observation_and_check_env_passes(tiny_home):
    env = HomeEnv(tiny_home, goal=WATCH_TV)
    obs, _ = env.reset(seed=0)
    assert "Goal: Watch TV: tv 14 is ON; do LOOKAT or WATCH" in obs["text"]
    check_env(env, skip_render_check=True)


def test_eai_tasks_in_the_env_agree_with_plan_scoring(real_data):
    """Replaying an annotated program step by step in its task's environment succeeds
    exactly when `homesim eval plans` says the program as a plan succeeds."""
    from homesim.goals.contexts import load_contexts
    from homesim.goals.plans import gold_plan, score_plan
    from homesim.knowledge.datasets import real_programs

    ids = ["27_2", "1003_2", "115_2", "407_1"]
    contexts = load_contexts(ids)
    programs = {p.id: p.program for p in real_programs()}
    for pid in ids:
        env = eai_env(pid, max_steps=100)
        env.reset(seed=0)
        steps = programs[f"file{pid}"].steps
        reached = len(steps)
        for k, step in enumerate(steps):
            *_, terminated, _, info = env.step(str(step))
            assert info["ok"], (pid, str(step), info["reason"])
            if terminated:
                reached = k
                break
        scored = score_plan(pid, gold_plan(programs[f"file{pid}"]), contexts[pid])
        assert info["success"] == scored.success is True, pid
        env.reset(seed=0)
        for step in steps[:reached]:  # everything but the step that reached the goal
            assert not env.step(str(step))[2], pid


def test_check_env_passes_on_an_eai_task(real_data):
    check_env(eai_env("27_2", formula=True), skip_render_check=True)


def test_unknown_task_is_a_data_error(real_data):
    from homesim.errors import DataError

    with pytest.raises(DataError, match="no EAI-annotated program '9999_9'"):
        eai_env("9999_9")
