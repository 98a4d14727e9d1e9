import random

from homesim.dataset.randomize import movable_objects, move_character, move_objects
from homesim.knowledge.kbtypes import default_kb
from homesim.world.floor import FloorModel
from homesim.world.homes import load_home
from homesim.world.vocab import CLOSE, INSIDE


def test_objects_move_only_where_the_placement_kb_allows():
    home = load_home("scene1")
    kb = default_kb()
    moved, moves = move_objects(home, 5, random.Random(1), kb)
    assert 1 <= len(moves) <= 5
    for m in moves:
        node = moved.node(m.node_id)
        assert node.bounding_box != home.node(m.node_id).bounding_box
        assert moved.has_edge(m.node_id, m.relation, m.destination)
        assert moved.has_edge(m.node_id, INSIDE, m.room)
        assert moved.has_edge(m.destination, CLOSE, m.node_id)
        allowed = {(p.destination, p.relation) for p in kb.placements(node.class_name)}
        dest = moved.node(m.destination).class_name
        assert any(rel == m.relation and dest in (d, *kb.equivalents(d)) for d, rel in allowed)
    # Same stream, same moves; the home itself is left as it was.
    again, moves2 = move_objects(home, 5, random.Random(1), kb)
    assert moves2 == moves and again == moved
    assert home == load_home("scene1")


def test_zero_moves_keep_the_home():
    home = load_home("scene1")
    assert move_objects(home, 0, random.Random(0), default_kb()) == (home, [])
    assert movable_objects(home)


def test_the_agent_starts_on_free_floor_of_a_random_room():
    home = load_home("scene2")
    starts = set()
    for seed in range(4):
        moved, start = move_character(home, random.Random(seed))
        assert start is not None
        char = moved.character_id
        assert moved.targets(char, INSIDE) == {start.room}
        assert not moved.targets(char, CLOSE)
        box = moved.node(char).bounding_box
        assert (box.center[0], box.center[2]) == (start.x, start.z)
        model = FloorModel(home)
        assert model.walkable(*model.index(start.x, start.z))
        starts.add(start.room)
    assert len(starts) > 1
