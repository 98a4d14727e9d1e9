"""What a run leaves and what it waits for: a mistyped command leaves nothing (D13); a
run holds its folder; writers that outlived a killed run are waited for (the resume race);
a replay never removes or replaces the user's file (D1)."""

from __future__ import annotations

import threading
import time

import pytest

from homesim.cli.main import main
from homesim.dataset import generate_dataset
from homesim.dataset.layout import Layout
from homesim.errors import HomesimError
from tests.dataset.conftest import tiny_config, tree_hashes


@pytest.mark.parametrize(("args", "words"), [
    (["--homes", "nope"], "unknown home 'nope'"),
    (["--programs", "missing.txt"], "--programs missing.txt: no such file"),
    (["--workers", "-1"], "--workers must be 0 (no Ray) or more"),
    (["--programs", "/dev/zero"], "not a regular file"),
])
def test_a_mistyped_command_leaves_nothing_and_the_right_one_runs(
        gl, program_file, tmp_path, capsys, monkeypatch, args, words):
    """D13: the bad command left dataset.json, shards/ and staging/ (and printed an
    empty "episodes 0/1" bar), and the corrected command was then refused for its "other
    options"."""
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "D"
    base = ["dataset", "generate", "--out", str(out), "--programs", str(program_file),
            "--n", "1", "--width", "32", "--height", "24", "--fps", "2", "--homes",
            "scene1", "--workers", "0"]
    assert main(base + args) == 2
    refused = capsys.readouterr()
    assert words in refused.err
    assert "episodes" not in refused.out  # no empty progress bar before the error
    assert not out.exists()
    assert main(base) == 0


def test_a_folder_where_nothing_was_made_takes_new_options(gl, program_file, tmp_path):
    out = tmp_path / "D"
    layout = Layout(out)
    layout.open(tiny_config(program_file, n=7))  # then killed before any episode
    layout.close()
    summary = generate_dataset(tiny_config(program_file, n=1), out, workers=0)
    assert summary.ok == 1


def test_a_second_run_in_the_same_folder_is_refused(program_file, tmp_path):
    layout = Layout(tmp_path / "D")
    layout.open(tiny_config(program_file))
    try:
        with pytest.raises(HomesimError, match="another homesim run is making this data set"):
            Layout(tmp_path / "D").open(tiny_config(program_file))
    finally:
        layout.close()
    Layout(tmp_path / "D").open(tiny_config(program_file))  # free again


def test_a_run_waits_for_the_writers_of_a_killed_run(program_file, tmp_path):
    """The resume race: Ray workers of a SIGKILLed run write on for seconds; a run
    started at once removed their temporaries and they then failed, deleting the new
    run's episode (FileNotFoundError: staging/ep-000000.tar)."""
    out = tmp_path / "D"
    first = Layout(out)
    first.open(tiny_config(program_file))
    first.close()  # the driver is gone; a worker of it writes on
    temp = first.staging / ".homesim-ep-000000.tar.p1.abcdefgh.tmp"
    writing = threading.Event()

    def orphan():
        with first.writing():
            temp.write_bytes(b"half")
            writing.set()
            time.sleep(1.0)
            temp.rename(first.staging / "ep-000000.tar")  # its episode, complete

    thread = threading.Thread(target=orphan)
    thread.start()
    writing.wait(10)
    t0 = time.monotonic()
    second = Layout(out)
    second.open(tiny_config(program_file))
    waited = time.monotonic() - t0
    thread.join()
    second.close()
    assert waited > 0.5
    assert sorted(p.name for p in first.staging.iterdir()) == ["ep-000000.tar"]


def test_a_failed_episode_leaves_the_file_at_its_path(gl, program_file, tmp_path):
    """A worker whose episode failed removed the file at the episode's path: another
    run's complete episode (part of the resume race)."""
    from homesim.dataset.episode import write_episode_file
    from homesim.dataset.spec import plan_episodes

    config = tiny_config(program_file)
    spec = plan_episodes(config, [("bad", "Sit\nx\n\n[Sit] <television> (1)\n")])[0]
    path = tmp_path / "ep-000000.tar"
    path.write_bytes(b"made by another run")
    outcome = write_episode_file(spec, config, path)
    assert not outcome.ok and path.read_bytes() == b"made by another run"


# ------------------------------------------------------------------ replay --out
def test_replay_keeps_the_users_file(tiny_dataset, tmp_path, capsys):
    """D1: a replay of a damaged data set deleted --out; a replay onto an existing file
    replaced it without --force."""
    import shutil

    out = tmp_path / "x.tar"
    out.write_text("keep\n")
    broken = tmp_path / "broken"
    shutil.copytree(tiny_dataset, broken)
    (broken / "shards" / "shard-000000.tar").write_bytes(b"garbage" * 100)
    assert main(["dataset", "replay", str(broken), "0", "--out", str(out), "--force"]) == 2
    err = capsys.readouterr().err
    assert "shard-000000.tar" in err and "internal error" not in err
    assert out.read_text() == "keep\n"
    assert main(["dataset", "replay", str(tiny_dataset), "1", "--out", str(out)]) == 2
    assert "already exists; pass --force" in capsys.readouterr().err
    assert out.read_text() == "keep\n"
    before = tree_hashes(tiny_dataset)
    assert main(["dataset", "replay", str(tiny_dataset), "1", "--out", str(out),
                 "--force"]) == 0
    assert out.read_bytes()[:4] != b"keep" and tree_hashes(tiny_dataset) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["broken", "x.tar"]
