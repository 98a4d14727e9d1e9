import json

import pytest

from homesim.errors import ExecutionError
from homesim.ground import Run, run_program
from homesim.program import parse_program
from homesim.world import load_home
from homesim.world.graph import EnvironmentGraph
from tests.conftest import tiny_home_dict

WINE = "[Walk] <dining_room> (1)\n[Find] <wine_glass> (1)\n[Grab] <wine_glass> (1)"


@pytest.fixture(scope="module")
def trimmed():
    return load_home("scene1_trimmed")


def test_an_ungrounded_program_is_prepared_grounded_and_executed(trimmed):
    run = run_program(parse_program(WINE), trimmed, trace=True)
    assert isinstance(run, Run) and run.executable and run.stage is None
    added = run.prepared.added[0]
    assert added.class_name == "wine_glass" and added.node_id in run.graph
    assert added.node_id not in trimmed  # the input home is left as it was
    assert run.bindings[("wine_glass", 1)] == added.node_id
    assert run.result.program == run.grounding.program and len(run.result.trace) == 3


def test_without_preparation_a_missing_object_is_a_grounding_failure(trimmed):
    run = run_program(parse_program(WINE), trimmed, prepare=False)
    assert (run.executable, run.stage, run.failed_step) == (False, "grounding", 2)
    assert run.result is None and run.grounding is None and run.graph is trimmed
    assert run.message.startswith("step 2 [Find] <wine_glass> (1): the home has no wine_glass")
    data = run.to_dict([3, 4, 5])
    assert data["steps"] == [] and data["failed_line"] == 4 and len(data["not_run"]) == 3
    assert data["reason"] == data["message"] == run.message


def test_a_grounded_program_is_checked_and_run_as_it_is():
    home = load_home("scene1")
    run = run_program("[Walk] <tv> (1.410)\n[SwitchOn] <tv> (1.410)", home)
    assert run.executable and run.prepared is None and run.graph is home
    assert dict(run.bindings) == {("tv", 1): 410} and run.grounding.standing is None
    refused = run_program("[Walk] <tv> (1.352)", home)
    assert (refused.executable, refused.stage, refused.failed_step) == (False, "grounding", 1)
    assert "<tv> (1) is node 352, a sofa, not a tv" in refused.message


def test_reference_mode_reads_ids_as_nodes(trimmed):
    text = "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)"
    assert run_program(text, trimmed).executable  # grounded to a tv
    ref = run_program(text, trimmed, reference=True)  # node 1 is the bathroom
    assert (ref.executable, ref.stage, ref.failed_step) == (False, "execution", 2)
    assert ref.grounding is None and ref.message.startswith("step 2 [SwitchOn] <tv> (1): ")


def test_same_seed_same_run_and_json(trimmed):
    text = "[Walk] <kitchen> (1)\n[Walk] <cup> (1)\n[Grab] <cup> (1)\n[Walk] <cup> (2)"
    a = run_program(text, "scene1_trimmed", seed=3, trace=True).to_dict()
    b = run_program(text, trimmed, seed=3, trace=True).to_dict()
    assert json.dumps(a) == json.dumps(b)
    assert set(a) >= {"executable", "stage", "message", "failed_step", "steps", "not_run",
                      "preparation", "grounding"}


def test_a_home_without_character_raises():
    d = tiny_home_dict()
    d["nodes"] = [n for n in d["nodes"] if n["class_name"] != "character"]
    d["edges"] = [e for e in d["edges"] if 10 not in (e["from_id"], e["to_id"])]
    with pytest.raises(ExecutionError, match="no character"):
        run_program("[Walk] <tv> (1.14)", EnvironmentGraph.from_dict(d))


def test_a_program_without_objects_is_prepared(trimmed):
    run = run_program("[StandUp]", trimmed)  # presupposes a seated character
    assert run.executable and run.prepared is not None
    assert not run_program("[StandUp]", trimmed, reference=True).executable


def test_runs_agrees_with_run_program(trimmed):
    from homesim.ground.pipeline import runs

    text = ("[Walk] <television> (1)\n[SwitchOn] <television> (1)\n[Grab] <television> (1)\n"
            "[Walk] <wine_glass> (1)\n[Grab] <wine_glass> (1)\n[SwitchOn] <television> (1)")
    program = parse_program(text)
    verdicts = []
    for k in range(1, len(program) + 1):
        prefix = program.with_steps(program.steps[:k])
        verdicts.append(runs(prefix, trimmed))
        assert verdicts[-1] == run_program(prefix, trimmed).executable
    assert verdicts == [True, True, False, False, False, False]
