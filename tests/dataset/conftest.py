"""Dataset test builders: a tiny data set (two-step programs, 32x24, 2 frames/s, scene1)
made once per session, and a GL skip."""

from __future__ import annotations

from pathlib import Path

import pytest

try:  # homesim.render.gl picks MUJOCO_GL before mujoco is first imported
    import homesim.render.gl  # noqa: F401
except ImportError:
    pytest.skip("needs the render extra (mujoco)", allow_module_level=True)

from homesim.dataset import DatasetConfig

PROGRAMS = """\
Watch TV
I turn on the TV.

[Walk] <television> (1)
[SwitchOn] <television> (1)
"""
BAD_PROGRAM = """\
Sit on the TV
Impossible.

[Sit] <television> (1)
"""


def tiny_config(program_path: Path, n: int = 3, shard_size: int = 2) -> DatasetConfig:
    return DatasetConfig(programs=str(program_path), n=n, seed=0, width=32, height=24, fps=2,
                         homes=("scene1",), shard_size=shard_size)


@pytest.fixture(scope="session")
def gl():
    from homesim.render.gl import BACKEND, gl_available

    if not gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={BACKEND}")
    return BACKEND


@pytest.fixture(scope="session")
def program_file(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("programs") / "watch_tv.txt"
    path.write_text(PROGRAMS)
    return path


@pytest.fixture(scope="session")
def tiny_dataset(gl, program_file, tmp_path_factory) -> Path:
    """Three episodes in two shards, made in this process without Ray."""
    from homesim.dataset import generate_dataset

    out = tmp_path_factory.mktemp("data") / "tiny"
    generate_dataset(tiny_config(program_file), out, workers=0)
    return out


def tree_hashes(root: Path) -> dict[str, str]:
    """sha256 of every file under `root`, by relative path."""
    import hashlib

    return {p.relative_to(root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(root.rglob("*")) if p.is_file()}
