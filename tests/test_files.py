import os

import pytest

from homesim.errors import HomesimError
from homesim.files import atomic_write, check_target, temp_dir, write_bytes, write_text


def test_write_replaces_in_one_step_with_the_usual_mode(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("old")
    write_text(path, "new")
    assert path.read_text() == "new"
    assert os.stat(path).st_mode & 0o777 == 0o666 & ~_umask()
    write_bytes(path, b"\x00\x01")
    assert path.read_bytes() == b"\x00\x01"
    assert [p.name for p in tmp_path.iterdir()] == ["a.txt"]


def test_refuses_to_overwrite_without_force(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("mine")
    with pytest.raises(HomesimError, match=r"a\.txt: already exists; pass --force"):
        write_text(path, "new", force=False)
    assert path.read_text() == "mine"


def test_an_error_while_writing_leaves_the_old_file_and_no_temp_file(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("old")
    with pytest.raises(KeyboardInterrupt), atomic_write(path) as f:
        f.write("half")
        raise KeyboardInterrupt
    assert path.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["a.txt"]


@pytest.mark.parametrize(("make", "message"), [
    (lambda p: p.mkdir(), "is a folder; give a file name"),
    (lambda p: None, "no such folder"),
])
def test_check_target_names_the_problem(tmp_path, make, message):
    path = tmp_path / "x"
    make(path)
    target = path if message != "no such folder" else path / "y" / "z.txt"
    with pytest.raises(HomesimError, match=message):
        check_target(target, force=True)


def test_temp_dir_is_removed_on_error(tmp_path):
    with pytest.raises(RuntimeError), temp_dir(tmp_path, "fetch") as d:
        (d / "f").write_text("x")
        assert d.name.startswith(".homesim-fetch-")
        raise RuntimeError
    assert list(tmp_path.iterdir()) == []


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


# ------------------------------------------------------------------ bounded reading
def test_read_limited_refuses_devices_fifos_and_folders_at_once(tmp_path):
    import time

    from homesim.files import read_limited

    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)  # no writer: a plain open() would wait forever
    t0 = time.monotonic()
    for path, kind in [("/dev/zero", "a character device"), (fifo, "a FIFO"),
                       (tmp_path, "a folder")]:
        with pytest.raises(HomesimError, match=f"not a regular file \\({kind}\\)"):
            read_limited(path, 10, "MAX_X")
    assert time.monotonic() - t0 < 1


def test_read_limited_counts_while_reading(tmp_path):
    from homesim.errors import LimitError
    from homesim.files import read_limited, read_text_limited

    path = tmp_path / "f"
    path.write_bytes(b"x" * 11)
    assert read_limited(path, 11, "MAX_X") == b"x" * 11
    with pytest.raises(LimitError, match=r"over the limit of 10 bytes for a file \(MAX_X\)"):
        read_limited(path, 10, "MAX_X")
    path.write_bytes(b"\xef\xbb\xbfok")
    assert read_text_limited(path, 10, "MAX_X") == "ok"
    path.write_bytes(b"\xff ok")
    with pytest.raises(HomesimError, match="not UTF-8 text"):
        read_text_limited(path, 10, "MAX_X")
    with pytest.raises(HomesimError, match="cannot read file"):
        read_limited(tmp_path / "missing", 10, "MAX_X")


# ------------------------------------------------------------------ killed writers
def test_a_killed_writers_temporary_is_removed_by_the_next_write(tmp_path):
    import subprocess
    import sys

    code = ("import sys, os, signal; from homesim.files import atomic_write\n"
            "with atomic_write(sys.argv[1]) as f:\n"
            "    f.write('half'); f.flush(); os.kill(os.getpid(), signal.SIGKILL)\n")
    target = tmp_path / "out.jsonl"
    proc = subprocess.run([sys.executable, "-c", code, str(target)], env={
        **os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
    assert proc.returncode == -9
    left = [p.name for p in tmp_path.iterdir()]
    assert len(left) == 1 and left[0].startswith(".homesim-out.jsonl.p")
    other = tmp_path / "other.txt"  # a write of another target leaves it alone
    write_text(other, "x")
    assert len(list(tmp_path.iterdir())) == 2
    write_text(target, "whole")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other.txt", "out.jsonl"]


def test_a_live_writers_temporary_is_kept(tmp_path):
    from homesim.files import remove_stale

    mine = tmp_path / f".homesim-a.txt.p{os.getpid()}.abcd1234.tmp"
    mine.write_text("in progress")
    dead = tmp_path / ".homesim-a.txt.p999999999.abcd1234.tmp"
    dead.write_text("left")
    users = tmp_path / ".homesim-a.txt.p1.notours"  # not our pattern
    users.write_text("keep")
    assert remove_stale(tmp_path, "a.txt") == [dead]
    assert mine.exists() and users.exists()
