import pytest

from homesim.errors import DataError
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
    with pytest.raises(DataError, match=r"s.jsonl:3: not a synthetic program"):
        read_jsonl(path)
