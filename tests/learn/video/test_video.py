"""Table 2 end to end on four tiny generated episodes: clip models, video -> program,
the CLI and the results section (seconds at 32x24, 2 frames/s; two seeds)."""

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
PARTS = {"ep-000000": "train", "ep-000001": "train", "ep-000002": "val",
         "ep-000003": "test-seen"}


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
    from homesim.learn.video import splits as videosplits

    monkeypatch.setattr(videosplits, "part_of", lambda item: PARTS[item.key])


def test_split_declares_seen_and_unseen_homes_and_agents():
    from types import SimpleNamespace

    from homesim.learn.video.splits import part_of, test_rows, video_split

    eps = [SimpleNamespace(key=f"ep-{i}", home=h, agent=a) for i, (h, a) in enumerate(
        [("scene1", "male1"), ("scene2_trimmed", "female2"), ("scene5", "male1"),
         ("gen-0", "female1")])]
    assert part_of(eps[0]) in ("train", "test-seen")
    assert part_of(eps[1]) == "test-unseen-agents"  # a seen home, an agent not trained on
    assert part_of(eps[2]) == "val" and part_of(eps[3]) == "test-unseen-homes"
    parts = video_split(eps)
    assert sum(len(v) for v in parts.values()) == 4
    rows = test_rows(parts)
    assert [e.key for e in rows["unseen-homes"]] == ["ep-2", "ep-3"]  # scene5 and gen-*
    assert len(rows["all"]) == 4 - len(parts["train"])


def test_frames_are_resampled_to_the_clip_rate():
    from homesim.learn.video.cache import VideoFormat, kept_frames

    assert kept_frames(31, 15, 8).tolist() == [0, 2, 4, 6, 8, 9, 11, 13, 15, 17, 19, 21, 22,
                                               24, 26, 28, 30]
    assert kept_frames(5, 2, 8).tolist() == [0, 1, 2, 3, 4]  # never more than the source
    assert VideoFormat.parse("96X72").tag == "96x72@4"


def test_bad_frame_size_is_one_clear_error():
    from homesim.errors import HomesimError
    from homesim.learn.video.cache import VideoFormat

    with pytest.raises(HomesimError, match="WIDTHxHEIGHT"):
        VideoFormat.parse("64by48")


def test_reduced_shards_are_cached(tiny_video, tmp_path):
    import numpy as np

    from homesim.learn.video.cache import VideoFormat
    from homesim.learn.video.data import load_episodes

    fmt = VideoFormat(16, 12, 4)
    first, index = load_episodes(tiny_video, fmt, tmp_path)
    assert len(list(tmp_path.glob("16x12@4/*.npz"))) == 4  # one per episode
    again, _ = load_episodes(tiny_video, fmt, tmp_path)
    assert [e.key for e in again] == [e.key for e in first]
    assert all(np.array_equal(a.frames, b.frames) and np.array_equal(a.classes, b.classes)
               for a, b in zip(first, again, strict=True))
    ep = first[0]
    assert ep.frames.shape[1:] == (3, 12, 16) and ep.fps == 2
    assert np.allclose(ep.classes.sum(1), 1.0) and len(index) == ep.classes.shape[1]


def test_mean_class_accuracy_weighs_classes_equally():
    from homesim.learn.video.clips import mean_class_accuracy

    # class a: 2 of 3 right; class b: 0 of 1
    assert mean_class_accuracy(["a", "a", "b", "a"], ["a", "a", "a", "b"]) == pytest.approx(
        100 * (2 / 3 + 0) / 2)


def test_write_section_keeps_the_rest(tmp_path):
    from homesim.learn.video.report import END, START, write_section

    path = tmp_path / "results.md"
    path.write_text("# Table 3\n\nrows\n")
    write_section(path, f"{START}\nfirst\n{END}\n")
    write_section(path, f"{START}\nsecond\n{END}\n")
    text = path.read_text()
    assert text.startswith("# Table 3\n\nrows\n") and "second" in text and "first" not in text


