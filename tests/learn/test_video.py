"""Table 2 end to end on four tiny generated episodes: clip models, video -> program,
the CLI and the results section (seconds at 32x24, 2 frames/s)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("torch")
try:  # homesim.render.gl picks MUJOCO_GL before mujoco is first imported
    import homesim.render.gl  # noqa: F401
except ImportError:
    pytest.skip("needs the render extra (mujoco)", allow_module_level=True)

PROGRAMS = {"a_tv.txt": "Watch TV\nI turn on the TV.\n\n[Walk] <television> (1)\n"
                        "[SwitchOn] <television> (1)\n",
            "b_light.txt": "Lights on\nI turn on the light.\n\n[Walk] <light> (1)\n"
                           "[SwitchOn] <light> (1)\n"}
PARTS = {"ep-000000": "train", "ep-000001": "train", "ep-000002": "test-seen",
         "ep-000003": "test-unseen"}


@pytest.fixture(scope="module")
def tiny_video(tmp_path_factory) -> Path:
    from homesim.dataset import DatasetConfig, generate_dataset
    from homesim.render.gl import BACKEND, gl_available

    if not gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={BACKEND}")
    root = tmp_path_factory.mktemp("video")
    programs = root / "programs"
    programs.mkdir()
    for name, text in PROGRAMS.items():
        (programs / name).write_text(text)
    out = root / "data"
    config = DatasetConfig(programs=str(programs), n=4, seed=0, width=32, height=24, fps=2,
                           modalities=("rgb", "class"), homes=("scene1",), shard_size=4)
    generate_dataset(config, out, workers=0)
    return out


@pytest.fixture()
def fixed_split(monkeypatch):
    from homesim.learn import videosplits

    monkeypatch.setattr(videosplits, "part_of", lambda item, seed: PARTS[item.key])


def test_split_declares_seen_and_unseen_homes():
    from types import SimpleNamespace

    from homesim.learn.videosplits import part_of, video_split

    eps = [SimpleNamespace(key=f"ep-{i}", home=h, agent=a) for i, (h, a) in enumerate(
        [("scene1", "male1"), ("scene2", "female2"), ("scene5", "male1"), ("gen-0", "female1")])]
    assert part_of(eps[1], 0) == "test-seen"  # a seen home, an agent not trained on
    assert part_of(eps[2], 0) == part_of(eps[3], 0) == "test-unseen"
    assert part_of(eps[0], 0) in ("train", "test-seen")
    assert sum(len(v) for v in video_split(eps, 0).values()) == 4


def test_mean_class_accuracy_weighs_classes_equally():
    from homesim.learn.clips import mean_class_accuracy

    # class a: 2 of 3 right; class b: 0 of 1
    assert mean_class_accuracy(["a", "a", "b", "a"], ["a", "a", "a", "b"]) == pytest.approx(
        100 * (2 / 3 + 0) / 2)


def test_write_section_keeps_the_rest(tmp_path):
    from homesim.learn.videoreport import END, START, write_section

    path = tmp_path / "results.md"
    path.write_text("# Table 3\n\nrows\n")
    write_section(path, f"{START}\nfirst\n{END}\n")
    write_section(path, f"{START}\nsecond\n{END}\n")
    text = path.read_text()
    assert text.startswith("# Table 3\n\nrows\n") and "second" in text and "first" not in text


def test_train_and_eval_video2prog(tiny_video, fixed_split, tmp_path):
    from typer.testing import CliRunner

    from homesim.cli.main import app
    from homesim.learn.text2prog import Text2Prog

    runs = tmp_path / "runs"
    res = CliRunner().invoke(app, [
        "learn", "train", "--task", "video2prog", "--data", str(tiny_video), "--out",
        str(runs), "--clip-epochs", "2", "--mle-epochs", "2", "--pg-epochs", "1",
        "--device", "cpu"])
    assert res.exit_code == 0, res.output
    model = Text2Prog.load(runs / "pg_lcs_sim.pt")
    assert model.model.config.feature_dim == 64 and len(model.steps) > 1  # config + vocab
    markdown = tmp_path / "results.md"
    markdown.write_text("# Table 3\n")
    res = CliRunner().invoke(app, ["learn", "eval", "--task", "video2prog", "--runs",
                                   str(runs), "--markdown", str(markdown), "--device", "cpu"])
    assert res.exit_code == 0, res.output
    result = json.loads((runs / "results.json").read_text())
    truth = result["programs"]["test-seen"]["Ground truth (reference)"]
    assert truth["steps"] == 1.0 and truth["simulator"] == 100.0
    assert set(result["programs"]["test-unseen"]) >= {"Random retrieval", "MLE", "PG (LCS)",
                                                        "PG (LCS+Sim)"}
    clips = result["clips"]["test-seen"]
    assert {"Random retrieval", "TRN (RGB)", "Single frame (RGB)"} <= set(clips)
    assert all(0 <= row["step"] <= 100 for row in clips.values())
    text = markdown.read_text()
    assert text.startswith("# Table 3\n") and "Table 2" in text


def test_video_data_without_class_maps_is_refused(tmp_path):
    from homesim.errors import HomesimError
    from homesim.learn.videodata import load_episodes

    with pytest.raises(HomesimError, match="no finished shards"):
        load_episodes(tmp_path)


def test_class_weights_balance_classes():
    import torch

    from homesim.learn.clips import class_weights

    w = class_weights(torch.tensor([0, 0, 0, 1]), 3)
    assert w[0] * 3 == pytest.approx(w[1] * 1) and w[2] == 0
