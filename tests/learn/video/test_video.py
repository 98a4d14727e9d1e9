"""Table 2 end to end on a tiny generated plan (two training episodes, one validation,
one test; 32x24 at 2 frames/s; two seeds): the frame store, every model, resuming, the
CLI and the results section."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
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
PLAN = {"name": "tiny",
        "parts": [{"name": "train", "role": "train", "homes": ["scene1"],
                   "agents": ["male1"], "share": 0.5},
                  {"name": "val", "role": "val", "homes": ["scene2"], "share": 0.25},
                  {"name": "test", "role": "test", "homes": ["scene1"], "share": 0.25}],
        "rows": [{"row": "seen", "label": "seen homes and agents", "parts": ["test"]},
                 {"row": "all", "label": "all test episodes", "parts": ["test"]}]}


@pytest.fixture(scope="module")
def tiny_plan(tmp_path_factory) -> Path:
    from homesim.dataset import DatasetConfig
    from homesim.dataset.generate import generate_plan
    from homesim.dataset.plan import Plan
    from homesim.render.gl import BACKEND, gl_available

    if not gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={BACKEND}")
    root = tmp_path_factory.mktemp("video")
    programs = root / "programs"
    programs.mkdir()
    for name, text in PROGRAMS.items():
        (programs / name).write_text(text)
    config = DatasetConfig(programs=str(programs), width=32, height=24, fps=2,
                           modalities=("rgb", "class"), shard_size=4)
    generate_plan(Plan.from_dict(PLAN), 4, root / "plan", config, workers=0)
    return root / "plan"


def test_legacy_folders_split_by_home_and_agent_and_never_test_validation():
    from homesim.learn.video.splits import LEGACY, legacy_part

    assert legacy_part("ep-1", "scene2_trimmed", "female2") == "test-unseen-agents"
    assert legacy_part("ep-2", "scene5", "male1") == "val"
    assert legacy_part("ep-3", "gen-0", "female1") == "test-unseen-homes"
    assert legacy_part("ep-0", "scene1", "male1") in ("train", "test-seen")
    tested = {p for _, _, parts in LEGACY.rows for p in parts}
    assert "val" not in tested and all(LEGACY.roles[p] == "test" for p in tested)


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


def test_a_clip_is_labelled_by_its_middle_frame():
    from homesim.learn.video.clips import FRAMES, clip_set

    ep = SimpleNamespace(key="k", start=10, length=12, fps=4,
                         steps=["[Walk] <tv> (1)", "[SwitchOn] <tv> (1)"])
    step = np.full(30, -1)
    step[10:13], step[13:22] = 0, 1  # frames 0-2 walk, 3-11 switch on: [0, 8) shows
    # walking least, but its middle frame (4) switches on
    clips = clip_set([ep], step)  # windows [0, 8) and no second one (12 frames)
    assert clips.steps == ["[SwitchOn] <tv>"] and clips.actions == ["SwitchOn"]
    assert clips.rows.shape == (1, FRAMES) and clips.rows[0, 0] == 10
    hopped = clip_set([ep], step, hop=1.0)  # [0, 8) and [4, 12)
    assert hopped.steps == ["[SwitchOn] <tv>", "[SwitchOn] <tv>"]
    step[14:22] = -1  # the middle frame shows nothing: no clip
    assert clip_set([ep], step).steps == []


def test_mean_class_accuracy_weighs_classes_equally():
    from homesim.learn.video.clips import mean_class_accuracy

    # class a: 2 of 3 right; class b: 0 of 1
    assert mean_class_accuracy(["a", "a", "b", "a"], ["a", "a", "a", "b"]) == pytest.approx(
        100 * (2 / 3 + 0) / 2)


def test_class_weights_balance_classes():
    from homesim.learn.video.framecnn import class_weights

    w = class_weights(np.array([0, 0, 0, 1, -100]), 3)
    assert w[0] * 3 == pytest.approx(w[1] * 1) and w[2] == 0


def test_the_clip_bootstrap_resamples_episodes():
    from homesim.learn.video.eval import clip_summary

    counts = np.array([[2.0, 0.0], [0.0, 1.0]])  # episode 0: 2 clips of class 0, ...
    hits = np.array([[1.0, 0.0], [0.0, 1.0]])
    s = clip_summary([(counts, hits), (counts, counts)])  # two seeds
    assert s["seeds"] == [pytest.approx(75.0), pytest.approx(100.0)]
    assert s["lo"] <= s["mean"] <= s["hi"] <= 100


def test_write_section_keeps_the_rest(tmp_path):
    from homesim.learn.video.report import END, START, write_section

    path = tmp_path / "results.md"
    path.write_text("# Table 3\n\nrows\n")
    write_section(path, f"{START}\nfirst\n{END}\n")
    write_section(path, f"{START}\nsecond\n{END}\n")
    text = path.read_text()
    assert text.startswith("# Table 3\n\nrows\n") and "second" in text and "first" not in text


def test_the_store_holds_frames_and_maps_of_every_part(tiny_plan, tmp_path):
    from homesim.learn.video.cache import VideoFormat
    from homesim.learn.video.data import read_store

    store, split = read_store(str(tiny_plan), VideoFormat(16, 12, 2), tmp_path)
    assert split.roles == {"train": "train", "val": "val", "test": "test"}
    assert [len(store.part(p)) for p in ("train", "val", "test")] == [2, 1, 1]
    assert store.frames.shape[1:] == (3, 12, 16) and store.maps.shape[1:] == (6, 8)
    assert store.classes[0] == "background" and store.maps.max() < len(store.classes)
    assert store.part("val")[0].key == "val/ep-000000" and store.part("val")[0].fps == 2
    again, _ = read_store(str(tiny_plan), VideoFormat(16, 12, 2), tmp_path)
    assert again.root == store.root  # built once, then read


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
            "TRN (predicted segmentation)", "TRN (ground-truth class maps: oracle)"} <= set(clips)
    assert all(0 <= row["step"]["lo"] <= row["step"]["hi"] <= 100 for row in clips.values())
    assert "all test" in result["segment"]["scores"]
    text = markdown.read_text()
    assert text.startswith("# Table 3\n") and "Table 2" in text and " ± " in text
    assert "*.528*" in text and "*24.6*" in text  # the paper's PG (LCS+Sim), seen homes
    assert "--plan tiny --n 4" in text and "--seeds 2 --frame-size 32x24" in text


def test_a_folder_that_is_not_a_data_set_is_refused(tmp_path):
    from homesim.errors import HomesimError
    from homesim.learn.video.cache import VideoFormat
    from homesim.learn.video.data import read_store

    with pytest.raises(HomesimError, match="not a data set folder"):
        read_store(str(tmp_path), VideoFormat(), tmp_path / "cache")
