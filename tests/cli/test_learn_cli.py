import json

import pytest

from homesim.cli.main import main

pytest.importorskip("torch")


def test_train_then_eval_prints_table_3(tmp_path, capsys):
    runs = tmp_path / "runs"
    args = ["learn", "train", "--task", "text2prog", "--data", "synthetic", "--synth-n", "30",
            "--mle-epochs", "1", "--pg-epochs", "1", "--batch-size", "8", "--out", str(runs)]
    assert main(args) == 0
    assert (runs / "synthetic" / "pg_lcs_sim.pt").is_file()
    assert main(args) == 2
    assert "pass --force" in capsys.readouterr().err
    md = tmp_path / "results.md"
    assert main(["learn", "eval", "--runs", str(runs), "--markdown", str(md)]) == 0  # both
    out = " ".join(capsys.readouterr().out.split())
    assert "Simulator %" in out and "NN retrieval (MiniLM)" in out
    assert f"skipped real: nothing trained in {runs / 'real'}" in out
    assert "| PG (LCS+Sim) + constrained decoding |" in md.read_text()
    assert (runs / "synthetic" / "results.json").is_file()


def test_unknown_task_and_missing_checkpoints_are_one_line(tmp_path, capsys):
    assert main(["learn", "train", "--task", "img2prog", "--out", str(tmp_path)]) == 2
    assert "--task img2prog: choose from text2prog, video2prog" in capsys.readouterr().err
    assert main(["learn", "train", "--task", "video2prog", "--out", str(tmp_path)]) == 2
    assert "--data both: with --task video2prog" in capsys.readouterr().err
    assert main(["learn", "eval", "--runs", str(tmp_path), "--data", "real"]) == 2
    err = capsys.readouterr().err
    assert "checkpoint not found" in err and "Traceback" not in err


def test_train_refuses_any_existing_checkpoint_before_training(tmp_path, capsys):
    (tmp_path / "synthetic").mkdir()
    (tmp_path / "synthetic" / "pg_lcs.pt").write_bytes(b"mine")
    args = ["learn", "train", "--data", "synthetic", "--out", str(tmp_path)]
    assert main(args) == 2
    assert "pg_lcs.pt: already exists; pass --force" in " ".join(capsys.readouterr().err.split())
    assert (tmp_path / "synthetic" / "pg_lcs.pt").read_bytes() == b"mine"


def test_out_naming_a_file_is_one_line(tmp_path, capsys):
    out = tmp_path / "runs"
    out.write_text("a file")
    assert main(["learn", "train", "--data", "synthetic", "--out", str(out)]) == 2
    err = " ".join(capsys.readouterr().err.split())
    assert "runs: not a folder; --out names the run folder" in err and "internal" not in err


def test_device_auto_is_cpu_without_cuda_and_cuda_is_refused(capsys):
    import torch

    from homesim.cli.learn import _torch

    if torch.cuda.is_available():
        assert _torch(1, "auto") == "cuda"
    else:
        assert _torch(1, "auto") == "cpu"
        assert main(["learn", "table", "--out", "x", "--device", "cuda"]) == 2
        assert "no CUDA device" in capsys.readouterr().err
    assert main(["learn", "table", "--out", "x", "--device", "tpu"]) == 2
    assert "--device tpu: choose from auto, cpu, cuda" in capsys.readouterr().err


@pytest.fixture
def writer_on_small_data(small_writer, monkeypatch):
    """`homesim learn write` answers with the small writer (not one fitted on all 518)."""
    from homesim.learn.rerank import program_writer as writer

    monkeypatch.setattr(writer, "real_writer", lambda fit=True: small_writer)
    return small_writer


def test_write_prints_a_program_that_homesim_run_reads(writer_on_small_data, tmp_path, capsys):
    out = tmp_path / "tv.txt"
    args = ["learn", "write", "Turn on the TV and watch it from the sofa.", "--home", "scene2",
            "--out", str(out)]
    assert main(args) == 0
    captured = capsys.readouterr()
    assert captured.out.startswith("Watch TV\nTurn on the TV and watch it from the sofa.\n\n[")
    assert "title guessed: Watch TV" in captured.err and "runs in scene2" in captured.err
    assert out.read_text() == captured.out
    assert main(["run", str(out), "--home", "scene2"]) == 0
    capsys.readouterr()
    assert main(args) == 2  # --out exists
    assert "pass --force" in capsys.readouterr().err
    assert main(["learn", "write", "watch tv", "--title", "Watch TV", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["home"] == "scene1" and data["title_given"] and data["run"]["executable"]


def test_write_bad_input_is_one_line(writer_on_small_data, capsys):
    assert main(["learn", "write", "  "]) == 2
    assert capsys.readouterr().err.strip() == "error: description: empty"
    assert main(["learn", "write", "x" * 2001]) == 2
    assert "over the limit of 2000 (MAX_DESCRIPTION_CHARS)" in capsys.readouterr().err
    assert main(["learn", "write", "watch tv", "--home", "nowhere"]) == 2
    assert "unknown home 'nowhere'" in capsys.readouterr().err


def test_write_reads_the_description_from_stdin(writer_on_small_data, monkeypatch, capsys):
    import io

    monkeypatch.setattr("sys.stdin", io.StringIO("Switch on the light.\n"))
    assert main(["learn", "write", "-", "--title", "Turn on light"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("Turn on light\nSwitch on the light.\n\n[") and "<light>" in out


def test_write_bad_text_is_refused_before_the_model_loads(monkeypatch, capsys, tmp_path):
    """D12: ``homesim learn write $'\\xff tv'`` (a byte not UTF-8: a lone surrogate in
    argv) exited 70, and only after the writer was loaded or fitted."""
    from homesim.learn.rerank import program_writer

    def no_model(fit=True):
        raise AssertionError("the model was loaded for a text that is refused")

    monkeypatch.setattr(program_writer, "real_writer", no_model)
    assert main(["learn", "write", "\udcff tv"]) == 2
    assert "description: not valid text" in capsys.readouterr().err
    assert main(["learn", "write", "tv", "--title", "\ud800"]) == 2
    assert "title: not valid text" in capsys.readouterr().err
    out = tmp_path / "x.txt"
    out.write_text("keep")
    assert main(["learn", "write", "watch tv", "--out", str(out)]) == 2
    assert "pass --force" in capsys.readouterr().err and out.read_text() == "keep"
