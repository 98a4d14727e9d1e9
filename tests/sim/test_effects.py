"""Preconditions and effects of each action on the tiny home of conftest.

Tiny home: kitchen 1 (character 10, closed fridge 11 holding cup 12, table 13 with
plate 16) and living_room 2 (tv 14 off, sofa 15 facing the tv).
"""

import pytest

from homesim.program import parse_program
from homesim.sim import execute


def run(home, text):
    return execute(parse_program(text), home, reference=True)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[Grab] <plate> (16)", "step 1 [Grab] <plate> (16): the character is not close to plate 16"),
        ("[Grab] <cup> (12)", "step 1 [Grab] <cup> (12): cup 12 is inside closed fridge 11"),
        ("[Walk] <fridge> (11)\n[Grab] <cup> (12)",
         "step 2 [Grab] <cup> (12): cup 12 is inside closed fridge 11"),
        ("[Walk] <fridge> (11)\n[Close] <fridge> (11)", "fridge 11 is not open"),
        ("[Walk] <tv> (14)\n[SwitchOff] <tv> (14)", "tv 14 is not on"),
        ("[Walk] <tv> (14)\n[Open] <tv> (14)", "tv 14 cannot be opened or closed"),
        ("[Walk] <table> (13)\n[Grab] <table> (13)", "table 13 cannot be grabbed"),
        ("[Walk] <table> (13)\n[Sit] <table> (13)", "table 13 cannot be sat on"),
        ("[StandUp]", "the character is not sitting or lying"),
        ("[Walk] <sofa> (15)\n[Sit] <sofa> (15)\n[Walk] <tv> (14)",
         "the character is sitting; it must stand up first"),
        ("[LookAt] <tv> (14)", "the character does not face tv 14"),
        ("[Walk] <table> (13)\n[Drop] <plate> (16)", "the character is not holding plate 16"),
        ("[Walk] <table> (13)\n[PutObjBack] <plate> (16)", "plate 16 was not grabbed"),
        ("[Walk] <tv> (14)\n[Watch] <tv> (14)", "the character does not face tv 14"),
        ("[Walk] <table> (13)\n[Grab] <plate> (16)\n[Walk] <tv> (14)\n[PutBack] <plate> (16) <table> (13)",
         "the character is not close to table 13"),
        ("[Walk] <fridge> (11)\n[Open] <fridge> (11)\n[Grab] <cup> (12)\n[Close] <fridge> (11)\n"
         "[PutIn] <cup> (12) <fridge> (11)", "fridge 11 is closed"),
        ("[Walk] <tv> (99)", "the home has no node 99 for <tv> (99)"),
        ("[Walk] <table> (13)\n[Wipe] <table> (13)", "the character holds nothing to wipe with"),
        ("[Walk] <table> (13)\n[Eat] <table> (13)", "table 13 is not food and has no food on it"),
        ("[Greet] <tv> (14)", "tv 14 is not a person"),
    ],
)
def test_failing_step_gives_the_reason(tiny_home, text, message):
    r = run(tiny_home, text)
    assert not r.executable
    assert message in r.message
    assert r.failed_step == len(parse_program(text))
    assert r.failed_index == r.failed_step - 1


def test_walk_moves_the_character_and_makes_it_close(tiny_home):
    r = run(tiny_home, "[Walk] <tv> (14)")
    g = r.final_graph
    assert g.targets(10, "INSIDE") == {2}
    assert g.has_edge(10, "CLOSE", 14) and g.has_edge(14, "CLOSE", 10)


def test_walk_to_a_surface_gets_close_to_what_is_on_it(tiny_home):
    g = run(tiny_home, "[Walk] <table> (13)").final_graph
    assert g.has_edge(10, "CLOSE", 16)


def test_find_walks_when_far_and_not_when_close(tiny_home):
    r = run(tiny_home, "[Find] <sofa> (15)")
    assert r.final_graph.targets(10, "INSIDE") == {2}


def test_open_grab_put_in_and_back(tiny_home):
    r = run(tiny_home, "[Walk] <fridge> (11)\n[Open] <fridge> (11)\n[Grab] <cup> (12)\n"
                       "[Walk] <table> (13)\n[PutBack] <cup> (12) <table> (13)")
    assert r.executable, r.message
    g = r.final_graph
    assert "OPEN" in g.node(11).states
    assert g.has_edge(12, "ON", 13)
    assert not g.targets(10, "HOLDS_RH")
    assert 11 not in g.targets(12, "INSIDE")


def test_grab_uses_the_right_hand_then_the_left(tiny_home):
    r = run(tiny_home, "[Walk] <fridge> (11)\n[Open] <fridge> (11)\n[Grab] <cup> (12)\n"
                       "[Walk] <table> (13)\n[Grab] <plate> (16)")
    g = r.final_graph
    assert g.targets(10, "HOLDS_RH") == {12} and g.targets(10, "HOLDS_LH") == {16}
    r = run(tiny_home, "[Walk] <table> (13)\n[Grab] <plate> (16)\n[Grab] <plate> (16)")
    assert r.final_graph.targets(10, "HOLDS_LH") == {16}  # both hands now hold it


def test_put_obj_back_returns_it_where_it_was(tiny_home):
    r = run(tiny_home, "[Walk] <table> (13)\n[Grab] <plate> (16)\n[Walk] <tv> (14)\n"
                       "[Walk] <table> (13)\n[PutObjBack] <plate> (16)")
    assert r.executable, r.message
    assert r.final_graph.has_edge(16, "ON", 13)


def test_hands_full(tiny_home):
    r = run(tiny_home, "[Walk] <fridge> (11)\n[Open] <fridge> (11)\n[Grab] <cup> (12)\n"
                       "[Walk] <table> (13)\n[Grab] <plate> (16)\n[Walk] <fridge> (11)\n"
                       "[Close] <fridge> (11)\n[Open] <fridge> (11)")
    assert r.message.endswith("the character has no free hand (it holds cup 12, plate 16)")


def test_watch_tv_program(tiny_home):
    r = run(tiny_home, "[Walk] <tv> (14)\n[SwitchOn] <tv> (14)\n[Walk] <sofa> (15)\n"
                       "[Sit] <sofa> (15)\n[Watch] <tv> (14)\n[StandUp]")
    assert r.executable, r.message
    g = r.final_graph
    assert "ON" in g.node(14).states and "OFF" not in g.node(14).states
    assert g.has_edge(10, "ON", 15) and g.has_edge(10, "FACING", 14)
    assert "SITTING" not in g.node(10).states


def test_lie_then_sleep_and_capacity(tiny_home):
    r = run(tiny_home, "[Walk] <sofa> (15)\n[Lie] <sofa> (15)\n[Sleep]\n[WakeUp]")
    assert r.executable and "LYING" in r.final_graph.node(10).states
    r = run(tiny_home, "[Walk] <sofa> (15)\n[Lie] <sofa> (15)\n[Lie] <sofa> (15)")
    assert "already lying" in r.message


def test_carried_object_comes_along(tiny_home):
    r = run(tiny_home, "[Walk] <table> (13)\n[Grab] <plate> (16)\n[Walk] <tv> (14)")
    g = r.final_graph
    assert g.has_edge(10, "CLOSE", 16) and g.has_edge(10, "HOLDS_RH", 16)


def test_water_and_children_are_taken_though_not_grabbable():
    from homesim.sim.effects import can_grab

    assert can_grab(frozenset(), "water") and can_grab(frozenset(), "child")
    assert can_grab(frozenset({"GRABBABLE"}), "cup")
    assert not can_grab(frozenset({"POURABLE"}), "milk_jug")
