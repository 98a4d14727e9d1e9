import pytest

from homesim.errors import GraphError
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import home_names, load_home


def test_ten_built_in_homes():
    names = home_names()
    assert names == sorted([f"scene{i}" for i in range(1, 6)]
                           + [f"scene{i}_trimmed" for i in range(1, 6)])


def test_built_in_homes_equal_the_shared_scenes(shared_data):
    for name in home_names():
        assert load_home(name) == EnvironmentGraph.load(shared_data / "scenes" / f"{name}.json")


def test_full_homes_have_geometry_trimmed_do_not():
    assert all(n.bounding_box is not None for n in load_home("scene1"))
    assert all(n.bounding_box is None for n in load_home("scene1_trimmed"))


def test_unknown_home_suggests_a_name():
    with pytest.raises(GraphError, match=r"unknown home 'scene7' \(did you mean scene\d\?\)"):
        load_home("scene7")
