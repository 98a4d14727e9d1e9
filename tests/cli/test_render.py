import json

import pytest

from homesim.cli.main import main

pytest.importorskip("homesim.render.gl", reason="needs the render extra",
                    exc_type=ImportError)


@pytest.fixture
def graph_file(tmp_path):
    from tests.render.conftest import box_home_dict

    path = tmp_path / "home.json"
    path.write_text(json.dumps(box_home_dict()))
    return path


def test_render_writes_a_recording_and_preview(tmp_path, graph_file, capsys):
    from homesim.render import gl_available, load_recording

    if not gl_available():
        pytest.skip("no OpenGL context")
    prog = tmp_path / "p.txt"
    prog.write_text("[Walk] <tv> (22)\n[SwitchOn] <tv> (22)\n")
    out = tmp_path / "rec"
    code = main(["render", str(prog), "--graph", str(graph_file), "--out", str(out),
                 "--width", "32", "--height", "24", "--fps", "5", "--seed", "2", "--preview"])
    assert code == 0
    text = capsys.readouterr().out
    assert "frames" in text and "preview" in text
    assert (out / "preview.png").stat().st_size > 0
    meta = load_recording(out).meta
    assert meta["seed"] == 2 and meta["home"] == str(graph_file)


@pytest.mark.parametrize(("args", "pattern"), [
    (["--home", "scene1_trimmed"], "no floor boxes"),
    (["--width", "31"], "must be even"),
])
def test_render_errors_are_one_line(tmp_path, args, pattern, capsys):
    prog = tmp_path / "p.txt"
    prog.write_text("[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n")
    code = main(["render", str(prog), "--out", str(tmp_path / "o"), *args])
    assert code == 2
    err = capsys.readouterr().err
    assert pattern in err and "Traceback" not in err


def test_an_ungrounded_program_is_grounded_before_rendering(tmp_path, graph_file, capsys):
    from homesim.render import gl_available, load_recording

    if not gl_available():
        pytest.skip("no OpenGL context")
    prog = tmp_path / "p.txt"
    prog.write_text("[Walk] <apple> (1)\n[Grab] <apple> (1)\n")
    out = tmp_path / "rec"
    assert main(["render", str(prog), "--graph", str(graph_file), "--out", str(out),
                 "--width", "32", "--height", "24", "--fps", "5"]) == 0
    assert "grounded in" in capsys.readouterr().out
    steps = load_recording(out).meta["steps"]
    assert [s["step"] for s in steps] == ["[Walk] <apple> (1.24)", "[Grab] <apple> (1.24)"]


def test_a_program_that_cannot_be_grounded_is_one_line(tmp_path, graph_file, capsys):
    prog = tmp_path / "p.txt"
    prog.write_text("[Walk] <unicorn> (1)\n")
    assert main(["render", str(prog), "--graph", str(graph_file),
                 "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "cannot ground the program in" in err and "unicorn" in err
    assert err.count("\n") == 1


def test_a_grounded_program_naming_nodes_of_another_class_is_refused(tmp_path, capsys):
    # the demo file is grounded for scene1; node 410 of scene1_trimmed is a light
    from homesim.examples import load_example

    program = tmp_path / "demo.txt"
    program.write_text(str(load_example("watch_tv")))
    code = main(["render", str(program), "--out", str(tmp_path / "o"), "--home",
                 "scene1_trimmed"])
    assert code == 2
    err = " ".join(capsys.readouterr().err.split())
    assert "step 1 [Walk] <tv> (1.410): <tv> (1) is node 410, a light, not a tv" in err


def _rendering(parent, name="rec"):
    """The temporary folder of a render to parent/name, once it holds a frame."""
    for d in parent.glob(f".homesim-render-{name}-*"):
        frames = d / "frames"
        if frames.is_dir() and any(frames.iterdir()):
            return d
    return None


@pytest.mark.parametrize("signum", ["SIGINT", "SIGTERM", "SIGKILL"])
def test_an_interrupted_render_leaves_nothing_that_blocks_a_rerun(tmp_path, signum, capsys):
    """D6: Ctrl-C left video.mp4 with 239 of 401 frames and frames/ without meta.json, and
    the folder was then refused ("already holds a recording"); SIGKILL left a 48-byte
    undecodable video.mp4."""
    import signal

    from homesim.render import gl_available, load_recording
    from tests.cli.subprocess_cli import start_cli, wait_for

    if not gl_available():
        pytest.skip("no OpenGL context")
    out = tmp_path / "rec"
    args = ["render", "--home", "scene1", "--out", str(out), "--width", "32", "--height",
            "24", "--fps", "30"]
    proc = start_cli(args)
    wait_for(lambda: _rendering(tmp_path) is not None, proc, timeout=240)
    proc.send_signal(getattr(signal, signum))
    proc.communicate(timeout=60)
    assert proc.returncode in (128 + getattr(signal, signum), -signal.SIGKILL)
    assert not out.exists()
    left = [p.name for p in tmp_path.iterdir()]
    if signum == "SIGKILL":  # no clean-up is possible; the next render removes it
        assert len(left) == 1 and left[0].startswith(".homesim-render-rec-p")
    else:
        assert left == []
    assert main([*args[:-2], "--fps", "2"]) == 0  # the same folder, at once
    assert load_recording(out).num_frames > 0
    assert [p.name for p in tmp_path.iterdir()] == ["rec"]  # SIGKILL's leftover is gone


def test_render_into_an_empty_or_other_folder(tmp_path, graph_file):
    from homesim.render import gl_available, load_recording

    if not gl_available():
        pytest.skip("no OpenGL context")
    prog = tmp_path / "p.txt"
    prog.write_text("[Walk] <tv> (22)\n")
    args = ["render", str(prog), "--graph", str(graph_file), "--width", "32", "--height",
            "24", "--fps", "5"]
    empty = tmp_path / "empty"
    empty.mkdir()
    assert main([*args, "--out", str(empty)]) == 0 and load_recording(empty).num_frames > 0
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    assert main([*args, "--out", str(other)]) == 0 and load_recording(other).num_frames > 0
    assert (other / "notes.txt").read_text() == "mine"
    assert main([*args, "--out", str(other)]) == 2  # a recording is never replaced
    assert not any(p.name.startswith(".homesim-") for p in tmp_path.iterdir())
