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
