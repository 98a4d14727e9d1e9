"""The example loop: a scripted policy reaches its goal; a fake LLM drives the env."""

from __future__ import annotations

import pytest

pytest.importorskip("gymnasium")

from homesim.agents import (
    FakeModel,
    HomeEnv,
    LLMPolicy,
    ScriptedPolicy,
    StateGoal,
    parse_reply,
    run_episode,
)


def test_a_scripted_policy_reaches_a_state_and_a_relation_goal(tiny_home):
    goal = StateGoal(states=((14, "ON"),), relations=((16, "ON", 15),))
    env = HomeEnv(tiny_home, goal=goal, max_steps=20)
    episode = run_episode(env, ScriptedPolicy(goal, tiny_home))
    assert episode.success and not episode.truncated
    assert episode.rewards[-1] == 1.0 and sum(episode.rewards) == 1.0
    assert episode.actions == ["[Walk] <tv> (14)", "[SwitchOn] <tv> (14)",
                               "[Walk] <plate> (16)", "[Grab] <plate> (16)",
                               "[Walk] <sofa> (15)", "[PutBack] <plate> (16) <sofa> (15)"]


def test_a_scripted_policy_that_cannot_reach_its_goal_is_truncated(tiny_home):
    goal = StateGoal(relations=((12, "ON", 15),))  # the cup is in the closed fridge
    env = HomeEnv(tiny_home, goal=goal, max_steps=6)
    episode = run_episode(env, ScriptedPolicy(goal, tiny_home))
    assert not episode.success and episode.truncated and len(episode.actions) == 6
    assert episode.infos[1]["reason"] == "cup 12 is inside closed fridge 11"


def test_a_fake_llm_drives_the_env_and_sees_its_failures(tiny_home):
    model = FakeModel([
        "I will switch the TV on: [SwitchOn] <tv> (14)",
        "Walk first.\n[Walk] <tv> (14)",
        "[SwitchOn] <tv> (14)",
    ])
    env = HomeEnv(tiny_home, goal=StateGoal(states=((14, "ON"),)), max_steps=5)
    episode = run_episode(env, LLMPolicy(model))
    assert episode.success and episode.actions == [
        "[SwitchOn] <tv> (14)", "[Walk] <tv> (14)", "[SwitchOn] <tv> (14)"]
    assert len(model.prompts) == 3
    assert "Goal: tv 14 is ON." in model.prompts[0]
    assert "[SwitchOn] <tv> (14) -> failed: the character is not close to tv 14" \
        in model.prompts[1]
    assert "[Walk] <tv> (14) -> ok" in model.prompts[2]


def test_a_new_episode_forgets_the_last_one(tiny_home):
    model = FakeModel(["[Walk] <tv> (14)"])
    policy = LLMPolicy(model)
    env = HomeEnv(tiny_home, max_steps=2)
    run_episode(env, policy)
    run_episode(env, policy)
    assert "Your last steps" not in model.prompts[2]


@pytest.mark.parametrize(("reply", "action"), [
    ("[PutBack] <plate> (16) <sofa> (15) now", "[PutBack] <plate> (16) <sofa> (15)"),
    ("Step: [ Walk ]  <tv>  (1.14)", "[ Walk ] <tv> (1.14)"),
    ("\n  no step here\nreally", "no step here"),
    ("", ""),
])
def test_parse_reply(reply, action):
    assert parse_reply(reply) == action
