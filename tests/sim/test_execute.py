import copy

import pytest

from homesim.errors import BindingError, ExecutionError
from homesim.program import parse_program
from homesim.sim import SimState, execute
from homesim.world.graph import EnvironmentGraph
from tests.conftest import tiny_home_dict

PROGRAM = ("[Walk] <table> (13)\n[Grab] <plate> (16)\n[Walk] <tv> (14)\n[SwitchOn] <tv> (14)\n"
           "[PutBack] <plate> (16) <tv> (14)")


def test_input_graph_is_never_mutated(tiny_home):
    before = copy.deepcopy(tiny_home.to_dict())
    r = execute(parse_program(PROGRAM), tiny_home, trace=True, reference=True)
    assert r.executable
    assert r.final_graph != tiny_home
    assert tiny_home.to_dict() == before


def test_trace_records_deltas_per_step(tiny_home):
    r = execute(parse_program(PROGRAM), tiny_home, trace=True, reference=True)
    assert [rec.ok for rec in r.trace] == [True] * 5
    switch = r.trace[3].changes
    assert switch.states == ((14, frozenset({"OFF"}), frozenset({"ON"})),)
    assert not switch.added and not switch.removed
    grab = r.trace[1].changes
    assert (10, "HOLDS_RH", 16) in grab.added and (16, "ON", 13) in grab.removed
    assert r.trace[4].nodes == (16, 14)


def test_replaying_the_trace_gives_the_final_graph(tiny_home):
    r = execute(parse_program(PROGRAM), tiny_home, trace=True, reference=True)
    edges = set(tiny_home.edges())
    states = {n.id: n.states for n in tiny_home}
    for rec in r.trace:
        edges -= set(rec.changes.removed)
        edges |= set(rec.changes.added)
        for node, before, after in rec.changes.states:
            assert states[node] == before
            states[node] = after
    assert edges == set(r.final_graph.edges())
    assert states == {n.id: n.states for n in r.final_graph}


def test_failed_run_keeps_state_before_the_failing_step(tiny_home):
    r = execute(parse_program("[Walk] <tv> (14)\n[SwitchOn] <tv> (14)\n[Grab] <tv> (14)"),
                tiny_home, trace=True, reference=True)
    assert (r.executable, r.failed_step, r.steps_run) == (False, 3, 2)
    assert "ON" in r.final_graph.node(14).states
    assert r.trace[-1].ok is False and not r.trace[-1].changes


def test_bindings_map_program_objects_to_nodes(tiny_home):
    p = parse_program("[Walk] <television> (1)\n[SwitchOn] <television> (1)")
    r = execute(p, tiny_home, bindings={("television", 1): 14})
    assert r.executable and "ON" in r.final_graph.node(14).states


def test_graph_without_character_is_an_error():
    d = tiny_home_dict()
    d["nodes"] = [n for n in d["nodes"] if n["class_name"] != "character"]
    d["edges"] = [e for e in d["edges"] if 10 not in (e["from_id"], e["to_id"])]
    with pytest.raises(ExecutionError, match="no character node"):
        execute(parse_program("[Walk] <tv> (14)"), EnvironmentGraph.from_dict(d), reference=True)


def test_undo_restores_the_state_exactly(tiny_home):
    st = SimState(tiny_home)
    r0 = execute(parse_program("[Walk] <table> (13)"), tiny_home, reference=True)
    from homesim.sim import execute_on

    execute_on(parse_program("[Walk] <table> (13)"), st, reference=True)
    mark = st.mark()
    execute_on(parse_program("[Grab] <plate> (16)\n[Walk] <tv> (14)\n[SwitchOn] <tv> (14)"), st,
               reference=True)
    assert st.to_graph() != r0.final_graph
    st.undo(mark)
    assert st.to_graph() == r0.final_graph
    st.undo(0)
    assert st.to_graph() == tiny_home


def test_message_when_all_steps_ran(tiny_home):
    r = execute(parse_program("[Walk] <tv> (1.14)"), tiny_home)
    assert r.message == "executable: all 1 steps ran" and r.failed_step is None


def test_an_ungrounded_ref_is_refused_unless_reference_is_asked_for(tiny_home):
    p = parse_program("[Walk] <tv> (14)\n[SwitchOn] <tv> (14)")
    with pytest.raises(BindingError, match=r"^step 1 \[Walk\] <tv> \(14\): <tv> \(14\) names no "
                       r"node: .*reference=True"):
        execute(p, tiny_home)
    assert execute(p, tiny_home, reference=True).executable


def test_a_ref_bound_to_a_node_of_another_class_is_refused(tiny_home):
    p = parse_program("[Walk] <tv> (1.14)\n[Walk] <sofa> (1.13)")
    with pytest.raises(BindingError, match=r"^step 2 \[Walk\] <sofa> \(1.13\): <sofa> \(1\) is "
                       r"node 13, a table, not a sofa") as e:
        execute(p, tiny_home)
    assert (e.value.step, e.value.obj, e.value.node) == (2, "<sofa> (1)", 13)
    with pytest.raises(BindingError, match="the home has no node 99 for <tv> \\(1\\)"):
        execute(parse_program("[Walk] <tv> (1.99)"), tiny_home)


def test_equivalent_class_names_match_as_in_grounding(tiny_home):
    # television and tv are one class for the knowledge base (and for grounding)
    assert execute(parse_program("[Walk] <television> (1.14)"), tiny_home).executable


def test_one_object_bound_to_two_nodes_is_refused(tiny_home):
    with pytest.raises(BindingError, match="is node 15 here but node 14 at an earlier step"):
        execute(parse_program("[Walk] <tv> (1.14)\n[Walk] <tv> (1.15)"), tiny_home)


def test_reference_mode_reads_the_instance_as_a_node_id():
    from homesim.world import load_home

    home = load_home("scene1_trimmed")
    p = parse_program("[Walk] <tv> (1)\n[SwitchOn] <tv> (1)")
    with pytest.raises(BindingError, match="names no node"):
        execute(p, home)
    r = execute(p, home, reference=True)  # node 1 is a room: walks there, then fails
    assert home.node(1).category == "Rooms" and r.failed_step == 2
