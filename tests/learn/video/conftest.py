"""Four tiny generated episodes (seconds at 32x24, 2 frames/s) shared by the video tests."""

from __future__ import annotations

from pathlib import Path

import pytest

PROGRAMS = {"a_tv.txt": "Watch TV\nI turn on the TV.\n\n[Walk] <television> (1)\n"
                        "[SwitchOn] <television> (1)\n",
            "b_light.txt": "Lights on\nI turn on the light.\n\n[Walk] <light> (1)\n"
                           "[SwitchOn] <light> (1)\n"}
PARTS = {"ep-000000": "train", "ep-000001": "train", "ep-000002": "val",
         "ep-000003": "test-seen"}


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


@pytest.fixture()
def fixed_split(monkeypatch):
    from homesim.learn.video import splits as videosplits

    monkeypatch.setattr(videosplits, "part_of", lambda item: PARTS[item.key])
