import json
from collections import Counter

import pytest

from homesim.errors import DataError, ProgramError
from homesim.knowledge.datasets import ActivityDataset, ActivityProgram, normalize_title

WATCH = "Watch TV\nI sit on the sofa and watch TV.\n\n[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n"
READ = "Read book\nTake a book\nand read it.\n\n[Walk] <book> (1)\n[Grab] <book> (1)\n[Read] <book> (1)\n"


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "a.txt").write_text(WATCH)
    (tmp_path / "sub" / "b.txt").write_text(READ)
    (tmp_path / "notes.md").write_text("ignored")
    return tmp_path


def test_normalize_title():
    assert normalize_title("  Watch  TV. ") == "watch tv"
    assert normalize_title("WATCH TV") == normalize_title("watch tv")


def test_from_folder_reads_every_txt_sorted(folder):
    ds = ActivityDataset.load(folder)
    assert [p.id for p in ds] == ["a", "sub/b"]
    assert ds[1].title == "Read book"
    assert ds[1].description == "Take a book and read it."  # wrapped lines joined
    assert len(ds[1].program) == 3
    assert ds[0].activity == "watch tv"
    assert ds.by_activity().keys() == {"watch tv", "read book"}


def test_from_file(folder):
    ds = ActivityDataset.load(folder / "a.txt")
    assert len(ds) == 1 and ds[0].id == "a" and str(ds[0].program.steps[1]) == "[SwitchOn] <tv> (1)"


def test_jsonl_round_trip(folder, tmp_path):
    ds = ActivityDataset.load(folder)
    out = ds.to_jsonl(tmp_path / "ds.jsonl")
    back = ActivityDataset.load(out)
    assert [(p.id, p.program) for p in back] == [(p.id, p.program) for p in ds]
    first = json.loads(out.read_text().splitlines()[0])
    assert first == {"id": "a", "title": "Watch TV", "description": "I sit on the sofa and watch TV.",
                     "program": ["[Walk] <tv> (1)", "[SwitchOn] <tv> (1)"], "graph": None,
                     "home": None}


def test_to_jsonl_never_overwrites_silently(folder, tmp_path):
    ds = ActivityDataset.load(folder)
    target = tmp_path / "keep.jsonl"
    target.write_text("precious\n")
    with pytest.raises(DataError, match="already exists"):
        ds.to_jsonl(target)
    assert target.read_text() == "precious\n"
    ds.to_jsonl(target, overwrite=True)
    assert len(ActivityDataset.load(target)) == 2


@pytest.mark.parametrize(("text", "message"), [
    ("Watch TV\n\n[Walk] <tv> (1)\n", "no description"),
    ("Watch TV\nI watch TV.\n\n", "empty program"),
    ("Watch TV\nI watch TV.\n", "empty program"),
    ("[Walk] <tv> (1)\n", "no title"),
])
def test_bad_files_name_the_file(tmp_path, text, message):
    path = tmp_path / "bad_one.txt"
    path.write_text(text)
    with pytest.raises(DataError, match=f"bad_one.txt: {message}"):
        ActivityDataset.load(path)


def test_bad_encoding_names_the_file(tmp_path):
    path = tmp_path / "latin1.txt"
    path.write_bytes("Café time\nI drink café.\n\n[Walk] <cup> (1)\n".encode("latin-1"))
    with pytest.raises(DataError, match=r"latin1\.txt: not UTF-8 text \(byte 3\)"):
        ActivityDataset.load(path)


def test_bad_step_names_file_and_line(tmp_path):
    path = tmp_path / "typo.txt"
    path.write_text("Watch TV\nI watch.\n\n[Walk] <tv> (1)\n[Wlak] <tv> (1)\n")
    with pytest.raises(ProgramError, match=r"typo\.txt:line 5"):
        ActivityDataset.load(path)


def test_folder_stops_at_a_bad_file_or_skips_it(folder):
    (folder / "c.txt").write_text("Watch TV\n\n[Walk] <tv> (1)\n")
    with pytest.raises(DataError, match=r"c\.txt: no description"):
        ActivityDataset.load(folder)
    ds = ActivityDataset.load(folder, skip_bad=True)
    assert [p.id for p in ds] == ["a", "sub/b"]
    assert len(ds.skipped) == 1 and "c.txt: no description" in ds.skipped[0]


