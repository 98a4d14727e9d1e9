import copy

import pytest

from homesim.errors import GroundingError
from homesim.ground import ground, prepare
from homesim.ground.placement import overlaps_xz, overlaps_y
from homesim.knowledge import load_kb
from homesim.program import parse_program
from homesim.sim import execute
from homesim.world import load_home

WINE = "[Walk] <dining_room> (1)\n[Find] <wine_glass> (1)\n[Grab] <wine_glass> (1)"


def test_adds_missing_object_at_a_kb_destination_without_touching_the_input():
    home = load_home("scene1_trimmed")
    before = copy.deepcopy(home.to_dict())
    prep = prepare(parse_program(WINE), home, seed=0)
    assert home.to_dict() == before
    [a] = prep.added
    g = prep.graph
    assert a.class_name == "wine_glass" and g.node(a.node_id).class_name == "wine_glass"
    allowed = {(p.destination, p.relation) for p in load_kb().placements("wine_glass")}
    assert (g.node(a.destination_id).class_name, a.relation) in allowed
    assert g.has_edge(a.node_id, a.relation, a.destination_id)
    assert g.room_of(a.node_id) == a.room
    assert "GRABBABLE" in g.node(a.node_id).properties
    # the program says where it wants it: the dining room it walks into
    assert g.node(a.room).class_name == "dining_room"


def test_nothing_missing_returns_the_same_graph():
    home = load_home("scene1_trimmed")
    prep = prepare(parse_program("[Walk] <television> (1)"), home)
    assert prep.graph is home and prep.added == [] and prep.states == []


def test_counts_instances_per_program_object():
    home = load_home("scene1_trimmed")
    have = len(home.nodes_of_class("wine_glass"))
    text = "\n".join(f"[Find] <wine_glass> ({i})" for i in range(1, have + 3))
    prep = prepare(parse_program(text), home)
    assert len(prep.added) == 2
    assert len({a.node_id for a in prep.added}) == 2


def test_same_seed_same_result_and_seeds_vary_destinations():
    home = load_home("scene1_trimmed")
    p = parse_program("[Find] <wine_glass> (1)")
    a = prepare(p, home, seed=3)
    b = prepare(p, home, seed=3)
    assert a.added == b.added and a.graph == b.graph
    places = {prepare(p, home, seed=s).added[0].destination_id for s in range(12)}
    assert len(places) > 1


def test_object_goes_where_the_program_needs_it():
    # walk to the freezer, find food, open the freezer: the food must start near it
    p = parse_program("[Walk] <freezer> (1)\n[Find] <food_food> (1)\n[Grab] <food_food> (1)\n"
                      "[Open] <freezer> (1)\n[PutIn] <food_food> (1) <freezer> (1)")
    home = load_home("scene1_trimmed")
    prep = prepare(p, home, seed=0)
    [a] = prep.added
    freezers = {n.id for n in home.nodes_of_class("freezer")}
    g = prep.graph
    assert a.destination_id in freezers or freezers & g.targets(a.node_id, "CLOSE")
    # not hidden in the closed freezer the program only opens later
    assert not (a.relation == "INSIDE" and a.destination_id in freezers)


def test_sets_the_states_the_program_presupposes():
    home = load_home("scene1_trimmed")
    p = parse_program("[StandUp]\n[Walk] <television> (1)\n[SwitchOff] <television> (1)\n"
                      "[Walk] <freezer> (1)\n[Open] <freezer> (1)")
    prep = prepare(p, home)
    g = prep.graph
    for tv in g.nodes_of_class("television"):
        assert "ON" in tv.states and "OFF" not in tv.states
    for f in g.nodes_of_class("freezer"):
        assert "CLOSED" in f.states
    assert "SITTING" in g.node(g.character_id).states
    changed = {n for n, _, _ in prep.states}
    assert g.character_id in changed


def test_added_object_gets_a_box_on_its_destination_with_geometry():
    home = load_home("scene1")
    prep = prepare(parse_program("[Find] <wine_glass> (1)\n[Find] <wine_glass> (2)"), home)
    g = prep.graph
    for a in prep.added:
        box = g.node(a.node_id).bounding_box
        dest = g.node(a.destination_id).bounding_box
        assert box is not None and dest is not None
        assert box.size == pytest.approx(load_kb().prefab_size("wine_glass"))
        for axis in (0, 2):  # footprint inside the destination's
            assert abs(box.center[axis] - dest.center[axis]) <= (dest.size[axis]
                                                                 - box.size[axis]) / 2 + 1e-9
        if a.relation == "ON":
            assert box.center[1] - box.size[1] / 2 == pytest.approx(
                dest.center[1] + dest.size[1] / 2)
        neighbours = g.sources(a.destination_id, a.relation) - {a.node_id}
        for other in neighbours:
            ob = g.node(other).bounding_box
            assert ob is None or not (overlaps_xz(box, ob) and overlaps_y(box, ob))


