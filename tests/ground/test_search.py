import copy
import math

import pytest

from homesim.errors import GroundingError
from homesim.ground import ground, prepare, prepare_and_ground, unground
from homesim.program import parse_program
from homesim.sim import execute
from homesim.world import load_home
from homesim.world.graph import EnvironmentGraph
from homesim.world.standing import FloorPlan
from tests.conftest import tiny_home_dict

WATCH = ("[Walk] <television> (1)\n[SwitchOn] <television> (1)\n[Walk] <couch> (1)\n"
         "[Sit] <couch> (1)\n[Watch] <television> (1)")


def two_tv_home(second_tv_states: list[str]) -> EnvironmentGraph:
    d = tiny_home_dict()
    d["nodes"].append({"id": 17, "class_name": "tv", "properties": ["HAS_SWITCH", "LOOKABLE"],
                       "states": second_tv_states})
    d["edges"].append({"from_id": 17, "relation_type": "INSIDE", "to_id": 2})
    return EnvironmentGraph.from_dict(d)


def test_grounded_program_executes_and_keeps_instances():
    home = load_home("scene1_trimmed")
    p = parse_program(WATCH)
    g = ground(p, home)
    assert g.program.is_grounded
    assert [ref.instance for s in g.program for ref in s.args] == [1] * 5
    assert execute(g.program, home).executable
    assert execute(p, home, bindings=g.bindings).executable
    assert g.standing is None


def test_same_object_same_node_different_objects_different_nodes():
    home = load_home("scene1_trimmed")
    p = parse_program("[Walk] <chair> (1)\n[Walk] <chair> (2)\n[Walk] <chair> (1)\n"
                      "[Walk] <chair> (3)")
    g = ground(p, home)
    nodes = [s.args[0].node_id for s in g.program]
    assert nodes[0] == nodes[2]
    assert len({nodes[0], nodes[1], nodes[3]}) == 3


def test_name_equivalences_bind_script_names_to_scene_classes():
    home = load_home("scene1")  # Unity class names: tv, sofa
    g = ground(parse_program(WATCH), home)
    assert home.node(g.bindings[("television", 1)]).class_name == "tv"
    assert home.node(g.bindings[("couch", 1)]).class_name == "sofa"


def test_preconditions_prune_candidates():
    # Whichever tie-break the seed gives, only the tv that is off can be switched on.
    for states in (["ON"], ["OFF"]):
        home = two_tv_home(states)
        off = {n.id for n in home.nodes_of_class("tv") if "OFF" in n.states}
        for seed in range(6):
            g = ground(parse_program("[Walk] <tv> (1)\n[SwitchOn] <tv> (1)"), home, seed=seed)
            assert g.bindings[("tv", 1)] in off


def test_backtracks_over_earlier_choices_without_touching_the_graph():
    home = two_tv_home(["ON"])
    before = copy.deepcopy(home.to_dict())
    # The first tv chosen is decided at step 1; only step 3 can rule out the one that is on.
    p = parse_program("[Walk] <tv> (1)\n[TurnTo] <tv> (1)\n[SwitchOn] <tv> (1)")
    for seed in range(6):
        g = ground(p, home, seed=seed)
        assert g.bindings[("tv", 1)] == 14
    assert home.to_dict() == before


def test_a_thousand_steps_ground_and_backtrack_without_recursion():
    # The API accepts 1000 steps; a recursive search hit RecursionError near 990 (issue 12).
    home = two_tv_home(["ON"])
    p = parse_program("[Walk] <tv> (1)\n" + "[TurnTo] <tv> (1)\n" * 998 + "[SwitchOn] <tv> (1)")
    chose_on_first = 0
    for seed in range(4):
        g = ground(p, home, seed=seed)
        assert g.bindings[("tv", 1)] == 14 and len(g.program.steps) == 1000
        chose_on_first += g.step_runs > 1000  # the tv that is on was tried first, undone
    assert chose_on_first  # some seed backtracked over all 999 steps
    assert execute(g.program, home).executable