def test_bad_jsonl_lines_name_file_and_line(tmp_path):
    path = tmp_path / "d.jsonl"
    good = json.dumps({"id": "x", "title": "T", "description": "D", "program": ["[Walk] <tv> (1)"]})
    cases = {
        "{not json": "not valid JSON",
        json.dumps({"title": "T", "program": []}): "missing description",
        json.dumps({"title": "T", "description": "D", "program": []}): "empty program",
        json.dumps({"title": "T", "description": "", "program": ["[Walk] <tv> (1)"]}): "no description",
        json.dumps([1, 2]): "expected a JSON object",
    }
    for line, message in cases.items():
        path.write_text(good + "\n\n" + line + "\n")
        with pytest.raises(DataError, match=rf"d\.jsonl:3: {message}"):
            ActivityDataset.load(path)


def test_missing_things(tmp_path):
    with pytest.raises(DataError, match="no such file or folder"):
        ActivityDataset.load(tmp_path / "nope")
    with pytest.raises(DataError, match="no program files"):
        ActivityDataset.load(tmp_path)


def test_duplicate_ids_are_refused():
    ds = ActivityDataset.from_texts({"a": WATCH})
    with pytest.raises(DataError, match="duplicate program id 'a'"):
        ActivityDataset([ds[0], ds[0]])


def _synthetic(sizes: dict[str, int]) -> ActivityDataset:
    texts = {f"{act}_{i}": f"{act}\nDo {act}.\n\n[Walk] <tv> ({i + 1})\n"
             for act, n in sizes.items() for i in range(n)}
    return ActivityDataset.from_texts(texts)


def test_split_is_deterministic_disjoint_and_stratified():
    sizes = {f"activity {k}": n for k, n in enumerate([40, 30, 20, 10, 5, 1, 1, 1, 1, 1])}
    ds = _synthetic(sizes)
    splits = ds.split(seed=7)
    assert list(splits) == ["train", "val", "test"]
    ids = [p.id for part in splits.values() for p in part]
    assert sorted(ids) == sorted(p.id for p in ds)  # a partition
    assert {k: len(v) for k, v in splits.items()} == {"train": 88, "val": 11, "test": 11}
    again = ds.split(seed=7)
    assert all([p.id for p in splits[k]] == [p.id for p in again[k]] for k in splits)
    other = ds.split(seed=8)
    assert [p.id for p in other["test"]] != [p.id for p in splits["test"]]
    for k, frac in (("train", 0.8), ("val", 0.1), ("test", 0.1)):
        counts = Counter(p.activity for p in splits[k])
        for act, n in sizes.items():
            if n >= 10:
                assert abs(counts[act] - frac * n) <= 1.5, (k, act, counts[act])
    # single-program activities do not all land in train
    singles = {f"activity {k}" for k in range(5, 10)}
    assert any(p.activity in singles for p in splits["val"]) or any(
        p.activity in singles for p in splits["test"])


def test_split_rejects_bad_fractions():
    with pytest.raises(ValueError, match="fractions"):
        _synthetic({"a": 3}).split(0, (0.5, -0.1, 0.6))


def test_activity_program_without_graphs():
    item = ActivityProgram("x", ActivityDataset.from_texts({"x": WATCH})[0].program)
    with pytest.raises(DataError, match="no stored graphs"):
        item.graphs()


@pytest.mark.dataset
def test_real_dataset(real_data):
    ds = ActivityDataset.load(real_data)
    assert len(ds) == 518
    assert len(ds.by_activity()) == 26
    assert all(p.graph_path.is_file() for p in ds)
    init, final = ds[0].graphs()
    assert init.character_id is not None and final.character_id == init.character_id
    splits = ds.split(seed=0)
    assert {k: len(v) for k, v in splits.items()} == {"train": 414, "val": 52, "test": 52}


@pytest.mark.dataset
def test_every_real_program_round_trips_through_jsonl(real_data, tmp_path):
    ds = ActivityDataset.load(real_data)
    back = ActivityDataset.load(ds.to_jsonl(tmp_path / "real.jsonl"))
    assert [(p.id, p.program, p.graph_path) for p in back] == [
        (p.id, p.program, p.graph_path) for p in ds]
