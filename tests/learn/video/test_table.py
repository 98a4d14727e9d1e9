"""Table 2 end to end on the tiny plan: every model, resuming, the CLI and the results
section (two seeds)."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("torch")


def test_train_resume_and_eval_video2prog(tiny_plan, tmp_path):
    from typer.testing import CliRunner

    from homesim.cli.main import app
    from homesim.learn.text.text2prog import Text2Prog

    runs = tmp_path / "runs"
    args = ["learn", "train", "--task", "video2prog", "--data", str(tiny_plan), "--out",
            str(runs), "--frame-epochs", "1", "--seg-epochs", "1", "--clip-epochs", "2",
            "--mle-epochs", "2", "--pg-epochs", "1", "--seeds", "2", "--frame-size",
            "32x24", "--video-cache", str(tmp_path / "cache"), "--device", "cpu"]
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 0, res.output
    model = Text2Prog.load(runs / "seed-1" / "pg_lcs_sim.pt")
    assert model.model.config.feature_dim == 128 and len(model.steps) > 1  # config + vocab
    assert (runs / "features" / "seg.npy").is_file() and (runs / "frames" / "segment.json")
    weights = (runs / "seed-0" / "clip_seg_trn.pt").read_bytes()
    (runs / "seed-0" / "mle.pt").unlink()  # as if stopped before the seed's MLE
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 0, res.output
    assert "clip_" not in res.output and "seed 0 mle" in res.output  # only what was missing
    assert (runs / "seed-0" / "clip_seg_trn.pt").read_bytes() == weights
    markdown = tmp_path / "results.md"
    markdown.write_text("# Table 3\n")
    res = CliRunner().invoke(app, ["learn", "eval", "--task", "video2prog", "--runs",
                                   str(runs), "--markdown", str(markdown), "--device", "cpu"])
    assert res.exit_code == 0, res.output
    result = json.loads((runs / "results.json").read_text())
    truth = result["programs"]["seen"]["Ground truth (reference)"]
    assert truth["steps"]["mean"] == 1.0 and truth["simulator"]["seeds"] == [1.0, 1.0]
    assert set(result["programs"]["all"]) >= {
        "Random retrieval", "MLE", "PG (LCS)", "PG (LCS+Sim)", "MLE + constrained decoding",
        "PG (LCS+Sim) + constrained decoding"}
    constrained = result["programs"]["all"]["PG (LCS+Sim) + constrained decoding"]
    assert constrained["simulator"]["mean"] == 1.0  # executable by construction
    clips = result["clips"]["all"]
    assert {"Random retrieval", "TRN (RGB)", "Single frame (RGB)",
            "TRN (predicted segmentation)", "TRN (predicted segmentation + pose + hands)",
            "TRN (ground-truth class maps: oracle)"} <= set(clips)
    assert all(0 <= row["step"]["lo"] <= row["step"]["hi"] <= 100 for row in clips.values())
    assert "all test" in result["segment"]["scores"]
    assert 0 <= result["pose"]["scores"]["all test"]["pck"] <= 100
    text = markdown.read_text()
    assert "Pose network (mean joint error" in text
    assert text.startswith("# Table 3\n") and "Table 2" in text and " ± " in text
    assert "*.528*" in text and "*24.6*" in text  # the paper's PG (LCS+Sim), seen homes
    assert "--plan tiny --n 4" in text and "--seeds 2 --frame-size 32x24" in text


def test_a_sitting_stopped_inside_the_frame_stage_keeps_the_times_of_its_done_stages(
        tiny_plan, tmp_path, monkeypatch):
    from homesim.learn.video import table

    def stop(run):
        raise KeyboardInterrupt  # the sitting ends while the segmentation network trains

    monkeypatch.setattr(table, "_segmentation", stop)
    config = table.VideoRunConfig(str(tiny_plan), frame_size="32x24", frame_epochs=1,
                                  cache=str(tmp_path / "cache"))
    with pytest.raises(KeyboardInterrupt):
        table.train_video(config, tmp_path / "run")
    seconds = json.loads((tmp_path / "run" / "train.json").read_text())["seconds"]
    assert {"read", "frames_rgb", "frames_oracle"} <= set(seconds)
    with pytest.raises(KeyboardInterrupt):  # the next sitting adds its reading time
        table.train_video(config, tmp_path / "run")
    again = json.loads((tmp_path / "run" / "train.json").read_text())["seconds"]
    assert again["frames_rgb"] == seconds["frames_rgb"] and again["read"] >= seconds["read"]


def test_settings_file_replaces_fields_and_refuses_unknown_ones(tmp_path):
    from homesim.errors import HomesimError
    from homesim.learn.video.table import VideoRunConfig

    path = tmp_path / "settings.json"
    path.write_text('{"clip_lr": 0.003, "pg_epochs": 4, "clip_hidden": 128, "pg_lr": 1}')
    cfg = VideoRunConfig("data").with_settings(path)
    assert (cfg.clip_lr, cfg.pg_epochs, cfg.clip_hidden, cfg.pg_lr) == (0.003, 4, 128, 1)
    assert cfg.data == "data" and cfg.mle_epochs == VideoRunConfig("data").mle_epochs
    for text, words in (('{"clip_lrr": 1}', "'clip_lrr' is not a setting"),
                        ('{"data": "x"}', "'data' is not a setting"),
                        ('{"pg_epochs": 1.5}', "pg_epochs must be an integer"),
                        ('[1]', "a JSON object"), ('{', "not a readable JSON")):
        path.write_text(text)
        with pytest.raises(HomesimError, match=words):
            VideoRunConfig("data").with_settings(path)


def test_train_subset_is_nested_and_keeps_store_order():
    from homesim.learn.video.table import train_subset

    class Ep:
        def __init__(self, key):
            self.key = key

    eps = [Ep(f"train/ep-{i:06d}") for i in range(40)]
    quarter, half = train_subset(eps, 0.25), train_subset(eps, 0.5)
    assert len(quarter) == 10 and len(half) == 20 and train_subset(eps, 1.0) is eps
    assert {e.key for e in quarter} < {e.key for e in half}
    assert [e.key for e in half] == sorted(e.key for e in half)  # store order
    assert {e.key for e in quarter} != {e.key for e in eps[:10]}  # not the first ten


def test_end_to_end_clip_models_train_their_frame_encoders_and_are_scored(tiny_plan,
                                                                         tmp_path):
    """`clip_end_to_end`: each clip model holds the frame stage's encoder of its input
    and fine-tunes it; the programs and the table read the frames and maps through it."""
    import torch

    from homesim.learn.video import table
    from homesim.learn.video.eval import evaluate_video

    config = table.VideoRunConfig(str(tiny_plan), frame_size="32x24", frame_epochs=1,
                                  seg_epochs=1, clip_epochs=1, mle_epochs=1, pg_epochs=1,
                                  clip_end_to_end=True, cache=str(tmp_path / "cache"))
    out = tmp_path / "run"
    table.train_video(config, out)
    for inp, kind in table.CLIP_MODELS:
        model, _, _ = table.load_clip_model(table.clip_path(out / "seed-0", kind, inp))
        if inp not in table.ENCODED:  # joined features: read fixed
            assert model.backbone is None
            continue
        encoder = torch.load(out / "frames" / f"{inp}.pt", weights_only=True)["state"]
        tuned = model.backbone.state_dict()
        assert tuned.keys() == encoder.keys()
        assert any(not torch.equal(tuned[k], encoder[k]) for k in encoder)
    result = evaluate_video(out)
    assert 0 <= result["clips"]["all"]["TRN (predicted segmentation)"]["action"]["mean"] <= 100
    assert result["programs"]["all"]["MLE"]["steps"]["mean"] >= 0


def test_frame_grid_is_cells_across_by_down_or_a_one_line_error():
    from homesim.errors import HomesimError
    from homesim.learn.video.table import _grid

    assert _grid("4x3") == (4, 3) and _grid("1X1") == (1, 1)
    for bad in ("4", "0x3", "ax3", "4x3x2"):
        with pytest.raises(HomesimError, match=r"frame_grid .*cells across x down"):
            _grid(bad)
