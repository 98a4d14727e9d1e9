import json

import pytest

pytest.importorskip("matplotlib")
pytest.importorskip("scipy")

from homesim.errors import DataError
from homesim.knowledge.datasets import ActivityDataset
from homesim.knowledge.stats import compute_stats
from homesim.knowledge.stats_plots import to_markdown, write_stats

from .test_stats import TINY

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def stats():
    return compute_stats(ActivityDataset.from_texts(TINY, "tiny"))


def test_write_stats(stats, tmp_path):
    written = write_stats(stats, tmp_path / "out")
    names = sorted(p.name for p in written)
    assert names == ["fig4_actions.png", "fig4_objects.png", "stats.json", "stats.md",
                     "table1c_similarity.png"]
    for path in written:
        if path.suffix == ".png":
            assert path.read_bytes()[:8] == PNG and path.stat().st_size > 5000
    data = json.loads((tmp_path / "out" / "stats.json").read_text())
    assert data["summary"]["programs"] == 3
    assert data["similarity"]["values"][0][0] is None  # nan -> null
    assert data["objects"][0] == ["tv", 5]


def test_markdown_tables(stats):
    md = to_markdown(stats)
    assert "| 3 | 2 | 3.33 | 1.33 | 4.67 |" in md
    assert "| watch tv | 2 | 1 | 3.00 | 0.750 |" in md
    assert "same activity: 0.750; different activities: 0.000" in md
    assert "| 1 | Walk | 3 | tv | 5 |" in md


def test_output_must_be_a_folder(stats, tmp_path):
    file = tmp_path / "file"
    file.write_text("x")
    with pytest.raises(DataError, match="file"):
        write_stats(stats, file)
    assert file.read_text() == "x"
