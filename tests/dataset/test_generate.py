import shutil
import signal

import pytest

from homesim.dataset import generate_dataset
from homesim.dataset.layout import Layout
from homesim.dataset.manifest import read_manifest
from homesim.dataset.replay import replay_from_dataset
from homesim.dataset.spec import FORMAT
from homesim.dataset.verify import verify_dataset
from homesim.errors import HomesimError
from tests.cli.subprocess_cli import start_cli, wait_for
from tests.dataset.conftest import BAD_PROGRAM, PROGRAMS, tiny_config, tree_hashes


def test_a_dataset_is_complete_and_verifies(tiny_dataset):
    report = verify_dataset(tiny_dataset)
    assert report.problems == []
    assert (report.shards, report.episodes, report.ok) == (2, 3, 3)
    rows = read_manifest(tiny_dataset / "episodes.parquet")
    assert [r["key"] for r in rows] == ["ep-000000", "ep-000001", "ep-000002"]
    assert all(r["status"] == "ok" and r["num_frames"] > 5 for r in rows)
    assert not (tiny_dataset / "staging").exists()  # removed once empty
    assert sorted(p.name for p in (tiny_dataset / "shards").iterdir()) == [
        "shard-000000.json", "shard-000000.tar", "shard-000001.json", "shard-000001.tar"]


def test_replay_gives_the_same_bytes(tiny_dataset, tmp_path):
    outcome, recorded = replay_from_dataset(tiny_dataset, "ep-000001", tmp_path / "ep.tar")
    assert outcome.ok and outcome.sha256 == recorded.sha256
    assert recorded.format == FORMAT and recorded.spec.index == 1


def test_running_again_changes_nothing(tiny_dataset, program_file):
    before = tree_hashes(tiny_dataset)
    summary = generate_dataset(tiny_config(program_file), tiny_dataset, workers=0)
    assert summary.ok == 3 and tree_hashes(tiny_dataset) == before


def test_other_options_in_the_same_folder_are_refused(tiny_dataset, program_file):
    with pytest.raises(HomesimError, match=r"other options \(n\)"):
        generate_dataset(tiny_config(program_file, n=4), tiny_dataset, workers=0)


def _with_format(tiny_dataset, tmp_path, made_in: str):
    import json

    copy = tmp_path / "copy"
    shutil.copytree(tiny_dataset, copy)
    info = json.loads((copy / "dataset.json").read_text())
    (copy / "dataset.json").write_text(json.dumps({**info, "format": made_in}))
    return copy


def test_a_data_set_of_another_format_is_not_resumed(tiny_dataset, program_file, tmp_path):
    copy = _with_format(tiny_dataset, tmp_path, "homesim-activity/1")
    with pytest.raises(HomesimError, match=r"in format homesim-activity/1, not "):
        generate_dataset(tiny_config(program_file), copy, workers=0)


def test_a_replay_that_differs_names_the_data_sets_older_format(tiny_dataset, tmp_path,
                                                                capsys):
    import pyarrow as pa
    import pyarrow.parquet as pq

    from homesim.cli.main import main

    copy = _with_format(tiny_dataset, tmp_path, "homesim-activity/1")
    table = pq.read_table(copy / "episodes.parquet")
    checksums = ["0" * 64] * table.num_rows  # as if encoded differently
    table = table.set_column(table.schema.get_field_index("sha256"), "sha256",
                             pa.array(checksums, table.schema.field("sha256").type))
    pq.write_table(table, copy / "episodes.parquet")
    assert main(["dataset", "replay", str(copy), "1", "--out", str(tmp_path / "e.tar")]) == 1
    out = capsys.readouterr().out
    assert "DIFFERENT" in out and "format homesim-activity/1; this homesim writes" in out


def test_verify_finds_a_changed_shard(tiny_dataset, tmp_path):
    copy = tmp_path / "copy"
    shutil.copytree(tiny_dataset, copy)
    shard = copy / "shards" / "shard-000001.tar"
    data = bytearray(shard.read_bytes())
    data[2000] ^= 0xFF
    shard.write_bytes(bytes(data))
    problems = verify_dataset(copy).problems
    assert any("shard-000001.tar: checksum differs" in p for p in problems)
    # A damaged shard is made again on the next run.
    assert Layout(copy).shard_info(1) is None


def test_a_failing_episode_is_recorded_and_the_run_goes_on(gl, tmp_path):
    programs = tmp_path / "programs.jsonl"
    from homesim.knowledge.datasets import ActivityProgram, write_jsonl
    from homesim.program.parse import parse_program

    write_jsonl([ActivityProgram("bad", parse_program(BAD_PROGRAM)),
                 ActivityProgram("good", parse_program(PROGRAMS))], programs)
    out = tmp_path / "data"
    summary = generate_dataset(tiny_config(programs, n=2), out, workers=0)
    assert (summary.ok, summary.failed) == (1, 1)
    bad = read_manifest(out / "episodes.parquet")[0]
    assert bad["status"] == "failed" and bad["stage"] == "grounding"
    assert "[Sit] <television> (1)" in bad["reason"]
    assert verify_dataset(out).problems == []


def test_killed_and_restarted_gives_the_same_bytes(tiny_dataset, program_file, tmp_path):
    out = tmp_path / "killed"
    config = tiny_config(program_file)
    args = ["dataset", "generate", "--out", str(out), "--programs", str(program_file),
            "--n", "3", "--width", "32", "--height", "24", "--fps", "2", "--homes", "scene1",
            "--shard-size", "2", "--workers", "0"]
    proc = start_cli(args)
    # Kill it once the first episode is staged (the second is being rendered).
    wait_for(lambda: (out / "staging" / "ep-000000.json").exists(), proc, timeout=180.0)
    proc.send_signal(signal.SIGKILL)
    _, err = proc.communicate()
    assert not (out / "episodes.parquet").exists()
    generate_dataset(config, out, workers=0)
    # Rows first: a failure's stage and reason, or which episode's bytes differ, show here.
    assert _rows(out) == _rows(tiny_dataset), f"the killed run's stderr ended: {err[-2000:]}"
    assert tree_hashes(out) == tree_hashes(tiny_dataset)


def _rows(root):
    return [{k: r[k] for k in ("key", "status", "stage", "reason", "sha256")}
            for r in read_manifest(root / "episodes.parquet")]
