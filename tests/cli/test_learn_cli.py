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
    assert main(["learn", "train", "--task", "prog2dance", "--out", str(tmp_path)]) == 2
    assert "--task prog2dance: choose from text2prog, video2prog" in capsys.readouterr().err
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
