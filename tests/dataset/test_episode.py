"""Where an episode is made: its drawn home, else the next home its program runs in."""

import pytest

from homesim.dataset.episode import EpisodeFailed, Outcome, ground_episode, homes_to_try
from homesim.dataset.generate import load_programs
from homesim.dataset.spec import DEFAULT_HOMES, DatasetConfig, EpisodeSpec
from homesim.ground.pipeline import run_program
from homesim.program.parse import parse_program
from homesim.world.homes import load_home

SIT_AND_WATCH = """\
Watch TV
I sit on the sofa and look at the TV.

[Walk] <couch> (1)
[Sit] <couch> (1)
[LookAt] <television> (1)
"""
"""Runs in scene4 (its sofas face the TV), not in scene3 or gen-33 (their sofas do not)."""


def spec(home: str, placement_seed: int = 7) -> EpisodeSpec:
    return EpisodeSpec(3, "watch", SIT_AND_WATCH, home, "female1", render_seed=1,
                       ground_seed=2, placement_seed=placement_seed, moves=0, speed=1.0)


def test_homes_to_try_start_with_the_drawn_home_and_hold_each_once():
    order = homes_to_try(spec("scene3"), DEFAULT_HOMES)
    assert order[0] == "scene3" and sorted(order) == sorted(DEFAULT_HOMES)
    assert order == homes_to_try(spec("scene3"), DEFAULT_HOMES)  # seeded
    orders = {tuple(homes_to_try(spec("scene3", seed), DEFAULT_HOMES)) for seed in range(5)}
    assert len(orders) > 1
    assert homes_to_try(spec("scene3"), ()) == ["scene3"]


def test_an_episode_whose_program_does_not_run_in_its_home_is_made_in_the_next_it_runs_in():
    with pytest.raises(EpisodeFailed, match="does not face"):
        ground_episode(spec("scene3"))
    made = ground_episode(spec("scene3"), ("scene3", "scene4"))
    assert made.home == "scene4" and made.run.executable
    assert ground_episode(spec("scene4"), ("scene3", "scene4")).home == "scene4"


def test_where_it_runs_in_no_home_the_drawn_homes_reason_is_given():
    with pytest.raises(EpisodeFailed, match=r"step 3 \[LookAt\].*does not face tv 216"):
        ground_episode(spec("scene3"), ("scene3", "gen-33"))  # gen-33: its tv 161
    with pytest.raises(EpisodeFailed, match=r"does not face tv 161"):
        ground_episode(spec("gen-33"), ("scene3", "gen-33"))


def test_the_manifest_row_names_the_home_made_in_and_the_home_drawn():
    made = Outcome("ep-000003", 3, True, num_frames=5, home="scene4").to_row(spec("scene3"))
    assert (made["home"], made["drawn_home"]) == ("scene4", "scene3")
    failed = Outcome("ep-000003", 3, False, "grounding", "no").to_row(spec("scene3"))
    assert (failed["home"], failed["drawn_home"]) == ("scene3", "scene3")


def test_synthetic_programs_are_drawn_in_the_data_sets_homes():
    """The grammar draws in the homes the episodes are made in, not in the trimmed homes
    (there 5 of these 40 programs do not run in scene3: a seat facing another thing)."""
    home = load_home("scene3")
    programs = load_programs(DatasetConfig(n=40, seed=0, homes=("scene3",)))
    assert len(programs) == 40
    for _, text in programs:
        run = run_program(parse_program(text), home, seed=0)
        assert run.executable, run.message
