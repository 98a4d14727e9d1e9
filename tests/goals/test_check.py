import pytest

from homesim.goals.check import GoalSet, Trajectory, check_goals, holds
from homesim.goals.formula import parse_formula
from homesim.ground.pipeline import run_program

PROGRAM = """[Walk] <fridge> (1.11)
[Open] <fridge> (1.11)
[Grab] <cup> (1.12)
[Walk] <tv> (1.14)
[SwitchOn] <tv> (1.14)"""


@pytest.fixture
def trajectory(tiny_home):
    run = run_program(PROGRAM, tiny_home, trace=True)
    assert run.executable, run.message
    return Trajectory(run.graph, run.result.trace)


@pytest.mark.parametrize(("text", "expected"), [
    ("ON(tv.14)", True),
    ("OFF(tv.14)", False),
    ("OPEN(fridge.11) and ON(tv.14)", True),
    ("CLOSED(fridge.11) then OPEN(fridge.11)", True),
    ("OPEN(fridge.11) then CLOSED(fridge.11)", False),
    ("exists x. (GRAB(x)) then exists y. (SWITCHON(y))", True),
    ("exists x. (SWITCHON(x)) then exists y. (GRAB(y))", False),
    ("GRAB(cup.12)", True),
    ("GRAB(plate.16)", False),
    ("exists x. (OPEN(x))", True),
    ("forall x. (not OPEN(x))", False),
    ("not ON(tv.14) then ON(tv.14)", True),
    ("ON(tv.14) then not ON(tv.14)", False),
    ("forn 2. x. (WALK(x))", True),
    ("forn 3. x. (WALK(x))", False),
])
def test_formulas_on_a_trace(trajectory, text, expected):
    assert holds(parse_formula(text), trajectory) is expected


def test_facts_at_each_time(trajectory):
    assert trajectory.length == 5
    assert trajectory.has_state(11, "CLOSED", 1) and trajectory.has_state(11, "OPEN", 2)
    assert not trajectory.has_state(14, "ON", 4) and trajectory.has_state(14, "ON", 5)


def test_goal_set(trajectory):
    hand = "HOLDS_RH" if trajectory.has_edge(10, "HOLDS_RH", 12, 5) else "HOLDS_LH"
    goals = GoalSet(states=((14, "tv", "ON"), (11, "fridge", "CLOSED")),
                    relations=((10, hand, 12),),
                    actions=(("GRAB",), ("WATCH", "SWITCHON")))
    report = check_goals(goals, trajectory)
    assert not report.success
    assert report.unmet == ("CLOSED(fridge.11)",)
    assert report.counts == {"state": (1, 2), "relation": (1, 1), "action": (2, 2)}


def test_action_goals_count_in_order(trajectory):
    report = check_goals(GoalSet(actions=(("SWITCHON",), ("GRAB",))), trajectory)
    assert report.counts["action"] == (1, 2) and report.unmet == ("GRAB",)


def test_every_gold_program_meets_its_goals(real_data):
    """The annotated programs themselves satisfy their goal sets and formulas."""
    from homesim.goals.eai import load_eai_goals
    from homesim.knowledge.datasets import real_programs

    goals = load_eai_goals(real_data)
    programs = {p.id: p for p in real_programs(real_data)}
    for pid in sorted(goals)[::17]:  # a spread sample keeps the test fast
        run = run_program(programs[pid].program, programs[pid].graph(), trace=True)
        tr = Trajectory(run.graph, run.result.trace)
        assert check_goals(goals[pid].goals, tr).success, pid
        if goals[pid].formula is not None:
            assert holds(goals[pid].formula, tr), pid
