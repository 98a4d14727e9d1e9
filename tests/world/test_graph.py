import gzip
import json
import re

import pytest

from homesim.errors import GraphError
from homesim.world.graph import EnvironmentGraph
from tests.conftest import tiny_home_dict


def test_indexes_by_id_class_and_relation(tiny_home):
    assert tiny_home.node(12).class_name == "cup"
    assert [n.id for n in tiny_home.nodes_of_class("tv")] == [14]
    assert tiny_home.targets(12, "INSIDE") == {11, 1}
    assert tiny_home.sources(13, "ON") == {16}
    assert tiny_home.character_id == 10
    assert tiny_home.room_ids == {1, 2}
    assert tiny_home.room_of(12) == 1
    assert tiny_home.room_of(1) == 1


def test_round_trip_dict_and_files(tiny_home, tmp_path):
    again = EnvironmentGraph.from_dict(tiny_home.to_dict())
    assert again == tiny_home
    for name in ("g.json", "g.json.gz"):
        tiny_home.save(tmp_path / name)
        assert EnvironmentGraph.load(tmp_path / name) == tiny_home
    assert gzip.decompress((tmp_path / "g.json.gz").read_bytes()).startswith(b"{")


def test_unknown_node_keys_are_kept():
    d = tiny_home_dict()
    d["nodes"][0]["obj_transform"] = {"position": [1, 2, 3]}
    d["extra_top"] = 7
    out = EnvironmentGraph.from_dict(d).to_dict()
    assert out["nodes"][0]["obj_transform"] == {"position": [1, 2, 3]}
    assert out["extra_top"] == 7


def broken(mutate):
    d = tiny_home_dict()
    mutate(d)
    return d


@pytest.mark.parametrize(
    ("data", "pattern"),
    [
        ([], r"must be a JSON object"),
        ({"nodes": []}, r"'edges' must be a list"),
        (broken(lambda d: d["nodes"].append({"id": 12, "class_name": "x"})),
         r"nodes\[9\]: duplicate node id 12"),
        (broken(lambda d: d["edges"].append({"from_id": 12, "relation_type": "ON",
                                             "to_id": 99})),
         r"edges\[14\] \(12 ON 99\): to_id 99 is not a node"),
        (broken(lambda d: d["edges"].append({"from_id": 12, "relation_type": "NEAR",
                                             "to_id": 13})),
         r"edges\[14\]: unknown relation 'NEAR'"),
        (broken(lambda d: d["nodes"][3].update(id="11")), r"nodes\[3\]: 'id' must be an integer"),
        (broken(lambda d: d["nodes"][3].update(id=True)), r"'id' must be an integer"),
        (broken(lambda d: d["nodes"][3].update(id=2**31)),  # D10: OverflowError in render
         r"nodes\[3\]: 'id' 2147483648 is outside 0..2147483647 \(MAX_NODE_ID"),
        (broken(lambda d: d["nodes"][3].update(id=-1)), r"'id' -1 is outside 0.."),
        (broken(lambda d: d["nodes"][3].update(states="OPEN")),
         r"nodes\[3\] \(id 11\): 'states' must be a list of strings"),
        (broken(lambda d: d["nodes"][3].update(class_name="")), r"'class_name' must be a non-empty"),
        (broken(lambda d: d["nodes"][3].update(bounding_box={"center": [0, 0], "size": [1, 1, 1]})),
         r"bounding_box 'center' must be 3 finite numbers"),
        (broken(lambda d: d["edges"].append("12 ON 13")), r"an edge must be a JSON object"),
        (broken(lambda d: d["edges"].append({"from_id": 12, "relation_type": ["ON"],
                                             "to_id": 13})), r"edges\[14\]: unknown relation"),
        (broken(lambda d: d["edges"].append({"from_id": True, "relation_type": "ON",
                                             "to_id": 13})), r"edges\[14\]: 'from_id' and"),
        (broken(lambda d: d["edges"].append({"from_id": 12, "to_id": 13})),
         r"edges\[14\]: unknown relation None"),
        (broken(lambda d: d["nodes"][3].update(
            bounding_box={"center": [1e308, 0, 0], "size": [1, 1, 1]})),
         r"^g.json: nodes\[3\] \(id 11\): bounding_box 'center' must be within ±10000 m"),
        (broken(lambda d: d["nodes"][3].update(
            bounding_box={"center": [0, 0, 0], "size": [1, -1, 1]})),
         r"nodes\[3\] \(id 11\): bounding_box 'size' must be between 0 and 1000 m"),
        (broken(lambda d: d["nodes"][3].update(
            bounding_box={"center": [0, 0, 0], "size": [1, float("nan"), 1]})),
         r"nodes\[3\] \(id 11\): bounding_box 'size' must be 3 finite numbers"),
        (broken(lambda d: d["nodes"].append({"id": 99, "class_name": "character"})),
         r"^g.json: character 99 is INSIDE no room"),
    ],
)
def test_broken_graphs_name_the_fault(data, pattern):
    with pytest.raises(GraphError, match=pattern):
        EnvironmentGraph.from_dict(data, source="g.json")


