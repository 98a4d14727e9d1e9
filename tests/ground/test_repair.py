"""Repair inserts the missing commonsense steps, says why, and keeps the program's own."""

from __future__ import annotations

import json

import pytest

from homesim.ground.repair import repair
from homesim.program import parse_program


def _own_steps(r) -> list[str]:
    inserted = {i.index for i in r.insertions}
    return [str(s) for i, s in enumerate(r.program.steps) if i not in inserted]


def test_a_walk_is_inserted_before_a_grab_with_its_reason(tiny_home):
    r = repair("[Grab] <plate> (1)", tiny_home)
    assert not r.before.executable and r.executable
    assert [str(s) for s in r.program.steps] == ["[Walk] <plate> (1)", "[Grab] <plate> (1)"]
    (ins,) = r.insertions
    assert (ins.index, ins.before) == (0, 0)
    assert ins.reason == "walk to <plate> (1) before [Grab]: it needs the character close to it"


def test_a_closed_container_is_opened_before_taking_from_it(tiny_home):
    # Grounded: the cup in the fridge (ungrounded, preparation may add another cup).
    r = repair("[Grab] <cup> (1.12)", tiny_home)
    assert r.executable
    # The grab fails with kind `enclosed`: opening the fridge comes first, and walking
    # to it first repairs that in turn.
    assert [str(i.step) for i in r.insertions] == ["[Walk] <fridge> (1.11)",
                                                   "[Open] <fridge> (1.11)"]
    assert "may be inside it" in r.insertions[1].reason


def test_stand_up_before_walking_and_grab_before_put(tiny_home):
    text = ("[Walk] <sofa> (1)\n[Sit] <sofa> (1)\n[Walk] <table> (1)\n"
            "[PutBack] <plate> (1) <table> (1)")
    r = repair(text, tiny_home)
    assert r.executable, r.run.message
    steps = [str(i.step) for i in r.insertions]
    assert steps == ["[StandUp]", "[Grab] <plate> (1)"]
    assert [i.before for i in r.insertions] == [2, 3]
    assert r.insertions[1].reason.startswith("grab <plate> (1) before [PutBack]")


def test_the_program_own_steps_are_never_changed(tiny_home):
    for text in ("[Grab] <cup> (1)\n[PutBack] <cup> (1) <table> (1)",
                 "[Sit] <sofa> (1)\n[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[Watch] <tv> (1)",
                 "[Open] <fridge> (1)\n[PutIn] <plate> (1) <fridge> (1)"):
        program = parse_program(text)
        r = repair(program, tiny_home)
        assert _own_steps(r) == [str(s) for s in program.steps]
        assert r.executable, r.run.message


def test_an_executable_program_is_left_alone(tiny_home):
    r = repair("[Walk] <plate> (1)\n[Grab] <plate> (1)", tiny_home)
    assert r.executable and r.insertions == () and r.runs == 1
    assert r.to_dict()["insertions"] == []


def test_undoing_a_state_is_only_done_when_asked(tiny_home):
    text = "[Walk] <tv> (1.14)\n[SwitchOn] <tv> (1.14)\n[SwitchOn] <tv> (1.14)"
    assert not repair(text, tiny_home).executable
    r = repair(text, tiny_home, undo_states=True)
    assert r.executable
    assert [str(i.step) for i in r.insertions] == ["[SwitchOff] <tv> (1.14)"]
    assert r.insertions[0].reason.endswith("it must be OFF")


def test_the_search_is_bounded(tiny_home):
    assert repair("[Grab] <cup> (1.12)", tiny_home).runs > 2  # needs a walk and an open
    r = repair("[Grab] <cup> (1.12)", tiny_home, max_runs=2)
    assert not r.executable and r.runs == 2
    assert _own_steps(r) == ["[Grab] <cup> (1.12)"]


@pytest.mark.dataset
def test_real_programs_without_walks_are_repaired(real_data):
    from homesim.ground import unground
    from homesim.knowledge import real_programs
    from homesim.world import load_home

    home = load_home("scene1_trimmed")
    before = after = 0
    programs = [unground(rp.program) for rp in real_programs(real_data)][:40]
    for p in programs:
        q = p.with_steps([s for s in p.steps if s.action.key not in ("WALK", "FIND", "RUN")])
        r = repair(q, home)
        before += r.before.executable
        after += r.executable
        assert _own_steps(r) == [str(s) for s in q.steps]
    assert before < 20 and after >= 38


