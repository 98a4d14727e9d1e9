"""Contract tests: the action catalog is the one table about actions.

Every registry keyed by action (effects; animations through the `motion` column) covers
every catalog row and keys nothing the catalog lacks; the columns agree with the
simulator; and adding an action is one row + one effect (+ one animation when no
existing motion fits), as docs/simulator.md ("Adding an action") walks through.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import pytest

from homesim.program import ACTIONS, ActionSpec, Category, lookup_action, parse_program
from homesim.program.actions import _needs
from homesim.sim import EFFECTS, Failure, FailureKind, execute
from homesim.sim.state import SimState
from homesim.world.graph import EnvironmentGraph
from tests.conftest import tiny_home_dict


def registry_problems(actions: Mapping[str, ActionSpec], effects: Mapping[str, object],
                      motions: Mapping[str, object] | None) -> list[str]:
    """What is wrong between the catalog and the registries (empty when they agree)."""
    problems = [f"{k}: no effect" for k in actions if k not in effects]
    problems += [f"{k}: effect of an action the catalog lacks" for k in effects
                 if k not in actions]
    if motions is not None:
        used = {a.motion for a in actions.values()}
        problems += [f"{k}: no animation {a.motion!r}" for k, a in actions.items()
                     if a.motion not in motions]
        problems += [f"animation {m!r}: no action uses it" for m in motions if m not in used]
    return problems


def _motions() -> Mapping[str, object] | None:
    try:
        from homesim.render.animate import MOTIONS
    except ImportError:  # no render extra: effects are still checked
        return None
    return MOTIONS


def test_every_registry_covers_the_catalog_and_nothing_more():
    assert registry_problems(ACTIONS, EFFECTS, _motions()) == []


def test_animations_by_action_derive_from_the_catalog():
    animate = pytest.importorskip("homesim.render.animate")
    assert set(animate.ANIMATIONS) == set(ACTIONS)
    for key, spec in ACTIONS.items():
        assert animate.animation_for(key) is animate.MOTIONS[spec.motion]


def test_a_row_without_effect_or_animation_is_reported(monkeypatch):
    knock = ActionSpec("KNOCK", "Knock", 1, Category.HANDS, False, "knock on a door",
                       motion="knock")
    monkeypatch.setitem(ACTIONS, "KNOCK", knock)
    problems = registry_problems(ACTIONS, EFFECTS, {"knock": None} | dict(_motions() or {}))
    assert problems == ["KNOCK: no effect"]
    problems = registry_problems(ACTIONS, EFFECTS, _motions() or {})
    assert "KNOCK: no effect" in problems and "KNOCK: no animation 'knock'" in problems


def test_adding_an_action_is_one_row_and_one_effect(monkeypatch):
    """The worked example of docs/simulator.md: [Knock] <door>, animated as a reach."""
    knock = ActionSpec("KNOCK", "Knock", 1, Category.HANDS, False, "knock on a door",
                       motion="reach", reach=True, needs=_needs("CAN_OPEN"),
                       presupposes=("CLOSED",))
    monkeypatch.setitem(ACTIONS, "KNOCK", knock)

    def knock_effect(st: SimState, n: int) -> Failure | None:
        if "CLOSED" not in st.states(n):
            return Failure(FailureKind.ALREADY, f"{st.label(n)} is open; no need to knock")
        return None

    monkeypatch.setitem(EFFECTS, "KNOCK", knock_effect)
    assert registry_problems(ACTIONS, EFFECTS, _motions()) == []
    home = EnvironmentGraph.from_dict(tiny_home_dict())
    program = parse_program("[Walk] <fridge> (11)\n[Knock] <fridge> (11)\n"
                            "[Open] <fridge> (11)\n[Knock] <fridge> (11)")
    result = execute(program, home, reference=True)
    assert result.failed_step == 4 and "is open; no need to knock" in result.message
    assert result.kind is FailureKind.ALREADY


def test_rows_are_consistent():
    for key, a in ACTIONS.items():
        assert a.key == key == a.name.upper()
        assert len(a.needs) <= a.arity, key
        assert (a.connector is not None) == (a.arity == 2), key
        assert a.reach <= (a.arity >= 1) and a.moves <= (a.arity == 1), key
        for alias in a.aliases:
            assert alias not in ACTIONS and lookup_action(alias) is a
        assert a.to_dict()["key"] == key and a.to_dict()["connector"] == a.connector


def _far_home() -> EnvironmentGraph:
    """The character in the kitchen holding a cup; in the living room an object with
    every property (and, for puts, a destination like it)."""
    every = ["GRABBABLE", "HAS_SWITCH", "HAS_PLUG", "CAN_OPEN", "SITTABLE", "LIEABLE",
             "LOOKABLE", "READABLE", "CLOTHES", "DRINKABLE", "POURABLE", "RECIPIENT",
             "PERSON", "CUTTABLE", "EATABLE", "MOVABLE", "SURFACES", "CONTAINERS"]
    nodes = [{"id": 1, "class_name": "kitchen", "category": "Rooms"},
             {"id": 2, "class_name": "living_room", "category": "Rooms"},
             {"id": 10, "class_name": "character", "category": "Characters"},
             {"id": 12, "class_name": "cup", "properties": every},
             {"id": 20, "class_name": "thing", "properties": every,
              "states": ["CLOSED", "OFF", "PLUGGED_OUT", "DIRTY"]}]
    edges = [(10, "INSIDE", 1), (12, "INSIDE", 1), (10, "HOLDS_RH", 12), (10, "CLOSE", 12),
             (12, "CLOSE", 10), (20, "INSIDE", 2)]
    return EnvironmentGraph.from_dict({"nodes": nodes, "edges": [
        {"from_id": a, "relation_type": r, "to_id": b} for a, r, b in edges]})


@pytest.mark.parametrize("key", [k for k, a in ACTIONS.items() if a.arity >= 1])
def test_reach_column_is_the_simulators_closeness_check(key):
    """`reach` is True exactly for the actions whose effect needs the character close to
    their (last) object: acting on a far object fails with "not close" for those only."""
    spec = ACTIONS[key]
    st = SimState(_far_home())
    args = (12, 20) if spec.arity == 2 else (20,)
    failure = EFFECTS[key](st, *args)
    reason = failure.reason if failure is not None else ""
    assert ("not close" in reason) == spec.reach, (key, reason)
    if spec.reach:
        assert failure is not None and failure.kind is FailureKind.UNREACHABLE


def test_to_dict_is_json_ready():
    import json

    rows = [a.to_dict() for a in ACTIONS.values()]
    assert json.loads(json.dumps(rows)) == rows
    assert {f.name for f in dataclasses.fields(ActionSpec)} == set(rows[0])
