import json

from homesim.cli.main import main


def test_synth_writes_jsonl_and_refuses_to_overwrite(tmp_path, capsys):
    out = tmp_path / "s.jsonl"
    assert main(["synth", "--n", "7", "--seed", "2", "--out", str(out)]) == 0
    lines = out.read_text().splitlines()
    assert len(lines) == 7 and json.loads(lines[0])["id"] == "synth-2-0"
    assert main(["synth", "--n", "3", "--out", str(out)]) == 2
    assert "already exists; pass --force" in capsys.readouterr().err
    assert len(out.read_text().splitlines()) == 7
    assert main(["synth", "--n", "3", "--out", str(out), "--force"]) == 0


def test_synth_bad_home_is_one_line(tmp_path, capsys):
    assert main(["synth", "--n", "1", "--home", "scene9", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert "--home scene9: not a built-in home" in err and "Traceback" not in err