def test_homesim_run_repair_lists_insertions_and_runs_the_repaired_program(tmp_path, capsys):
    from homesim.cli.main import main

    p = tmp_path / "p.txt"
    p.write_text("[Grab] <wine_glass> (1)\n")
    assert main(["run", str(p), "--home", "scene1_trimmed", "--no-repair"]) == 1
    assert "inserted" not in capsys.readouterr().out
    assert main(["run", str(p), "--home", "scene1_trimmed"]) == 0  # repair by default
    out = capsys.readouterr().out
    assert ("inserted step 1 [Walk] <wine_glass> (1): walk to <wine_glass> (1) before "
            "[Grab]") in out
    assert "as written: step 1 [Grab] <wine_glass> (1): cannot be grounded" in out
    assert "executable: all 2 steps ran" in out
    assert main(["run", str(p), "--home", "scene1_trimmed", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["executable"] and len(data["steps"]) == 2
    assert [s["line"] for s in data["steps"]] == [None, None]  # no lines without a file
    assert data["repair"]["executable_before"] is False
    assert [i["step"] for i in data["repair"]["insertions"]] == ["[Walk] <wine_glass> (1)"]
    assert data["message"] == "executable: all 2 steps ran, 1 of them inserted by repair"


def test_no_ground_reads_node_ids_and_never_repairs(tmp_path, capsys):
    from homesim.cli.main import main

    p = tmp_path / "p.txt"
    p.write_text("[Grab] <wine_glass> (1)\n")
    assert main(["run", str(p), "--no-ground", "--json"]) != 0
    data = json.loads(capsys.readouterr().out)
    assert data["repair"] is None and data["steps"][0]["step"] == "[Grab] <wine_glass> (1)"


@pytest.mark.parametrize(("text", "walk"), [
    # The table is not in the program: a new ref, bound to the node it must be.
    ("[Walk] <plate> (1.16)\n[Grab] <plate> (1.16)\n[Walk] <sofa> (1.15)\n"
     "[PutObjBack] <plate> (1.16)", "[Walk] <table> (1.13)"),
    # It is: the program's own ref.
    ("[Walk] <table> (2.13)\n[Grab] <plate> (1.16)\n[Walk] <sofa> (1.15)\n"
     "[PutObjBack] <plate> (1.16)", "[Walk] <table> (2.13)"),
])
def test_put_obj_back_walks_back_to_where_the_object_was_taken_from(tiny_home, text, walk):
    r = repair(text, tiny_home)
    assert r.executable, r.run.message
    (ins,) = r.insertions
    assert (str(ins.step), ins.index) == (walk, 3)
    assert ins.reason.startswith(f"walk back to {walk[7:]}, where <plate>")


def test_same_seed_same_repair():
    text = "[Grab] <remote_control> (1)\n[Sit] <sofa> (1)\n[Walk] <television> (1)"
    a, b = (repair(text, "scene2_trimmed", seed=3).to_dict() for _ in range(2))
    assert a == b and a["insertions"]
    assert json.dumps(a)  # JSON-ready


@pytest.mark.parametrize(("text", "walk"), [
    # Sitting on the couch the character stands by leaves no room to lie on it; a walk
    # before the first step on the couch lets grounding pick another one.
    ("[Sit] <couch> (1)\n[Lie] <couch> (1)", "[Walk] <couch> (1)"),
    # The cellphone at hand cannot be typed on; the phone that can is across the home.
    ("[Grab] <phone> (1)\n[Type] <phone> (1)", "[Walk] <phone> (1)"),
])
def test_a_walk_before_the_first_step_on_an_object_lets_grounding_pick_another(text, walk):
    r = repair(text, "scene4")
    assert not r.before.executable and r.executable
    assert [(i.index, str(i.step), i.before) for i in r.insertions] == [(0, walk, 0)]
    assert "first acts on it" in r.insertions[0].reason
    assert _own_steps(r) == text.split("\n")


def test_repair_reads_the_failure_kind(tiny_home):
    """Facing: the turn is tried before the walk (kind not_facing), so one run finds it."""
    r = repair("[Walk] <tv> (1.14)\n[LookAt] <tv> (1.14)", tiny_home)
    assert r.before.kind.value == "not_facing"
    assert [str(i.step) for i in r.insertions] == ["[TurnTo] <tv> (1.14)"]
    assert r.runs == 2  # the program, then the turn: the first candidate


def test_run_program_switches_off_what_is_on_only_when_nothing_else_helps(tiny_home):
    """Issue 41: a device already on blocked real programs ([SwitchOn] <light>); the
    pipeline's repair then undoes the state, and says so."""
    from homesim.ground.pipeline import run_program

    text = "[Walk] <tv> (1.14)\n[SwitchOn] <tv> (1.14)\n[SwitchOn] <tv> (1.14)"
    assert not repair(text, tiny_home).executable  # repair alone does not change meaning
    run = run_program(text, tiny_home)
    assert run.executable and run.strict.kind.value == "already"
    assert [str(i.step) for i in run.insertions] == ["[SwitchOff] <tv> (1.14)"]
    assert "it must be OFF" in run.insertions[0].reason
