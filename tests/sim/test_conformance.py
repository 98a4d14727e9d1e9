"""The simulator against the graphs stored with the 518 real programs.

Each program runs from its stored initial graph; node states and the INSIDE, ON,
HOLDS_RH and HOLDS_LH edges of the result must equal the stored final graph. CLOSE and
FACING agreement are measured too (docs/simulator.md explains where CLOSE differs).
"""

import pytest

from homesim.knowledge.datasets import real_programs
from homesim.sim import execute
from homesim.sim.compare import CORE_ASPECTS, compare_graphs

pytestmark = pytest.mark.dataset


@pytest.fixture(scope="module")
def outcomes(real_data):
    results = []
    for rp in real_programs(real_data):
        init, final = rp.graphs()
        r = execute(rp.program, init, reference=True)
        results.append((rp, r, compare_graphs(r.final_graph, final) if r.executable else None))
    return results


def test_all_518_real_programs_are_executable(outcomes):
    assert len(outcomes) == 518
    failed = [(rp.id, r.message) for rp, r, _ in outcomes if not r.executable]
    assert failed == []


def test_final_states_and_core_relations_equal_the_stored_graphs(outcomes):
    wrong = {rp.id: sorted(set(d) & set(CORE_ASPECTS)) for rp, _, d in outcomes
             if d is not None and set(d) & set(CORE_ASPECTS)}
    assert wrong == {}


def test_facing_agrees_everywhere_and_close_mostly(outcomes):
    diffs = [d for _, _, d in outcomes if d is not None]
    assert sum("FACING" not in d for d in diffs) == len(diffs)
    # CLOSE differs only where the old executor made the character close to itself or
    # picked another resting place for PutObjBack (docs/simulator.md): measured 429/518
    # exactly, 501/518 ignoring character self-loops.
    exact = sum("CLOSE" not in d for d in diffs)
    no_self = sum(
        "CLOSE" not in d or (not d["CLOSE"][0] and all(a == b for a, b in d["CLOSE"][1]))
        for d in diffs
    )
    assert exact >= 429 and no_self >= 501


def test_input_graphs_are_left_unchanged(real_data):
    rp = real_programs(real_data)[0]
    init, _ = rp.graphs()
    before = init.to_dict()
    execute(rp.program, init, trace=True, reference=True)
    assert init.to_dict() == before


def test_every_real_program_round_trips_through_print(real_data):
    from homesim.program import parse_program

    for rp in real_programs(real_data):
        assert parse_program(str(rp.program)) == rp.program


def test_the_real_programs_pass_the_binding_check_with_the_same_outcome(outcomes):
    """The stored programs are grounded (``(1.417)``): checked mode runs them as the
    reference mode does."""
    for rp, ref, _ in outcomes:
        init, _ = rp.graphs()
        checked = execute(rp.program, init)
        assert (checked.executable, checked.final_graph) == (ref.executable, ref.final_graph)