def test_a_body_part_is_never_a_prop_on_a_counter():
    home = load_home("scene1")
    program = parse_program("[Walk] <bathroom> (1)\n[Wash] <teeth> (1)\n[Wash] <hair> (1)")
    prep = prepare(program, home, seed=0)
    g = prep.graph
    assert [g.node(a.node_id).class_name for a in prep.added] == ["teeth", "hair"]
    for a in prep.added:
        node = g.node(a.node_id)
        assert "BODY_PART" in node.properties and node.bounding_box is None
        assert a.destination_id == a.room and g.targets(a.node_id, "ON") == set()
    assert execute(program, g, bindings=ground(program, g).bindings).executable


def test_object_without_destination_stands_on_free_floor():
    home = load_home("scene1")  # it has no dishwasher, and no class lists a place for one
    prep = prepare(parse_program("[Walk] <kitchen> (1)\n[Find] <dishwasher> (1)"), home)
    [a] = prep.added
    box = prep.graph.node(a.node_id).bounding_box
    assert a.destination_id == a.room and box is not None
    assert box.center[1] == pytest.approx(box.size[1] / 2)
    assert home.node(a.room).class_name == "kitchen"


def test_a_missing_room_cannot_be_added():
    with pytest.raises(GroundingError, match=r"step 1 \[Walk\] <garage> \(1\):.*rooms and "
                                             "characters cannot be added") as e:
        prepare(parse_program("[Walk] <garage> (1)"), load_home("scene1_trimmed"))
    assert e.value.step == 1 and e.value.obj == "<garage> (1)"


def test_an_unknown_object_cannot_be_placed():
    with pytest.raises(GroundingError, match=r"step 2 \[Grab\] <flux_capacitor> \(1\): the "
                       "home has no flux_capacitor.*does not know 'flux_capacitor'"):
        prepare(parse_program("[Walk] <dining_room> (1)\n[Grab] <flux_capacitor> (1)"),
                load_home("scene1_trimmed"))


def test_clothes_taken_off_first_are_worn():
    p = parse_program("[Walk] <bedroom> (1)\n[Walk] <clothes_pants> (1)\n"
                      "[PutOff] <clothes_pants> (1)\n[Find] <clothes_shirt> (1)\n"
                      "[PutOff] <clothes_shirt> (1)")
    home = load_home("scene1_trimmed")
    prep = prepare(p, home)
    g = prep.graph
    worn = [a for a in prep.added if a.destination_id == g.character_id]
    assert {a.class_name for a in worn} == {"clothes_pants", "clothes_shirt"}
    assert all(a.relation == "ON" and g.node(a.room).class_name == "bedroom" for a in worn)
    assert execute(ground(p, g).program, g).executable


def test_a_second_character_outside_every_room_is_refused_at_load_not_a_key_error():
    from homesim.errors import GraphError
    from homesim.world.graph import EnvironmentGraph
    from tests.conftest import tiny_home_dict

    d = tiny_home_dict()
    d["nodes"].append({"id": 20, "class_name": "character", "category": "Characters"})
    # was KeyError: None in prepare (room_rank of no room); now the loader says why
    with pytest.raises(GraphError, match="character 20 is INSIDE no room"):
        EnvironmentGraph.from_dict(d)


def test_classes_the_knowledge_base_knows_without_properties_are_added():
    """Issue 41: `mirror` is in the knowledge base (states, no affordances); it was
    refused as unknown. A plural stands for its singular; an unknown name gets one line
    with the known names spelled like it."""
    from homesim.ground.pipeline import run_program

    run = run_program("[Walk] <mirror> (1)\n[LookAt] <mirror> (1)", "scene1")
    assert run.executable
    assert [a.class_name for a in run.prepared.added] == ["mirror"]
    assert run_program("[Walk] <cups> (1)\n[Grab] <cups> (1)", "scene1").executable
    run = run_program("[Walk] <televison> (1)", "scene1")
    assert not run.executable and run.kind.value == "missing"
    assert run.message.endswith("does not know 'televison', so none can be added (did you "
                                "mean television?)")
