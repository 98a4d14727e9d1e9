"""Column files: every built-in home's column file gives exactly the graph of its JSON."""

import gzip
from importlib import resources

import orjson
import pytest

from homesim.errors import GraphError
from homesim.world import homes
from homesim.world.columns import SUFFIX, from_columns, read_columns, to_columns, write_columns
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import home_names, load_builtin, load_home

BUILTIN = resources.files("homesim.world.builtin")


def assert_identical(a: EnvironmentGraph, b: EnvironmentGraph) -> None:
    """Equal in every field `==` skips too: node order, extra keys, meta, the index."""
    assert list(a.nodes) == list(b.nodes)
    assert a.to_dict() == b.to_dict()  # nodes with extra keys, edges, meta
    ia, ib = a.index, b.index
    assert ia.nodes == ib.nodes and ia.out == ib.out and ia.incoming == ib.incoming
    assert dict(ia.by_class) == dict(ib.by_class)
    assert (ia.rooms, ia.character, ia.body_parts, ia.close_symmetric) == (
        ib.rooms, ib.character, ib.body_parts, ib.close_symmetric)
    assert (ia.out["CLOSE"] is ia.incoming["CLOSE"]) == (ib.out["CLOSE"] is ib.incoming["CLOSE"])


@pytest.mark.parametrize("name", home_names())
def test_column_file_equals_the_json_home(name):
    """Regenerate with tools/pack_homes.py when this fails after a JSON home changed."""
    assert (BUILTIN / f"{name}{SUFFIX}").is_file(), f"{name}: no column file"
    with resources.as_file(BUILTIN / f"{name}.json.gz") as path:
        from_json = EnvironmentGraph.load(path)
    assert_identical(load_builtin(name), from_json)


def test_load_home_reads_the_column_file(monkeypatch):
    def no_json(*args, **kwargs):
        raise AssertionError("the JSON loader was used")

    monkeypatch.setattr(EnvironmentGraph, "load", no_json)
    load_home.cache_clear()
    try:
        assert len(load_home("scene1")) == 437
    finally:
        load_home.cache_clear()


def test_a_home_with_only_its_json_still_loads(tmp_path, monkeypatch, tiny_home):
    tiny_home.save(tmp_path / "tiny.json.gz")
    monkeypatch.setattr(homes.resources, "files", lambda package: tmp_path)
    assert home_names() == ["tiny"]
    assert load_builtin("tiny") == tiny_home
    write_columns(tiny_home, tmp_path / f"tiny{SUFFIX}")
    assert home_names() == ["tiny"]
    assert_identical(load_builtin("tiny"), tiny_home)


def test_round_trip_keeps_extra_keys_meta_and_missing_boxes(tmp_path):
    data = {"nodes": [{"id": 1, "class_name": "kitchen", "category": "Rooms",
                       "bounding_box": {"center": [1, 0, 2.5], "size": [4, 3, 4]}},
                      {"id": 7, "class_name": "character", "obj_transform": {"rot": [0, 1]}},
                      {"id": 3, "class_name": "cup", "properties": ["grabbable"],
                       "states": ["DIRTY"]}],
            "edges": [{"from_id": 7, "relation_type": "INSIDE", "to_id": 1},
                      {"from_id": 3, "relation_type": "CLOSE", "to_id": 7}],
            "trimmed_nodes": [5, 6]}
    graph = EnvironmentGraph.from_dict(data)
    write_columns(graph, tmp_path / "g.columns.json.gz")
    back = read_columns(tmp_path / "g.columns.json.gz")
    assert_identical(back, graph)
    assert back.node(7).extra == {"obj_transform": {"rot": [0, 1]}}
    assert back.meta == {"trimmed_nodes": [5, 6]} and not back.index.close_symmetric


def test_same_graph_same_bytes(tmp_path, tiny_home):
    write_columns(tiny_home, tmp_path / "a")
    write_columns(EnvironmentGraph.from_dict(tiny_home.to_dict()), tmp_path / "b")
    assert (tmp_path / "a").read_bytes() == (tmp_path / "b").read_bytes()


@pytest.mark.parametrize(("change", "why"), [
    (lambda d: d.update(version=99), "version 99"),
    (lambda d: d["nodes"]["class_name"].pop(), "different lengths"),
    (lambda d: d["out"].update(NEAR=[[1], [[2]]]), "bad relation 'NEAR'"),
    (lambda d: d.pop("meta"), "KeyError"),
    (lambda d: d["nodes"]["id"].__setitem__(1, d["nodes"]["id"][0]), "duplicate node ids"),
])
def test_a_malformed_column_file_is_one_line_naming_it(tiny_home, change, why):
    data = to_columns(tiny_home)
    change(data)
    with pytest.raises(GraphError, match=r"^home\.columns: not a valid home column file") as e:
        from_columns(data, "home.columns")
    assert why in str(e.value) and "\n" not in str(e.value)


def test_an_unreadable_column_file_names_it(tmp_path, tiny_home):
    bad = tmp_path / f"x{SUFFIX}"
    bad.write_bytes(gzip.compress(b"{nope"))
    with pytest.raises(GraphError, match=r"x\.columns\.json\.gz: cannot read home column"):
        read_columns(bad)
    no_char = to_columns(tiny_home)
    no_char["nodes"]["class_name"][2] = "robot"
    bad.write_bytes(gzip.compress(orjson.dumps(no_char)))
    with pytest.raises(GraphError, match="has no character node"):
        read_columns(bad)
