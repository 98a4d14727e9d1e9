import pytest

from homesim.cli.main import main

pytest.importorskip("pyarrow")


def test_generate_verify_and_replay_from_the_command_line(tmp_path, capsys):
    from homesim.render.gl import gl_available

    if not gl_available():
        pytest.skip("no OpenGL context")
    program = tmp_path / "p.txt"
    program.write_text("Watch TV\nI turn on the TV.\n\n[Walk] <television> (1)\n")
    out = tmp_path / "data"
    args = ["dataset", "generate", "--out", str(out), "--programs", str(program), "--n", "1",
            "--width", "32", "--height", "24", "--fps", "2", "--homes", "scene1",
            "--workers", "0"]
    assert main(args) == 0
    assert "ok: 1 episodes (0 failed)" in capsys.readouterr().out
    assert main(["dataset", "verify", str(out)]) == 0
    assert "checksums match" in capsys.readouterr().out
    assert main(["dataset", "replay", str(out), "0", "--out", str(tmp_path / "e.tar")]) == 0
    assert "identical to the data set's" in capsys.readouterr().out


def test_bad_options_are_one_line(tmp_path, capsys):
    assert main(["dataset", "generate", "--out", str(tmp_path / "d"), "--modalities",
                 "rgb,normals"]) == 2
    assert "unknown modality 'normals'" in capsys.readouterr().err
    assert main(["dataset", "verify", str(tmp_path)]) == 2
    assert "not a homesim data set" in capsys.readouterr().err


def test_a_plan_from_the_command_line_verifies_part_by_part(tmp_path, capsys):
    import json

    from homesim.render.gl import gl_available

    if not gl_available():
        pytest.skip("no OpenGL context")
    program = tmp_path / "p.txt"
    program.write_text("Watch TV\nI turn on the TV.\n\n[Walk] <television> (1)\n")
    plan = tmp_path / "plan.json"
    plan.write_text(json.dumps({"parts": [
        {"name": "train", "role": "train", "homes": ["scene1"], "share": 0.5},
        {"name": "test", "role": "test", "homes": ["scene2"], "agents": ["male2"],
         "share": 0.5}], "rows": [{"row": "all", "parts": ["test"]}]}))
    out = tmp_path / "data"
    args = ["dataset", "generate", "--out", str(out), "--programs", str(program), "--n", "2",
            "--width", "32", "--height", "24", "--fps", "2", "--plan", str(plan),
            "--workers", "0"]
    assert main([*args, "--agents", "male1"]) == 2
    assert "leave out --homes and --agents" in capsys.readouterr().err
    assert main(args) == 0
    assert capsys.readouterr().out.count("ok: 1 episodes (0 failed)") == 2
    assert main(["dataset", "verify", str(out)]) == 0
    assert capsys.readouterr().out.count("checksums match") == 2