def test_train_and_eval_video2prog(tiny_video, fixed_split, tmp_path):
    from typer.testing import CliRunner

    from homesim.cli.main import app
    from homesim.learn.text.text2prog import Text2Prog

    runs = tmp_path / "runs"
    res = CliRunner().invoke(app, [
        "learn", "train", "--task", "video2prog", "--data", str(tiny_video), "--out",
        str(runs), "--clip-epochs", "2", "--mle-epochs", "2", "--pg-epochs", "1",
        "--seeds", "2", "--frame-size", "32x24", "--video-cache", str(tmp_path / "cache"),
        "--device", "cpu"])
    assert res.exit_code == 0, res.output
    model = Text2Prog.load(runs / "seed-1" / "pg_lcs_sim.pt")
    assert model.model.config.feature_dim == 64 and len(model.steps) > 1  # config + vocab
    markdown = tmp_path / "results.md"
    markdown.write_text("# Table 3\n")
    res = CliRunner().invoke(app, ["learn", "eval", "--task", "video2prog", "--runs",
                                   str(runs), "--markdown", str(markdown), "--device", "cpu"])
    assert res.exit_code == 0, res.output
    result = json.loads((runs / "results.json").read_text())
    truth = result["programs"]["seen"]["Ground truth (reference)"]
    assert truth["steps"]["mean"] == 1.0 and truth["simulator"]["values"] == [100.0, 100.0]
    assert set(result["programs"]["unseen-homes"]) >= {
        "Random retrieval", "MLE", "PG (LCS)", "PG (LCS+Sim)", "MLE + constrained decoding"}
    constrained = result["programs"]["all"]["PG (LCS+Sim) + constrained decoding"]
    assert constrained["simulator"]["mean"] == 100.0  # executable by construction
    clips = result["clips"]["all"]
    assert {"Random retrieval", "TRN (RGB)", "Single frame (RGB)"} <= set(clips)
    assert all(0 <= row["step"]["mean"] <= 100 for m, row in clips.items() if "gap" not in m)
    gap = clips["Oracle-perception gap (oracle TRN - RGB TRN)"]["action"]["values"]
    assert gap == [o - r for o, r in zip(clips["TRN (oracle perception: class maps)"]["action"][
        "values"], clips["TRN (RGB)"]["action"]["values"], strict=True)]
    text = markdown.read_text()
    assert text.startswith("# Table 3\n") and "Table 2" in text and " ± " in text
    assert "--seeds 2 --frame-size 32x24" in text  # the exact command


def test_a_folder_that_is_not_a_data_set_is_refused(tmp_path):
    from homesim.errors import HomesimError
    from homesim.learn.video.data import load_episodes

    with pytest.raises(HomesimError, match="not a data set folder"):
        load_episodes(tmp_path)


def test_class_weights_balance_classes():
    import torch

    from homesim.learn.video.clips import class_weights

    w = class_weights(torch.tensor([0, 0, 0, 1]), 3)
    assert w[0] * 3 == pytest.approx(w[1] * 1) and w[2] == 0


def test_staged_episodes_of_a_running_generation_are_cached(tiny_video, tmp_path):
    import json
    import shutil

    from homesim.learn.video.cache import VideoFormat, cache_file, warm_staged

    shard = json.loads((tiny_video / "shards" / "shard-000000.json").read_text())
    row = shard["rows"][0]
    running = tmp_path / "running"
    (running / "staging").mkdir(parents=True)
    shutil.copy(tiny_video / "shards" / "shard-000000.tar", running / "staging" / "ep-000000.tar")
    (running / "staging" / "ep-000000.json").write_text(json.dumps(row))
    (running / "staging" / "ep-000009.json").write_text(json.dumps({**row, "key": "ep-000009",
                                                                    "sha256": "gone"}))
    fmt, cache = VideoFormat(16, 12, 4), tmp_path / "cache"
    assert warm_staged(running, fmt, cache) >= 1
    assert cache_file(cache, row["sha256"], fmt).is_file()
    assert not cache_file(cache, "gone", fmt).exists()  # its tar was not there: skipped
