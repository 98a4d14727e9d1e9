import json
import signal

import pytest

from homesim.cli.main import main
from tests.cli.subprocess_cli import start_cli, wait_for


def test_synth_writes_jsonl_and_refuses_to_overwrite(tmp_path, capsys):
    out = tmp_path / "s.jsonl"
    assert main(["synth", "--n", "7", "--seed", "2", "--out", str(out)]) == 0
    lines = out.read_text().splitlines()
    assert len(lines) == 7 and json.loads(lines[0])["id"] == "synth-2-0"
    assert main(["synth", "--n", "3", "--out", str(out)]) == 2
    assert "already exists; pass --force" in capsys.readouterr().err
    assert len(out.read_text().splitlines()) == 7
    assert main(["synth", "--n", "3", "--out", str(out), "--force"]) == 0


def test_synth_description_styles(tmp_path, capsys):
    from homesim.synth import generate

    for style in ("people", "templates"):
        out = tmp_path / f"{style}.jsonl"
        assert main(["synth", "--n", "3", "--seed", "4", "--descriptions", style,
                     "--out", str(out)]) == 0
        texts = [json.loads(line)["description"] for line in out.read_text().splitlines()]
        assert texts == [sp.program.description for sp in generate(3, 4, style=style)]
    default = tmp_path / "default.jsonl"
    assert main(["synth", "--n", "3", "--seed", "4", "--out", str(default)]) == 0
    assert default.read_text() == (tmp_path / "people.jsonl").read_text()
    assert main(["synth", "--n", "1", "--descriptions", "poems", "--out", str(tmp_path / "x")]) == 2
    assert "--descriptions poems: choose people or templates" in capsys.readouterr().err


def test_synth_bad_home_is_one_line(tmp_path, capsys):
    assert main(["synth", "--n", "1", "--home", "scene9", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert "--home scene9: not a built-in home" in err and "Traceback" not in err


def test_out_folder_fails_before_any_work(tmp_path, capsys):
    assert main(["synth", "--n", "100000", "--out", str(tmp_path), "--force"]) == 2
    err = capsys.readouterr().err
    assert "is a folder; give a file name" in err and "internal error" not in err


def test_a_users_part_file_is_left_alone(tmp_path):
    out = tmp_path / "s.jsonl"
    part = tmp_path / "s.jsonl.part"
    part.write_text("precious\n")
    assert main(["synth", "--n", "2", "--out", str(out)]) == 0
    assert part.read_text() == "precious\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.jsonl", "s.jsonl.part"]


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_interrupted_synth_leaves_the_old_file_and_nothing_else(tmp_path, signum):
    out = tmp_path / "s.jsonl"
    out.write_text("old\n")
    proc = start_cli(["synth", "--n", "1000000", "--out", str(out), "--force"])
    wait_for(lambda: any(p.name.startswith(".homesim-") for p in tmp_path.iterdir()), proc)
    proc.send_signal(signum)
    assert proc.wait(timeout=60) == 128 + signum
    assert out.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["s.jsonl"]
