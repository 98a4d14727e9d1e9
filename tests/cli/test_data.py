import pytest

from homesim.cli.main import main

pytest.importorskip("matplotlib")

WATCH = "Watch TV\nI watch TV.\n\n[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[Watch] <tv> (1)\n"


def test_stats_on_a_folder(tmp_path, capsys):
    data = tmp_path / "programs"
    data.mkdir()
    (data / "a.txt").write_text(WATCH)
    (data / "b.txt").write_text(WATCH.replace("[SwitchOn] <tv> (1)\n", ""))
    out = tmp_path / "out"
    assert main(["data", "stats", str(data), "--out", str(out)]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "Table 1(a)" in text and "Table 1(b)" in text
    assert "watch tv │ 2 │ 1 │ 2.00 │ 0.667" in text  # LCS 2 of 3 steps
    assert sorted(p.name for p in out.iterdir()) == [
        "fig4_actions.png", "fig4_objects.png", "stats.json", "stats.md", "table1c_similarity.png"]


def test_stats_on_a_bad_file_gives_one_line(tmp_path, capsys):
    data = tmp_path / "programs"
    data.mkdir()
    (data / "a.txt").write_text(WATCH)
    (data / "broken.txt").write_text("Watch TV\n\n[Walk] <tv> (1)\n")
    assert main(["data", "stats", str(data), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.replace("\n", "")  # rich wraps long lines
    assert "broken.txt: no description" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()
    assert main(["data", "stats", str(data), "--out", str(tmp_path / "out"), "--skip-bad"]) == 0
    assert "skipped" in capsys.readouterr().out


def test_stats_on_a_missing_dataset(tmp_path, capsys):
    assert main(["data", "stats", str(tmp_path / "nope")]) == 2
    assert "no such file or folder" in capsys.readouterr().err.replace("\n", "")


def test_stats_refuses_to_replace_outputs_without_force(tmp_path, capsys):
    data = tmp_path / "programs"
    data.mkdir()
    (data / "a.txt").write_text(WATCH)
    out = tmp_path / "out"
    out.mkdir()
    (out / "stats.md").write_text("my notes")
    assert main(["data", "stats", str(data), "--out", str(out)]) == 2
    assert "stats.md: already exists; pass --force" in capsys.readouterr().err.replace("\n", "")
    assert [p.name for p in out.iterdir()] == ["stats.md"]
    assert main(["data", "stats", str(data), "--out", str(out), "--force"]) == 0
    assert (out / "stats.md").read_text() != "my notes" and len(list(out.iterdir())) == 5