def test_prefers_objects_near_the_ones_already_chosen():
    home = load_home("scene1_trimmed")
    p = parse_program("[Walk] <computer> (1)\n[SwitchOn] <computer> (1)\n"
                      "[Find] <keyboard> (1)\n[Type] <keyboard> (1)\n[Find] <mouse> (1)")
    for seed in range(5):
        g = ground(p, home, seed=seed)
        room = home.room_of(g.bindings[("computer", 1)])
        assert home.room_of(g.bindings[("keyboard", 1)]) == room
        assert home.room_of(g.bindings[("mouse", 1)]) == room


def test_same_seed_same_grounding():
    home = load_home("scene1")
    p = parse_program(WATCH)
    assert ground(p, home, seed=7) == ground(p, home, seed=7)


def test_standing_spots_with_geometry():
    home = load_home("scene1")
    g = ground(parse_program(WATCH + "\n[StandUp]\n[Walk] <fridge> (1)\n[Open] <fridge> (1)"),
               home)
    assert g.standing is not None
    plan = FloorPlan(home)
    assert set(g.standing) == set(range(len(g.program)))
    for index, (x, z) in g.standing.items():
        step = g.program.steps[index]
        if not step.args:
            continue
        node = home.node(step.args[-1].node_id)
        assert plan.is_free(home.room_of(node.id), x, z)
        box = node.bounding_box
        gap = math.hypot(max(0.0, abs(x - box.center[0]) - box.size[0] / 2),
                         max(0.0, abs(z - box.center[2]) - box.size[2] / 2))
        assert gap <= 1.6
    # the spot stays while the agent acts without moving
    assert g.standing[3] == g.standing[2]


def test_missing_object_names_step_and_classes_in_plain_words():
    with pytest.raises(GroundingError) as e:
        ground(parse_program("[Walk] <dining_room> (1)\n[Grab] <wine_glass> (1)"),
               load_home("scene1_trimmed"))
    # No function names: web users read this message too.
    assert str(e.value) == ("step 2 [Grab] <wine_glass> (1): the home has no wine_glass or "
                            "wineglass for <wine_glass> (1)")
    with pytest.raises(GroundingError, match=r"no television_set for <television_set> \(1\); "
                       r"did you mean television\?$"):
        ground(parse_program("[Walk] <television_set> (1)"), load_home("scene1_trimmed"))


def test_contradictory_steps_fail_with_the_reason_and_what_was_tried():
    home = load_home("scene1_trimmed")
    p = parse_program("[Walk] <television> (1)\n[SwitchOn] <television> (1)\n"
                      "[SwitchOn] <television> (1)")
    with pytest.raises(GroundingError) as e:
        prepare_and_ground(p, home)
    msg = str(e.value)
    assert msg.startswith("step 3 [SwitchOn] <television> (1): cannot be grounded: ")
    assert "is not off" in msg and "tried <television> (1) as television" in msg
    assert e.value.step == 3


def test_object_out_of_reach_everywhere_fails():
    # Sitting down, nothing can be grabbed from the other room.
    p = parse_program("[Walk] <sofa> (1)\n[Sit] <sofa> (1)\n[Grab] <plate> (1)")
    home = EnvironmentGraph.from_dict(tiny_home_dict())
    with pytest.raises(GroundingError, match=r"step 3 \[Grab\] <plate> \(1\): cannot be "
                                             r"grounded: the character is not close to plate"):
        ground(p, home)


def test_too_few_instances_fail_clearly():
    home = EnvironmentGraph.from_dict(tiny_home_dict())
    with pytest.raises(GroundingError, match=r"step 2 \[Walk\] <tv> \(2\): cannot be grounded: "
                       r"all 1 instances of <tv> in the home are bound to other objects"):
        ground(parse_program("[Walk] <tv> (1)\n[Walk] <tv> (2)"), home)


def test_budget_stops_the_search():
    home = load_home("scene1_trimmed")
    text = "\n".join(f"[Walk] <chair> ({i})" for i in range(1, 4)) + "\n[Sit] <television> (1)"
    with pytest.raises(GroundingError, match=r"step 4 \[Sit\] <television> \(1\): cannot be "
                       r"grounded: .*\(search stopped after 6 step runs\)"):
        ground(parse_program(text), home, budget=5)


