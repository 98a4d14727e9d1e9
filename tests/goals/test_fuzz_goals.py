"""Fuzz: goal formulas and plan texts, however hostile, give an answer or one clear error.

A formula parses (and prints back to itself, and is judged on a trace without error) or
raises `GoalError` / `LimitError`; a plan always gets a `PlanScore` whose error is one of
EAI's kinds, in both modes. Bounded and derandomized: every run tries the same cases.
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from homesim.errors import HomesimError
from homesim.goals.check import GoalSet, Trajectory, holds
from homesim.goals.contexts import TaskContext
from homesim.goals.eai import TaskGoals
from homesim.goals.formula import parse_formula
from homesim.goals.plans import GRAMMAR_KINDS, RUNTIME_KINDS, score_plan
from homesim.program import parse_program
from homesim.sim import execute


def _cases(n: int) -> Any:
    return settings(derandomize=True, max_examples=n, deadline=None, database=None,
                    suppress_health_check=list(HealthCheck))


_FORMULA_PARTS = ["(", ")", " ", "and", "or", "then", "not", "exists", "forall", "forn",
                  ".", ",", "x", "x0", "y", "ON", "OFF", "ONTOP", "GRAB", "TYPE", "FLY",
                  "tv.14", "sofa.15", "tv.9999999999", "2", "9" * 5000, "(" * 300,
                  ")" * 300, "\u2028", "é", "\x00", "tv.", ".14", "character.10"]
formula_texts = st.lists(st.one_of(st.sampled_from(_FORMULA_PARTS), st.text(max_size=4)),
                         max_size=30).map(" ".join)


@st.composite
def formulas(draw: Any, depth: int = 3, quantifiers: int = 2) -> str:
    """A well-formed formula over the tiny home's nodes (for the judge)."""
    atom = st.sampled_from(["ON(tv.14)", "OFF(tv.14)", "CLOSED(fridge.11)",
                            "ONTOP(plate.16, table.13)", "NEXT_TO(character.10, tv.14)",
                            "SWITCHON(tv.14)", "WALK(tv.14)"])
    if depth == 0:
        return draw(atom)
    kinds = ["atom", "not", "and", "or", "then"] + ["exists", "forall"] * (quantifiers > 0)
    kind = draw(st.sampled_from(kinds))
    if kind == "atom":
        return draw(atom)
    if kind == "not":
        return f"not {draw(formulas(depth - 1, quantifiers))}"
    if kind in ("and", "or", "then"):
        parts = draw(st.lists(formulas(depth - 1, quantifiers), min_size=2, max_size=3))
        return "(" + f" {kind} ".join(parts) + ")"
    var = f"x{quantifiers}"
    return f"{kind} {var}. (SWITCHON({var}) or {draw(formulas(depth - 1, quantifiers - 1))})"


@_cases(300)
@given(formula_texts)
@example("(" * 200 + "ON(tv.14)" + ")" * 200)
@example("ON(tv." + "9" * 4301 + ")")
@example("forn " + "9" * 4301 + ". x. (GRAB(x))")
def test_any_formula_text_parses_or_gives_a_one_line_error(text):
    try:
        f = parse_formula(text)
    except HomesimError as e:  # GoalError, LimitError
        assert "\n" not in str(e)
        return
    assert parse_formula(str(f)) == f


@pytest.fixture(scope="module")
def trace():
    from homesim.world.graph import EnvironmentGraph
    from tests.conftest import tiny_home_dict

    home = EnvironmentGraph.from_dict(tiny_home_dict())
    run = execute(parse_program("[Walk] <tv> (14)\n[SwitchOn] <tv> (14)\n[Walk] <table> (13)\n"
                                "[Grab] <plate> (16)"), home, trace=True, reference=True)
    return Trajectory(home, run.trace)


@_cases(150)
@given(formulas())
def test_well_formed_formulas_round_trip_and_are_judged(trace, text):
    f = parse_formula(text)
    assert parse_formula(str(f)) == f
    assert holds(f, trace) in (True, False)
    try:
        parse_formula(text, strict_eai=True)
    except HomesimError as e:
        assert "joins state and temporal goals" in str(e)


_PLAN_PARTS = ['"WALK"', '"GRAB"', '"PUT"', '"PUTBACK"', '"STANDUP"', '"walk"', '"FLY"',
               '"Walk To"', ":", ",", "[", "]", "{", "}", "[]", '"tv"', '"14"', "14",
               '"plate"', '"16"', '"table"', '"13"', '"unicorn"', '"99999"', "'", "```json",
               "```", "\n", " ", "null", "1e999", '"' + "9" * 5000 + '"', "[" * 50,
               "]" * 50, "{" * 40, "\ud800", "\\", '\\"']
plan_texts = st.lists(st.one_of(st.sampled_from(_PLAN_PARTS), st.text(max_size=4)),
                      max_size=50).map("".join)


@pytest.fixture(scope="module")
def context():
    from homesim.world.graph import EnvironmentGraph
    from tests.conftest import tiny_home_dict

    home = EnvironmentGraph.from_dict(tiny_home_dict())
    goals = TaskGoals("file1_1", "Put away", GoalSet(relations=((16, "ON", 13),)), None, "")
    objects = frozenset({("tv", 14), ("table", 13), ("plate", 16), ("kitchen", 1)})
    return TaskContext(goals, home, objects)


@_cases(300)
@given(plan_texts, st.booleans())
@example('{"WALK": ["table", "13"], "GRAB": ["plate", "16"], "PUTBACK": ["plate", "16", '
         '"table", "13"]}', False)
@example('{"WALK": ' + "[" * 3000 + "]" * 3000 + "}", True)
@example('{"WALK": ' + "[" * 3000 + "]" * 3000 + "}", False)
@example("{" + ", ".join(['"WALK": ["tv", "14"]'] * 1001) + "}", False)
def test_any_plan_text_gets_a_verdict(context, text, strict):
    s = score_plan("1_1", text, context, strict_eai=strict)
    assert s.error is None or s.error in GRAMMAR_KINDS + RUNTIME_KINDS
    assert s.reason is None or "\n" not in s.reason
    assert (s.goals is None) == (s.error in GRAMMAR_KINDS)
    s.to_dict()
