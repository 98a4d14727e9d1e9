"""The video split: seen and unseen homes and agents."""


def test_split_declares_seen_and_unseen_homes_and_agents():
    from types import SimpleNamespace

    from homesim.learn.video.splits import part_of, test_rows, video_split

    eps = [SimpleNamespace(key=f"ep-{i}", home=h, agent=a) for i, (h, a) in enumerate(
        [("scene1", "male1"), ("scene2_trimmed", "female2"), ("scene5", "male1"),
         ("gen-0", "female1")])]
    assert part_of(eps[0]) in ("train", "test-seen")
    assert part_of(eps[1]) == "test-unseen-agents"  # a seen home, an agent not trained on
    assert part_of(eps[2]) == "val" and part_of(eps[3]) == "test-unseen-homes"
    parts = video_split(eps)
    assert sum(len(v) for v in parts.values()) == 4
    rows = test_rows(parts)
    assert [e.key for e in rows["unseen-homes"]] == ["ep-2", "ep-3"]  # scene5 and gen-*
    assert len(rows["all"]) == 4 - len(parts["train"])