def test_broken_files(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"nodes": [}')
    with pytest.raises(GraphError, match=r"bad.json: invalid JSON at line 1 column 12"):
        EnvironmentGraph.load(bad)
    with pytest.raises(GraphError, match=r"cannot read graph file"):
        EnvironmentGraph.load(tmp_path / "missing.json")
    big = tmp_path / "big.json"
    big.write_text(json.dumps(tiny_home_dict()))
    with pytest.raises(GraphError, match=r"over the limit of 10 bytes for a graph \(MAX_GRAPH_BYTES\)"):
        EnvironmentGraph.load(big, max_bytes=10)
    binary = tmp_path / "bin.json"
    binary.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(GraphError, match=r"bin.json: "):
        EnvironmentGraph.load(binary)


def test_missing_node_lookup_is_a_graph_error(tiny_home):
    with pytest.raises(GraphError, match="no node 999"):
        tiny_home.node(999)


def test_loads_the_ten_shared_scenes(shared_data):
    paths = sorted((shared_data / "scenes").glob("scene*.json"))
    assert len(paths) == 10
    for path in paths:
        g = EnvironmentGraph.load(path)
        raw = json.loads(path.read_text())
        assert len(g) == len(raw["nodes"])
        assert g.num_edges() == len({(e["from_id"], e["relation_type"], e["to_id"])
                                     for e in raw["edges"]})
        assert g.character_id is not None and g.room_of(g.character_id) in g.room_ids
        assert EnvironmentGraph.from_dict(g.to_dict()) == g


def test_huge_coordinates_are_refused_at_load_not_in_grounding():
    d = tiny_home_dict()
    for n in d["nodes"]:
        n["bounding_box"] = {"center": [0, 1, 0], "size": [1, 1, 1]}
    d["nodes"][3]["bounding_box"] = {"center": [1e308, 1, 1e308], "size": [1e308, 1, 1]}
    with pytest.raises(GraphError, match=r"nodes\[3\] \(id 11\): bounding_box 'center'"):
        EnvironmentGraph.from_dict(d)
    d["nodes"][3]["bounding_box"] = {"center": [1e4, 1, -1e4], "size": [1e3, 0, 1]}
    assert EnvironmentGraph.from_dict(d).node(11).bounding_box.size == (1e3, 0.0, 1.0)


@pytest.mark.parametrize(("text", "pattern"), [
    ('{"nodes": [{"id": 1, "class_name": "kitch', r"invalid JSON at line 1 column 36: a string "
     r"starting there never ends; the text ends early \(is the file truncated\?\)"),
    ('{"nodes": [{"id": 1,', r"invalid JSON at line 1 column 21: expecting property name "
     r"enclosed in double quotes; the text ends early \(is the file truncated\?\)"),
    ("", r"the file is empty, not a JSON graph"),
    ('{"nodes": [] "edges": []}', r"invalid JSON at line 1 column 14: expecting ',' delimiter"),
])
def test_json_errors_are_full_lines_naming_the_file(tmp_path, text, pattern):
    bad = tmp_path / "bad.json"
    bad.write_text(text)
    with pytest.raises(GraphError, match=f"^{re.escape(str(bad))}: {pattern}$"):
        EnvironmentGraph.load(bad)


def test_truncated_gzip_and_a_home_without_character_name_the_file(tmp_path):
    gz = tmp_path / "g.json.gz"
    gz.write_bytes(gzip.compress(json.dumps(tiny_home_dict()).encode())[:-12])
    with pytest.raises(GraphError, match=r"g.json.gz: the gzip data ends early"):
        EnvironmentGraph.load(gz)
    d = tiny_home_dict()
    d["nodes"] = [n for n in d["nodes"] if n["class_name"] != "character"]
    d["edges"] = [e for e in d["edges"] if 10 not in (e["from_id"], e["to_id"])]
    path = tmp_path / "nochar.json"
    path.write_text(json.dumps(d))
    with pytest.raises(GraphError, match=r"nochar.json: the graph has no character node"):
        EnvironmentGraph.load(path)
    assert EnvironmentGraph.from_dict(d).character_id is None  # dicts may lack one


def test_deeply_nested_json_is_a_graph_error(tmp_path):
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000 + "]" * 100_000)  # was a RecursionError
    with pytest.raises(GraphError, match=r"deep.json: JSON nested deeper .*MAX_JSON_DEPTH"):
        EnvironmentGraph.load(path)
    d = tiny_home_dict()
    d["nodes"][0]["note"] = [[[1]]]
    assert EnvironmentGraph.from_dict(d).nodes[1].extra == {"note": [[[1]]]}
    d["nodes"][0]["note"] = json.loads("[" * 40 + "]" * 40)
    with pytest.raises(GraphError, match=r"nodes\[0\] \(id 1\): JSON nested deeper"):
        EnvironmentGraph.from_dict(d)


def test_a_gzip_bomb_or_a_huge_number_is_a_graph_error(tmp_path):
    bomb = tmp_path / "bomb.json.gz"
    bomb.write_bytes(gzip.compress(b" " * 5_000_000))  # 5 KB that unpack to 5 MB
    with pytest.raises(GraphError, match=r"unpacks to over the 1 MiB limit .*MAX_GRAPH_BYTES"):
        EnvironmentGraph.load(bomb, max_bytes=2**20)
    huge = tmp_path / "huge.json"
    huge.write_text('{"nodes": [{"id": ' + "9" * 5000 + "}]}")  # was a ValueError
    with pytest.raises(GraphError, match=r"huge.json: invalid JSON \(Exceeds the limit"):
        EnvironmentGraph.load(huge)