def test_repair_adds_an_instance_where_the_program_needs_it():
    # The home's phone is far from the table the program grabs it at: add one there.
    home = load_home("scene1_trimmed")
    p = parse_program("[Walk] <home_office> (1)\n[Walk] <table> (1)\n[Find] <phone> (1)\n"
                      "[Grab] <phone> (1)")
    prepared, g = prepare_and_ground(p, home)
    assert execute(g.program, prepared.graph).executable


def test_unground_renumbers_per_class():
    p = parse_program("[Walk] <cup> (1.40)\n[Walk] <cup> (1.12)\n[Grab] <plate> (1.7)\n"
                      "[Grab] <cup> (1.40)")
    u = unground(p)
    assert str(u) == ("[Walk] <cup> (1)\n[Walk] <cup> (2)\n[Grab] <plate> (1)\n"
                      "[Grab] <cup> (1)")
    assert not u.is_grounded


@pytest.mark.dataset
@pytest.mark.parametrize("home", [f"scene{i}{t}" for i in range(1, 6)
                                  for t in ("_trimmed", "")])
def test_real_programs_run_in_every_home(real_data, home):
    """A small CI subset; benchmarks/grounding.py runs all 518 in every home."""
    from homesim.knowledge import real_programs

    graph = load_home(home)
    programs = real_programs(real_data)[::100]  # 6 programs spread over the set
    ok = 0
    for rp in programs:
        p = unground(rp.program)
        prepared, g = prepare_and_ground(p, graph, seed=0)
        ok += execute(g.program, prepared.graph).executable
        assert all(ref.node_id in prepared.graph for s in g.program for ref in s.args)
    assert ok >= len(programs) - 1


def test_prepare_never_mutates_and_ground_in_prepared_home():
    home = load_home("scene3")
    before = copy.deepcopy(home.to_dict())
    p = parse_program("[Walk] <kitchen> (1)\n[Find] <wine_glass> (1)\n[Grab] <wine_glass> (1)")
    prep = prepare(p, home, seed=1)
    g = ground(p, prep.graph, seed=1)
    assert home.to_dict() == before
    assert g.bindings[("wine_glass", 1)] == prep.added[0].node_id
    assert execute(g.program, prep.graph).executable


def test_nearest_point_is_the_exact_minimum_of_square_distance():
    import random

    from homesim.ground.search import _Points
    from homesim.world.standing import square_distance

    rng = random.Random(0)
    for _ in range(2000):
        scale = rng.choice([1.0, 30.0, 1e300])

        def coord(scale=scale):
            return rng.uniform(-scale, scale) if rng.random() < 0.7 else rng.choice(
                [0.0, 0.5, 1e308, -1e308])

        centers = [(coord(), 0.0, coord()) for _ in range(rng.randint(1, 20))]
        query = (coord(), 0.0, coord())
        assert _Points(centers).nearest(query) == min(square_distance(query, c)
                                                      for c in centers)


def test_a_program_with_many_objects_grounds_each_to_its_own_instance():
    # Many chosen objects on one surface: the surface index and the nearest-point sweep of
    # order() (benchmarks/grounding_many.py times them against comparing every pair).
    p = parse_program("".join(f"[Walk] <cup> ({i})\n" for i in range(1, 61)))
    for home in ("scene1_trimmed", "scene1"):
        _, g = prepare_and_ground(p, load_home(home))
        assert len(set(g.bindings.values())) == 60


def test_eaten_food_is_eatable_in_full_homes(shared_data):
    """Issue 12: scene2 and scene3 have food but none of it EATABLE, scene1 one piece; a
    program eating six pieces gets eatable ones (added by preparation), as in the trimmed
    homes."""
    from homesim.ground.search import prepare_and_ground
    from homesim.sim import execute

    text = "[Walk] <kitchen> (1)\n" + "".join(
        f"[Walk] <food_food> ({i})\n[Eat] <food_food> ({i})\n" for i in range(1, 7))
    program = parse_program(text)
    for home in ("scene1", "scene2", "scene3", "scene2_trimmed"):
        prepared, grounding = prepare_and_ground(program, load_home(home), seed=0)
        assert execute(grounding.program, prepared.graph).executable, home
        eaten = {grounding.bindings[("food_food", i)] for i in range(1, 7)}
        assert all("EATABLE" in prepared.graph.node(n).properties for n in eaten), home
