"""The split of folders made without a plan."""


def test_legacy_folders_split_by_home_and_agent_and_never_test_validation():
    from homesim.learn.video.splits import LEGACY, legacy_part

    assert legacy_part("ep-1", "scene2_trimmed", "female2") == "test-unseen-agents"
    assert legacy_part("ep-2", "scene5", "male1") == "val"
    assert legacy_part("ep-3", "gen-0", "female1") == "test-unseen-homes"
    assert legacy_part("ep-0", "scene1", "male1") in ("train", "test-seen")
    tested = {p for _, _, parts in LEGACY.rows for p in parts}
    assert "val" not in tested and all(LEGACY.roles[p] == "test" for p in tested)
