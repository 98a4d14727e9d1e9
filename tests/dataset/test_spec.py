import pytest

from homesim.dataset.spec import (
    AGENT_NAMES,
    MODALITIES,
    PROFILES,
    DatasetConfig,
    EpisodeSpec,
    draw_spec,
    episode_key,
    plan_episodes,
)
from homesim.errors import HomesimError


def test_agent_names_are_the_renderers():
    from homesim.render.agent import AGENTS

    assert set(AGENT_NAMES) == set(AGENTS)


def test_an_episode_draws_from_its_own_stream():
    config = DatasetConfig(n=5, seed=3)
    programs = [("a", "[Walk] <tv> (1)"), ("b", "[Walk] <sofa> (1)")]
    specs = plan_episodes(config, programs)
    assert [s.program_id for s in specs] == ["a", "b", "a", "b", "a"]
    # Episode 4 alone, or after the others: the same choices.
    assert draw_spec(config, 4, "a", "[Walk] <tv> (1)") == specs[4]
    assert len({(s.render_seed, s.ground_seed, s.placement_seed) for s in specs}) == 5
    other = plan_episodes(DatasetConfig(n=5, seed=4), programs)
    assert [s.render_seed for s in other] != [s.render_seed for s in specs]


def test_spec_and_config_round_trip_through_dicts():
    config = DatasetConfig(n=7, modalities=("rgb", "flow"), homes=("scene2",))
    assert DatasetConfig.from_dict(config.to_dict()) == config
    spec = draw_spec(config, 2, "p", "[Walk] <tv> (1)")
    assert EpisodeSpec.from_dict(spec.to_dict()) == spec
    assert spec.key == episode_key(2) == "ep-000002"


def test_bad_options_are_refused():
    with pytest.raises(HomesimError, match="unknown modality 'normals'"):
        DatasetConfig(modalities=("rgb", "normals"))
    with pytest.raises(HomesimError, match="at least 1"):
        DatasetConfig(n=0)
    # Before any episode is planned, not as one failed episode after another.
    with pytest.raises(HomesimError, match="image size 33x24: width and height must be even"):
        DatasetConfig(width=33, height=24)
    with pytest.raises(HomesimError, match="fps 0 out of range"):
        DatasetConfig(fps=0)
    with pytest.raises(HomesimError, match="no programs"):
        plan_episodes(DatasetConfig(n=1), [])


def test_profiles_name_what_episodes_keep():
    """``full`` is the default config; ``learn`` what the video models read."""
    from homesim.learn.video.cache import VideoFormat

    assert DatasetConfig.from_profile("full") == DatasetConfig()
    learn = DatasetConfig.from_profile("learn", n=3)
    video = VideoFormat()
    assert (learn.width, learn.height, learn.fps) == (video.width, video.height, video.fps)
    assert learn.modalities == ("rgb", "class") and learn.gt_stride == 1 and learn.n == 3
    assert DatasetConfig.from_profile("learn", fps=8).fps == 8  # options override it
    assert PROFILES["full"].modalities == MODALITIES
    with pytest.raises(HomesimError, match="unknown profile 'tiny'; choose from full, learn"):
        DatasetConfig.from_profile("tiny")
