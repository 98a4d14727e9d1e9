import json

import pytest

from homesim.dataset.card import write_card


def test_card_counts_table_and_figures(tiny_dataset, tmp_path):
    paths = write_card(tiny_dataset, tmp_path / "card")
    assert sorted(p.name for p in paths) == ["actions.png", "contact_sheet.png", "objects.png",
                                             "stats.json"]
    stats = json.loads((tmp_path / "card" / "stats.json").read_text())
    assert (stats["episodes"], stats["made"], stats["failed"]) == (3, 3, 0)
    assert stats["homes"] == {"scene1": 3} and sum(stats["agents"].values()) == 3
    assert stats["table1a"]["programs"] == 3 and stats["table1a"]["avg_steps"] == 2
    assert dict(map(tuple, stats["actions"])) == {"Walk": 3, "SwitchOn": 3}
    assert stats["hours"] * 3600 * stats["fps"] == pytest.approx(stats["frames"])
    assert stats["bytes_per_frame"] > 0


def test_card_of_a_run_not_finished_counts_the_finished_shards(tiny_dataset, tmp_path):
    import shutil

    copy = tmp_path / "partial"
    shutil.copytree(tiny_dataset, copy)
    (copy / "episodes.parquet").unlink()
    info = json.loads((copy / "dataset.json").read_text())
    (copy / "dataset.json").write_text(json.dumps({"format": info["format"],
                                                   "config": info["config"]}))
    for p in (copy / "shards").glob("shard-000001.*"):
        p.unlink()
    write_card(copy, tmp_path / "card")
    stats = json.loads((tmp_path / "card" / "stats.json").read_text())
    assert (stats["episodes"], stats["made"]) == (2, 2)
