import gzip
import importlib.util
import json
from pathlib import Path

import pytest

from homesim.errors import DataError
from homesim.knowledge import ObjectKB, Placement, load_kb
from homesim.world.homes import load_home

ROOT = Path(__file__).resolve().parents[2]


def _converter():
    spec = importlib.util.spec_from_file_location("convert_knowledge",
                                                  ROOT / "tools" / "convert_knowledge.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def kb() -> ObjectKB:
    return load_kb()


def test_load_is_cached(kb):
    assert load_kb() is kb
    assert len(kb) == len(kb.classes()) > 500


def test_properties(kb):
    assert kb.has_property("cup", "GRABBABLE")
    assert kb.has_property("cup", "grabbable")
    assert not kb.has_property("sofa", "GRABBABLE")
    assert kb.properties("fridge") >= {"CAN_OPEN", "CONTAINERS", "HAS_SWITCH"}
    assert kb.properties("no_such_thing") == frozenset()
    assert "no_such_thing" not in kb


def test_states_include_those_affordances_imply(kb):
    assert {"ON", "OFF", "PLUGGED_IN", "PLUGGED_OUT"} <= kb.states("tv")
    assert {"OPEN", "CLOSED", "CLEAN", "DIRTY"} <= kb.states("fridge")
    assert "GRABBED" not in kb.states("cup")  # holding is a relation, not a state
    assert all(s == s.strip().upper() for c in kb.classes() for s in kb.states(c))


def test_default_states(kb):
    assert kb.default_states("tv") == {"OFF", "PLUGGED_IN"}
    assert kb.default_states("fridge") == {"CLEAN", "CLOSED", "OFF", "PLUGGED_IN"}
    assert kb.default_states("cup") == {"CLEAN"}
    assert kb.default_states("no_such_thing") == frozenset()


def test_spelling_is_forgiven(kb):
    assert kb.resolve("Bathroom Cabinet") == "bathroom_cabinet"
    assert kb.resolve("cpuscreen") is None or kb.resolve("cpuscreen") in kb.classes()
    assert kb.resolve("CoffeeTable") == "coffeetable"
    assert kb.properties("Kitchen Counter") == kb.properties("kitchen_counter")


def test_equivalents_and_script_names(kb):
    assert kb.equivalents("fruit")[0] == "fruit"
    assert {"apple", "banana"} <= set(kb.equivalents("fruit"))
    assert kb.equivalents("couch") == ["couch", "sofa"]
    assert kb.equivalents("television") == ["television", "tv", "walltv"]
    assert "alarmclock" in kb.equivalents("alarm_clock")
    assert kb.script_names("sofa")[:2] == ["sofa", "couch"]
    assert "television" in kb.script_names("tv")
    # the two directions agree
    for script in ("couch", "television", "computer", "cup"):
        for cls in kb.equivalents(script)[1:]:
            assert script in kb.script_names(cls)


def test_placements(kb):
    places = kb.placements("cup")
    assert Placement("kitchen_counter", "ON", None) in places
    assert all(p.relation in ("ON", "INSIDE") for c in kb.classes() for p in kb.placements(c))
    assert any(p.relation == "INSIDE" for p in places)
    assert len(places) == len(set(places))
    assert kb.placements("no_such_thing") == []


def test_prefab_size(kb):
    x, y, z = kb.prefab_size("fridge")
    assert 1.5 < y < 2.5 and 0.4 < x < 1.2 and 0.4 < z < 1.2  # metres, y up
    assert kb.prefab_size("television") == kb.prefab_size("tv")
    assert kb.prefab_size("no_such_thing") is None


def test_kb_agrees_with_the_simulator_home(kb):
    home = load_home("scene1_trimmed")
    objects = [n for n in home if n.category != "Rooms" and n.class_name != "character"]
    same = sum(n.properties == kb.properties(n.class_name) for n in objects)
    states_ok = sum(n.states <= kb.states(n.class_name) for n in objects)
    assert same / len(objects) > 0.9
    assert states_ok / len(objects) > 0.95


@pytest.mark.dataset
def test_every_real_program_object_is_known(kb, real_data):
    from homesim.knowledge import real_programs

    names = {a.name for r in real_programs(real_data) for s in r.program.steps for a in s.args}
    rooms = {"bathroom", "bedroom", "dining_room", "home_office", "kitchen", "living_room"}
    assert sorted(n for n in names - rooms if n not in kb) == []


def test_shipped_file_matches_the_converter(shared_data):
    content, _ = _converter().convert(shared_data / "resources")
    shipped = json.loads(gzip.decompress(
        (ROOT / "src/homesim/knowledge/builtin/objects.json.gz").read_bytes()))
    assert shipped == json.loads(json.dumps(content))


def test_bad_files_name_the_file(tmp_path):
    path = tmp_path / "objects.json"
    path.write_text('{"format": "something-else"}')
    with pytest.raises(DataError, match=r"objects\.json: not a homesim object knowledge file"):
        ObjectKB.load(path)
    path.write_text('{"format": "homesim-objects/1", "classes": {"cup": {}}}')
    with pytest.raises(DataError, match=r"objects\.json: malformed object knowledge"):
        ObjectKB.load(path)
    path.write_bytes(b"\xff\xfe{")
    with pytest.raises(DataError, match=r"objects\.json: cannot read"):
        ObjectKB.load(path)
    with pytest.raises(DataError, match=r"missing\.json"):
        ObjectKB.load(tmp_path / "missing.json")


def test_spellings_share_facts(kb):
    # cutlery_fork has only a 3D model in the source, cutleryfork only properties
    assert kb.properties("cutlery_fork") == kb.properties("cutleryfork") >= {"GRABBABLE"}
    assert kb.prefab_size("cutleryfork") == kb.prefab_size("cutlery_fork") is not None
    assert kb.placements("wineglass") == kb.placements("wine_glass") != []
