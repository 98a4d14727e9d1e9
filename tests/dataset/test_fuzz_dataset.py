"""Fuzz: damaged and hostile data sets (manifests, shards, the data set's json, members)
only ever give report lines or one `DataError` from `verify_dataset`, `find_spec` and the
CLI: no other exception, no hang, nothing read outside the data set, nothing changed.

Bounded and derandomized (every run tries the same cases); the damage is drawn from what
the 2026 audit found (D5): truncated, garbage, empty shards, a shard that is a folder, a
FIFO or a link, missing keys, JSON of the wrong shape or depth, ``gt_stride`` 0, null
manifest values, markup in a member name, shard names that are paths.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import tarfile
import time
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from homesim.cli.main import main
from homesim.dataset.replay import find_spec
from homesim.dataset.verify import verify_dataset
from homesim.errors import HomesimError
from tests.dataset.conftest import tree_hashes

pytest.importorskip("pyarrow")

CASES = settings(derandomize=True, max_examples=60, deadline=None, database=None,
                 suppress_health_check=list(HealthCheck))

HOSTILE = st.one_of(
    st.none(), st.booleans(), st.integers(-2**70, 2**70), st.sampled_from([0, -1, 2**31]),
    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=12),
    st.sampled_from(["../../dev/zero", "/dev/zero", "shard-000000.tar/../../x", "",
                     "[red]boom[/red]", "shard-000009.tar", "\x1b[31m", "ep-000000"]),
    st.lists(st.integers(), max_size=3), st.dictionaries(st.text(max_size=5),
                                                         st.integers(), max_size=3),
    st.integers(1, 3000).map(lambda n: json.loads("[" * n + "]" * n) if n < 500 else None))


def _regular(path: Path) -> Path:
    """`path` if an earlier damage left it a regular file (reading a FIFO would block)."""
    if path.is_symlink() or not path.is_file():
        raise ValueError(f"{path} is no longer a regular file")
    return path


def _paths(value: Any, prefix: tuple = ()) -> list[tuple]:
    """Every path into a JSON value (keys and indexes), the value's own first."""
    out = [prefix]
    if isinstance(value, dict):
        for k, v in value.items():
            out += _paths(v, (*prefix, k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            out += _paths(v, (*prefix, i))
    return out


def _set(value: Any, path: tuple, new: Any, delete: bool) -> Any:
    if not path:
        return new
    parent = value
    for step in path[:-1]:
        parent = parent[step]
    if delete and isinstance(parent, dict):
        del parent[path[-1]]
    else:
        parent[path[-1]] = new
    return value


@st.composite
def json_damage(draw: Any, name: str) -> Any:
    """Replace or delete one value somewhere in a json file of the data set."""
    path_index, new, delete = draw(st.integers(0, 10**6)), draw(HOSTILE), draw(st.booleans())

    def apply(root: Path) -> None:
        file = _regular(root / name)
        data = json.loads(file.read_text())
        paths = _paths(data)
        data = _set(data, paths[path_index % len(paths)], new, delete)
        file.write_text(json.dumps(data))
    return apply


@st.composite
def byte_damage(draw: Any, name: str) -> Any:
    """Truncate, flip bytes in, empty or replace a file."""
    how = draw(st.sampled_from(["truncate", "flip", "empty", "garbage"]))
    where, garbage = draw(st.floats(0, 1)), draw(st.binary(max_size=3000))

    def apply(root: Path) -> None:
        file = _regular(root / name)
        data = bytearray(file.read_bytes())
        at = int(where * max(len(data) - 1, 0))
        if how == "truncate":
            data = data[:at]
        elif how == "flip" and data:
            for i in range(at, min(at + 16, len(data))):
                data[i] ^= 0xA5
        elif how == "empty":
            data = bytearray()
        else:
            data = bytearray(garbage)
        file.write_bytes(bytes(data))
    return apply


@st.composite
def kind_damage(draw: Any, name: str) -> Any:
    """Make a file a folder, a FIFO or a link (to /dev/zero, or to a file outside)."""
    kind = draw(st.sampled_from(["folder", "fifo", "dev_link", "outside_link"]))

    def apply(root: Path) -> None:
        file = root / name
        file.unlink()
        if kind == "folder":
            file.mkdir()
        elif kind == "fifo":
            os.mkfifo(file)
        elif kind == "dev_link":
            file.symlink_to("/dev/zero")
        else:
            outside = root.parent / "outside.txt"
            outside.write_text("secret")
            file.symlink_to(outside)
    return apply


@st.composite
def member_damage(draw: Any) -> Any:
    """Rewrite shard 0 with a member renamed, dropped, or its episode json damaged."""
    how = draw(st.sampled_from(["rename", "drop", "meta", "meta_value", "dir_member"]))
    pick, new_name = draw(st.integers(0, 10**6)), draw(st.sampled_from(
        ["[red]x[/red].json", "ep-000000.[bold]", "../../etc/passwd", "ep-000000.json",
         "\x1b[2J", "ep-000001.mp4", "a" * 300]))
    meta_value, meta_key = draw(HOSTILE), draw(st.sampled_from(
        ["num_frames", "gt_stride", "modalities", "spec", "key"]))

    def apply(root: Path) -> None:
        shard = _regular(root / "shards" / "shard-000000.tar")
        with tarfile.open(shard) as tar:
            members = [(m, tar.extractfile(m).read()) for m in tar.getmembers()]
        i = pick % len(members)
        if how == "rename":
            members[i][0].name = new_name
        elif how == "drop":
            del members[i]
        elif how in ("meta", "meta_value"):
            j = next(k for k, (m, _) in enumerate(members) if m.name.endswith(".json"))
            meta = json.loads(members[j][1])
            if how == "meta":
                meta.pop(meta_key, None)
            else:
                meta[meta_key] = meta_value
            data = json.dumps(meta).encode()
            members[j][0].size = len(data)
            members[j] = (members[j][0], data)
        else:
            members[i][0].type = tarfile.DIRTYPE
        buf = io.BytesIO()
        with tarfile.open(fileobj=buf, mode="w", format=tarfile.GNU_FORMAT) as out:
            for info, data in members:
                out.addfile(info, io.BytesIO(data) if info.isfile() else None)
        shard.write_bytes(buf.getvalue())
    return apply


FILES = ["dataset.json", "episodes.parquet", "shards/shard-000000.tar",
         "shards/shard-000001.tar", "shards/shard-000000.json"]
damages = st.one_of(
    json_damage("dataset.json"), json_damage("shards/shard-000000.json"),
    st.sampled_from(FILES).flatmap(byte_damage),
    st.sampled_from(FILES).flatmap(kind_damage),
    member_damage())


def _check_one_line(problems: list[str]) -> None:
    assert all(p and "\n" not in p and len(p) < 700 for p in problems), problems


@pytest.fixture(scope="module")
def damaged_root(tiny_dataset, tmp_path_factory):
    """A fresh copy of the tiny data set per example (the outside file beside it)."""
    base = tmp_path_factory.mktemp("fuzz")

    def fresh() -> Path:
        for p in base.iterdir():
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            else:
                p.unlink()
        shutil.copytree(tiny_dataset, base / "D")
        return base / "D"
    return fresh


@CASES
@given(damage=st.lists(damages, min_size=1, max_size=3))
def test_verify_reports_damage_in_lines_and_changes_nothing(damaged_root, damage):
    root = damaged_root()
    for apply in damage:  # a damage that does not apply after an earlier one is skipped
        with contextlib.suppress(OSError, ValueError, KeyError, IndexError, StopIteration,
                                 TypeError, AttributeError, tarfile.TarError):
            apply(root)
    before = _hashes(root)
    t0 = time.monotonic()
    try:
        report = verify_dataset(root)
    except HomesimError as e:  # only "no dataset.json" is not a report line
        assert "not a homesim data set" in str(e)
    else:
        _check_one_line(report.problems)
    try:
        find_spec(root, "0")
        find_spec(root, "ep-000002")
    except HomesimError as e:
        assert "\n" not in str(e)
    assert time.monotonic() - t0 < 20
    assert _hashes(root) == before


def _hashes(root: Path) -> dict[str, str]:
    """tree_hashes, without following links or reading what is not a regular file."""
    kinds = {}
    for p in sorted(root.rglob("*")):
        rel = p.relative_to(root).as_posix()
        if p.is_symlink():
            kinds[rel] = "link:" + os.readlink(p)
        elif p.is_dir():
            kinds[rel] = "folder"
        elif not p.is_file():
            kinds[rel] = "special"
    files = {k: v for k, v in tree_hashes(root).items() if k not in kinds}
    return {**files, **kinds}


@pytest.mark.parametrize("damage", [
    "truncated", "garbage", "empty", "folder", "fifo", "dev_link", "gt_stride_0",
    "null_manifest", "markup_member", "path_name", "deep_json", "missing_keys"])
def test_each_audited_fault_is_one_line_naming_shard_and_member(
        damaged_root, capsys, monkeypatch, damage):
    """D5: each of these crashed verify or replay (exit 70), or hung."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from homesim.dataset import replay
    from homesim.dataset.episode import Outcome

    # Replay reads the data set as verify does; rendering the episode again adds nothing.
    monkeypatch.setattr(replay, "replay_episode", lambda spec, config, path: Outcome(
        spec.key, spec.index, False, "render", "not rendered in this test"))

    root = damaged_root()
    shard = root / "shards" / "shard-000000.tar"
    info = json.loads((root / "dataset.json").read_text())
    if damage == "truncated":
        shard.write_bytes(shard.read_bytes()[:3000])
    elif damage == "garbage":
        shard.write_bytes(b"\x07" * 5000)
    elif damage == "empty":
        shard.write_bytes(b"")
    elif damage in ("folder", "fifo", "dev_link"):
        shard.unlink()
        {"folder": shard.mkdir, "fifo": lambda: os.mkfifo(shard),
         "dev_link": lambda: shard.symlink_to("/dev/zero")}[damage]()
    elif damage in ("gt_stride_0", "markup_member"):
        member_rewrite(shard, damage)
    elif damage == "null_manifest":
        table = pq.read_table(root / "episodes.parquet")
        col = table.schema.get_field_index("num_frames")
        table = table.set_column(col, "num_frames", pa.array([None] * table.num_rows,
                                                             pa.int64()))
        pq.write_table(table, root / "episodes.parquet")
    elif damage == "path_name":
        info["shards"][0]["name"] = "../../../../../../dev/zero"
        (root / "dataset.json").write_text(json.dumps(info))
    elif damage == "deep_json":
        (root / "dataset.json").write_text("[" * 100_000 + "]" * 100_000)
    else:
        del info["shards"][0]["sha256"], info["config"]
        (root / "dataset.json").write_text(json.dumps(info))
    t0 = time.monotonic()
    code = main(["dataset", "verify", str(root)])
    out = capsys.readouterr()
    assert time.monotonic() - t0 < 20
    assert code == 2, out
    problems = [line for line in out.out.splitlines() if line.startswith("problem: ")]
    assert problems and "internal error" not in out.err
    where = {"null_manifest": "episodes.parquet", "path_name": "dataset.json",
             "deep_json": "dataset.json"}.get(damage, "shard-000000.tar")
    assert any(where in p for p in problems), problems
    if damage in ("gt_stride_0", "markup_member"):
        assert any("ep-000000.json" in p or "[red]" in p for p in problems), problems
    code = main(["dataset", "replay", str(root), "0", "--out", str(root.parent / "e.tar")])
    assert code in (0, 1, 2) and "internal error" not in capsys.readouterr().err


def member_rewrite(shard: Path, damage: str) -> None:
    with tarfile.open(shard) as tar:
        members = [(m, tar.extractfile(m).read()) for m in tar.getmembers()]
    out = io.BytesIO()
    with tarfile.open(fileobj=out, mode="w", format=tarfile.USTAR_FORMAT) as tar:
        for info, data in members:
            if damage == "gt_stride_0" and info.name == "ep-000000.json":
                meta = json.loads(data)
                meta["gt_stride"] = 0
                data = json.dumps(meta).encode()
                info.size = len(data)
            if damage == "markup_member" and info.name.endswith(".mp4"):
                info.name = "ep-000000.[red]mp4[/red]"
            tar.addfile(info, io.BytesIO(data))
    shard.write_bytes(out.getvalue())
