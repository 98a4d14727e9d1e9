"""Typed failures: every failing step says what kind of precondition failed.

Tiny home of conftest: kitchen 1 (character 10, closed fridge 11 holding cup 12, table 13
with plate 16) and living_room 2 (tv 14 off, sofa 15 facing the tv).
"""

import pytest

from homesim.program import parse_program
from homesim.sim import EFFECTS, Failure, FailureKind, SimState, execute, run_step
from homesim.world.graph import EnvironmentGraph

K = FailureKind


def run(home, text, trace=False):
    return execute(parse_program(text), home, reference=True, trace=trace)


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        ("[Grab] <plate> (16)", K.UNREACHABLE),
        ("[Grab] <cup> (12)", K.ENCLOSED),
        ("[Walk] <fridge> (11)\n[Close] <fridge> (11)", K.ALREADY),
        ("[Walk] <tv> (14)\n[SwitchOff] <tv> (14)", K.ALREADY),
        ("[Walk] <tv> (14)\n[SwitchOn] <tv> (14)\n[SwitchOn] <tv> (14)", K.ALREADY),
        ("[StandUp]", K.ALREADY),
        ("[Walk] <sofa> (15)\n[Sit] <sofa> (15)\n[Sit] <sofa> (15)", K.ALREADY),
        ("[Walk] <tv> (14)\n[Open] <tv> (14)", K.AFFORDANCE),
        ("[Walk] <table> (13)\n[Grab] <table> (13)", K.AFFORDANCE),
        ("[Greet] <tv> (14)", K.AFFORDANCE),
        ("[Walk] <sofa> (15)\n[Sit] <sofa> (15)\n[Walk] <tv> (14)", K.POSTURE),
        ("[Sleep]", K.POSTURE),
        ("[LookAt] <tv> (14)", K.NOT_FACING),
        ("[Walk] <tv> (14)\n[Watch] <tv> (14)", K.NOT_FACING),
        ("[Walk] <table> (13)\n[Drop] <plate> (16)", K.NOT_HELD),
        ("[Walk] <table> (13)\n[PutObjBack] <plate> (16)", K.NOT_HELD),
        ("[Walk] <table> (13)\n[Wipe] <table> (13)", K.NOT_HELD),
        ("[Walk] <fridge> (11)\n[Open] <fridge> (11)\n[Grab] <cup> (12)\n[Close] <fridge> (11)\n"
         "[PutIn] <cup> (12) <fridge> (11)", K.STATE),
        ("[Walk] <tv> (99)", K.MISSING),
        ("[Walk] <fridge> (11)\n[Open] <fridge> (11)\n[Grab] <cup> (12)\n[Walk] <table> (13)\n"
         "[Grab] <plate> (16)\n[Walk] <fridge> (11)\n[Close] <fridge> (11)\n[Open] <fridge> (11)",
         K.HANDS_FULL),
    ],
)
def test_a_failing_step_has_its_kind(tiny_home, text, kind):
    r = run(tiny_home, text, trace=True)
    assert not r.executable
    assert r.kind is kind
    assert r.trace[-1].kind is kind and r.trace[-1].reason == r.reason
    assert r.to_dict()["kind"] == kind.value


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        # What the object cannot do is named wherever the character stands (U9: typing on
        # a table far away is an affordance error, not a missing walk).
        ("[Type] <table> (13)", K.AFFORDANCE),
        ("[Sit] <table> (13)", K.AFFORDANCE),
        ("[Eat] <table> (13)", K.AFFORDANCE),
        ("[Squeeze] <tv> (14)", K.AFFORDANCE),
        ("[Cut] <table> (13)", K.AFFORDANCE),
        # U8: a room cannot be washed, even after walking into it.
        ("[Walk] <kitchen> (1)\n[Wash] <kitchen> (1)", K.AFFORDANCE),
        ("[Wash] <table> (13)", K.UNREACHABLE),
    ],
)
def test_affordance_comes_before_reach(tiny_home, text, kind):
    assert run(tiny_home, text).kind is kind


def test_a_step_that_runs_has_no_kind(tiny_home):
    r = run(tiny_home, "[Walk] <tv> (14)\n[SwitchOn] <tv> (14)", trace=True)
    assert r.executable and r.kind is None
    assert all(rec.kind is None and rec.ok for rec in r.trace)


def test_run_step_returns_a_failure_and_leaves_the_state(tiny_home):
    st = SimState(tiny_home)
    step = parse_program("[Grab] <plate> (16)").steps[0]
    failure = run_step(st, step, (16,))
    assert isinstance(failure, Failure)
    assert failure.kind is K.UNREACHABLE and str(failure) == failure.reason
    assert st.to_graph().to_dict() == tiny_home.to_dict()


def test_every_effect_fails_with_a_typed_failure(tiny_home: EnvironmentGraph):
    """Contract over the action table: on the tiny home, every action applied to every
    node (or pair) either runs or returns a `Failure` with a kind and a sentence."""
    nodes = sorted(tiny_home.nodes)
    seen = set()
    for key, effect in EFFECTS.items():
        arity = effect.__code__.co_argcount - 1
        cases = [()] if arity == 0 else (
            [(n,) for n in nodes] if arity == 1 else [(a, b) for a in nodes for b in nodes])
        for ids in cases:
            st = SimState(tiny_home)
            out = effect(st, *ids)
            assert out is None or (isinstance(out, Failure) and isinstance(out.kind, K)
                                   and out.reason), (key, ids, out)
            if out is not None:
                seen.add(out.kind)
    assert {K.AFFORDANCE, K.UNREACHABLE, K.ALREADY, K.NOT_HELD} <= seen
