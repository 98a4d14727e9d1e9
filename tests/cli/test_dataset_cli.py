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


def test_a_profile_sets_size_rate_and_modalities_and_options_override_it(tmp_path,
                                                                         monkeypatch):
    made = []

    def generate(config, out, **kwargs):
        made.append(config)
        raise SystemExit(0)  # the config is all this test looks at

    monkeypatch.setattr("homesim.dataset.generate_dataset", generate)
    assert main(["dataset", "generate", "--out", str(tmp_path / "a"), "--profile", "learn"]) == 0
    assert main(["dataset", "generate", "--out", str(tmp_path / "b"), "--profile", "learn",
                 "--fps", "8", "--modalities", "rgb"]) == 0
    learn, changed = made
    assert (learn.width, learn.height, learn.fps, learn.modalities) == (64, 48, 4,
                                                                         ("rgb", "class"))
    assert (changed.width, changed.fps, changed.modalities) == (64, 8, ("rgb",))
    assert main(["dataset", "generate", "--out", str(tmp_path / "c"), "--profile", "tiny"]) == 2


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


def test_a_learn_profile_data_set_keeps_rgb_and_class_only_and_verifies(tmp_path, capsys):
    from homesim.dataset.verify import iter_episodes
    from homesim.render.gl import gl_available

    if not gl_available():
        pytest.skip("no OpenGL context")
    program = tmp_path / "p.txt"
    program.write_text("Watch TV\nI turn on the TV.\n\n[Walk] <television> (1)\n")
    out = tmp_path / "data"
    assert main(["dataset", "generate", "--out", str(out), "--programs", str(program),
                 "--n", "1", "--profile", "learn", "--fps", "2", "--homes", "scene1",
                 "--workers", "0"]) == 0
    assert main(["dataset", "verify", str(out)]) == 0
    assert "checksums match" in capsys.readouterr().out
    (shard,) = (out / "shards").glob("*.tar")
    ((_, members),) = list(iter_episodes(shard))
    kinds = {name.split(".", 1)[1].split(".")[-2] if name.endswith(".png") else
             name.split(".", 1)[1] for name, _ in members}
    assert "class" in kinds and "mp4" in kinds and "json" in kinds
    assert not kinds & {"depth", "instance", "flow"}
