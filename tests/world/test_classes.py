from homesim.knowledge import load_kb
from homesim.world.classes import class_names_for, default_kb


def test_script_names_reach_scene_classes_and_back():
    kb = load_kb()
    assert class_names_for("television", kb)[0] == "television"
    assert "tv" in class_names_for("television", kb)
    assert "television" in class_names_for("tv", kb)
    assert "livingroom" in class_names_for("home_office", kb)
    assert "kitchen" in class_names_for("dining_room", kb)


def test_unknown_name_stands_for_itself():
    assert class_names_for("flux_capacitor", load_kb()) == ["flux_capacitor"]


def test_callers_that_pass_no_knowledge_base_get_the_package_one():
    # The facade (homesim/__init__.py) plugs load_kb in before any homesim module runs.
    assert default_kb() is load_kb()
