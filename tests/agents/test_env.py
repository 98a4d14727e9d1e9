"""HomeEnv: the Gymnasium contract, failure reasons in info, goal reward and termination."""

from __future__ import annotations

import pytest

gym = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402

from homesim.agents import HomeEnv, StateGoal  # noqa: E402


@pytest.fixture
def env(tiny_home):
    return HomeEnv(tiny_home, goal=StateGoal(states=((14, "ON"),)), max_steps=5)


def test_check_env_passes(env):
    check_env(env, skip_render_check=True)


def test_check_env_passes_on_a_built_in_home_through_make():
    env = gym.make("homesim/Home-v0", home="scene1_trimmed",
                   goal=StateGoal(states=((42, "ON"),)), render_mode="ansi")
    check_env(env.unwrapped)
    env.reset(seed=0)
    assert env.render().startswith("You are in <bathroom> (1).")


def test_a_failed_step_changes_nothing_and_says_why(env):
    obs, _ = env.reset(seed=0)
    after, reward, terminated, truncated, info = env.step("[SwitchOn] <tv> (14)")
    assert (reward, terminated, truncated) == (0.0, False, False)
    assert info["ok"] is False and info["reason"] == "the character is not close to tv 14"
    assert after == obs


@pytest.mark.parametrize(("action", "reason"), [
    ("[Wlak] <tv> (14)", "did you mean Walk?"),
    ("[Walk] <tv> (99)", "the home has no node 99 for <tv>"),
    ("[Walk] <sofa> (14)", "node 14 is a tv, not a sofa"),
    ("x" * 300, "longer than 256 characters"),
])
def test_bad_actions_are_answers_not_errors(env, action, reason):
    env.reset()
    info = env.step(action)[4]
    assert info["ok"] is False and reason in info["reason"]


def test_the_goal_gives_reward_and_terminates(env):
    env.reset()
    obs, reward, terminated, _, info = env.step("[Walk] <tv> (1.14)")
    assert (reward, terminated, info["ok"]) == (0.0, False, True)
    assert obs["room"] == "<living_room> (2)"
    assert any(o["id"] == 14 and o["close"] == 1 for o in obs["objects"])
    obs, reward, terminated, truncated, info = env.step("[SwitchOn] <tv> (14)")
    assert (reward, terminated, truncated, info["success"]) == (1.0, True, False, True)
    assert info["changed"] == "tv 14: OFF → ON"


def test_truncation_after_max_steps_and_reset_starts_again(env):
    env.reset()
    results = [env.step("[Walk] <sofa> (15)") for _ in range(5)]
    assert [r[3] for r in results] == [False] * 4 + [True]
    obs, _ = env.reset(options={"goal": StateGoal(states=((11, "OPEN"),))})
    assert obs["room"] == "<kitchen> (1)" and "Goal: fridge 11 is OPEN." in obs["text"]


def test_failure_penalty(tiny_home):
    env = HomeEnv(tiny_home, failure_penalty=-0.1)
    env.reset()
    assert env.step("[Grab] <cup> (12)")[1] == -0.1
