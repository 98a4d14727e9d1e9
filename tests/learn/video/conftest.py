"""Tiny generated data shared by the video tests (seconds at 32x24, 2 frames/s): four\nepisodes in one folder, and a plan of four episodes in train, val and test parts."""

from __future__ import annotations

from pathlib import Path

import pytest

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


@pytest.fixture(scope="session")
def tiny_video(tmp_path_factory) -> Path:
    """The data set folder (made once per session; needs the render extra and OpenGL)."""
    # homesim.render.gl picks MUJOCO_GL before mujoco is first imported
    pytest.importorskip("homesim.render.gl", reason="needs the render extra (mujoco)")
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


@pytest.fixture(scope="session")
def tiny_plan(tmp_path_factory) -> Path:
    """A plan folder: two training episodes, one validation, one test."""
    pytest.importorskip("homesim.render.gl", reason="needs the render extra (mujoco)")
    from homesim.dataset import DatasetConfig
    from homesim.dataset.generate import generate_plan
    from homesim.dataset.plan import Plan
    from homesim.render.gl import BACKEND, gl_available

    if not gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={BACKEND}")
    root = tmp_path_factory.mktemp("video-plan")
    programs = root / "programs"
    programs.mkdir()
    for name, text in PROGRAMS.items():
        (programs / name).write_text(text)
    config = DatasetConfig(programs=str(programs), width=32, height=24, fps=2,
                           modalities=("rgb", "class"), shard_size=4)
    generate_plan(Plan.from_dict(PLAN), 4, root / "plan", config, workers=0)
    return root / "plan"
