"""The results file holds both tables: rewriting one keeps the other."""

from pathlib import Path

from homesim.learn.video.report import END, START, with_table2, write_section


def test_text_table_rewrite_keeps_the_video_section(tmp_path: Path) -> None:
    path = tmp_path / "results.md"
    path.write_text("# Table 3\nold text rows\n", encoding="utf-8")
    write_section(path, f"{START}\n# Table 2\nvideo rows\n{END}\n")
    text = with_table2(path, "# Table 3\nnew text rows\n")
    assert "new text rows" in text and "old text rows" not in text
    assert f"{START}\n# Table 2\nvideo rows\n{END}" in text


def test_no_video_section_leaves_the_text_alone(tmp_path: Path) -> None:
    path = tmp_path / "results.md"
    path.write_text("# Table 3\n", encoding="utf-8")
    assert with_table2(path, "# new\n") == "# new\n"
    assert with_table2(tmp_path / "missing.md", "# new\n") == "# new\n"


def test_write_section_keeps_the_rest(tmp_path):
    from homesim.learn.video.report import END, START, write_section

    path = tmp_path / "results.md"
    path.write_text("# Table 3\n\nrows\n")
    write_section(path, f"{START}\nfirst\n{END}\n")
    write_section(path, f"{START}\nsecond\n{END}\n")
    text = path.read_text()
    assert text.startswith("# Table 3\n\nrows\n") and "second" in text and "first" not in text
