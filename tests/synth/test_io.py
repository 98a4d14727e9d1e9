import pytest

from homesim.errors import DataError, HomesimError
from homesim.knowledge.datasets import ActivityDataset
from homesim.learn.data import synthetic_examples
from homesim.synth import generate, read_jsonl, write_jsonl


def test_write_then_read(tmp_path):
    path = tmp_path / "s.jsonl"
    programs = list(generate(5, seed=1))
    assert write_jsonl(programs, path) == 5
    back = read_jsonl(path)
    assert [p.to_json() for p in back] == [p.to_json() for p in programs]


def test_bad_line_names_file_and_line(tmp_path):
    path = tmp_path / "s.jsonl"
    write_jsonl(generate(2, seed=1), path)
    path.write_text(path.read_text() + '{"id": "x"}\n')
    with pytest.raises(DataError, match=r"s.jsonl:3: missing title, description, program"):
        read_jsonl(path)


def test_synth_files_are_data_sets_every_loader_reads(tmp_path):
    path = tmp_path / "s.jsonl"
    programs = list(generate(4, seed=2))
    write_jsonl(programs, path)
    ds = ActivityDataset.load(path)
    assert [p.to_json() for p in ds] == [p.to_json() for p in programs]
    assert ds[0].home == programs[0].home and ds[0].bindings == programs[0].bindings
    assert ds[0].graph() is programs[0].graph()
    assert [e.text for e in synthetic_examples(path=path)] == [p.text for p in programs]


def test_write_refuses_to_replace_without_force_and_leaves_nothing(tmp_path):
    path = tmp_path / "s.jsonl"
    path.write_text("mine\n")
    with pytest.raises(HomesimError, match="already exists"):
        write_jsonl(generate(2, seed=1), path, force=False)
    assert path.read_text() == "mine\n"
    assert [p.name for p in tmp_path.iterdir()] == ["s.jsonl"]


def test_failure_while_generating_keeps_the_old_file(tmp_path):
    path = tmp_path / "s.jsonl"
    path.write_text("old\n")

    def broken():
        yield from generate(2, seed=1)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_jsonl(broken(), path)
    assert path.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["s.jsonl"]
