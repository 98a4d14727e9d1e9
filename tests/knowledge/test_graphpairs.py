import copy
import json

import pytest

from homesim.errors import DataError, GraphError
from homesim.knowledge import graphpairs
from homesim.knowledge.graphpairs import GraphPairReader, changed_objects
from homesim.world.graph import EnvironmentGraph
from tests.conftest import tiny_home_dict


def _edge(a, r, b):
    return {"from_id": a, "relation_type": r, "to_id": b}


def _variants():
    """(init, final) pairs of one home with different changes, as the real data has."""
    base = tiny_home_dict()
    pairs = []
    final = copy.deepcopy(base)
    final["nodes"][6]["states"] = ["ON"]  # tv switched on
    final["edges"].append(_edge(10, "CLOSE", 14))
    pairs.append((base, final))
    init = copy.deepcopy(base)
    init["nodes"][3]["states"] = ["OPEN"]  # fridge open here; the cup taken out
    init["edges"] = [e for e in init["edges"] if e != _edge(12, "INSIDE", 11)]
    init["nodes"].append({"id": 17, "class_name": "book", "properties": ["GRABBABLE"]})
    init["edges"].append(_edge(17, "ON", 13))
    final = copy.deepcopy(init)
    final["nodes"][4]["properties"] = ["RECIPIENT", "GRABBABLE"]  # same set: no change
    final["edges"].remove(_edge(17, "ON", 13))
    final["edges"].append(_edge(10, "HOLDS_RH", 17))
    pairs.append((init, final))
    init = copy.deepcopy(base)
    init["nodes"] = [n for n in init["nodes"] if n["id"] != 16]  # no plate in this home
    init["edges"] = [e for e in init["edges"] if 16 not in (e["from_id"], e["to_id"])]
    final = copy.deepcopy(init)
    final["nodes"].append({"id": 18, "class_name": "apple"})
    pairs.append((init, final))
    return pairs


def _write(path, init, final, **kw):
    path.write_text(json.dumps({"init_graph": init, "final_graph": final}, **kw))
    return path


def test_fast_path_gives_what_the_slow_path_gives(tmp_path, monkeypatch):
    paths = [_write(tmp_path / f"f{k}.json", *pair) for k, pair in enumerate(_variants())]
    monkeypatch.setattr(graphpairs, "_slow", lambda raw, path: pytest.fail("slow path"))
    reader = GraphPairReader()
    got = [reader.read(p) for p in paths]
    for (graph, objects), (init, final) in zip(got, _variants(), strict=True):
        expected = EnvironmentGraph.from_dict(init)
        assert graph == expected
        assert graph.index.by_class == expected.index.by_class
        assert graph.index.close_symmetric == expected.index.close_symmetric
        assert objects == changed_objects(init, final)
    assert got[0][1] == {("tv", 14), ("character", 10)}
    assert got[1][1] == {("book", 17), ("character", 10), ("table", 13)}
    assert got[2][1] == {("apple", 18)}


def test_other_layouts_take_the_slow_path(tmp_path):
    reader = GraphPairReader()
    init, final = _variants()[1]
    graph, objects = reader.read(_write(tmp_path / "a.json", init, final, indent=1))
    assert graph == EnvironmentGraph.from_dict(init)
    assert objects == changed_objects(init, final)
    assert not reader._nodes  # nothing was parsed record by record


def test_a_dangling_edge_is_named_whichever_path(tmp_path):
    reader = GraphPairReader()
    reader.read(_write(tmp_path / "a.json", *_variants()[0]))
    init, final = _variants()[2]
    init["edges"].append(_edge(12, "ON", 16))  # the plate is not in this home
    with pytest.raises(GraphError, match=r"b\.json:init_graph.*to_id 16 is not a node"):
        reader.read(_write(tmp_path / "b.json", init, final))


def test_unreadable_files_are_data_errors(tmp_path):
    (tmp_path / "bad.json").write_text('{"init_graph": {"nodes": [')
    with pytest.raises(DataError, match=r"bad\.json: cannot read stored graphs"):
        GraphPairReader().read(tmp_path / "bad.json")
    with pytest.raises(DataError, match=r"missing\.json: cannot read"):
        GraphPairReader().read(tmp_path / "missing.json")


def test_real_stored_graphs_read_alike(real_data):
    from homesim.knowledge.datasets import real_programs

    items = real_programs()[::60]
    reader = GraphPairReader()
    for item in items:
        graph, objects = reader.read(item.graph_path)
        init, final = item.graph_dicts()
        assert graph == EnvironmentGraph.from_dict(init)
        assert objects == changed_objects(init, final)
    assert reader._nodes  # the fast path read them
