import pytest

from homesim.goals.check import GoalSet
from homesim.goals.contexts import TaskContext, task_objects
from homesim.goals.eai import TaskGoals
from homesim.goals.plans import PlanReport, parse_plan, score_plan, score_plans


@pytest.fixture
def context(tiny_home):
    goals = TaskGoals("file1_1", "Turn on TV", GoalSet(states=((14, "tv", "ON"),)), None, "")
    objects = frozenset({("fridge", 11), ("cup", 12), ("tv", 14), ("sofa", 15),
                         ("kitchen", 1)})
    return TaskContext(goals, tiny_home, objects)


def plan(*steps: str) -> str:
    return "{" + ", ".join(steps) + "}"


WALK_TV = '"WALK": ["tv", "14"]'
ON_TV = '"SWITCHON": ["tv", "14"]'


def test_a_plan_that_reaches_the_goal(context):
    s = score_plan("1_1", "```json\n" + plan(WALK_TV, ON_TV) + "\n```", context)
    assert (s.error, s.executable, s.success) == (None, True, True)
    assert s.steps == ["[WALK] <tv> (1.14)", "[SWITCHON] <tv> (1.14)"]


def test_keys_repeat_in_order():
    assert parse_plan(plan(WALK_TV, '"WALK": ["sofa", 15]', WALK_TV)) == [
        ("WALK", ["tv", "14"]), ("WALK", ["sofa", 15]), ("WALK", ["tv", "14"])]


@pytest.mark.parametrize(("text", "kind", "reason"), [
    ("I would walk to the TV", "format", "no JSON object"),
    ("{}", "format", "no steps"),
    ('{"WALK": ["tv"]}', "format", "name, id pairs"),
    (plan('"FLY": ["tv", "14"]'), "hallucination", "unknown action 'FLY'"),
    (plan('"WALK": ["unicorn", "9"]'), "hallucination", "unicorn 9 is not an object"),
    (plan('"WALK": ["tv", "15"]'), "hallucination", "tv 15 is not an object"),
    (plan('"WALK": ["tv", "14", "sofa", "15"]'), "arity", "takes 1 object"),
    (plan(ON_TV), "missing_step", "not close to tv"),
    (plan('"WALK": ["fridge", "11"]', '"GRAB": ["cup", "12"]'), "missing_step",
     "inside closed fridge"),
    (plan('"WALK": ["fridge", "11"]', '"GRAB": ["fridge", "11"]'), "affordance",
     "not GRABBABLE"),
    (plan(WALK_TV, '"WALK": ["fridge", "11"]', ON_TV), "wrong_order", "not close to tv"),
])
def test_error_kinds(context, text, kind, reason):
    s = score_plan("1_1", text, context)
    assert s.error == kind
    assert reason in s.reason
    assert not s.executable and not s.success


def test_additional_steps_are_skipped_and_the_plan_goes_on(context):
    s = score_plan("1_1", plan(WALK_TV, ON_TV, ON_TV), context)
    assert (s.error, s.additional, s.executable, s.success) == (
        "additional_step", [3], True, True)


def test_summary_uses_eai_metrics(context):
    scores = [score_plan("1_1", t, context) for t in (
        plan(WALK_TV, ON_TV), plan(ON_TV), "nonsense", plan(WALK_TV, ON_TV, ON_TV))]
    summary = PlanReport(scores).summary()
    assert summary["goal_evaluation"]["task_success_rate"] == 50.0
    traj = summary["trajectory_evaluation"]
    assert traj["execution_success_rate"] == 50.0
    assert traj["grammar_error"]["parsing"] == 25.0
    assert traj["runtime_error"] == {"wrong_order": 0.0, "missing_step": 25.0,
                                     "affordance_error": 0.0, "additional_step": 25.0}


def test_task_objects_are_what_changed():
    init = {"nodes": [{"id": 1, "class_name": "tv", "states": ["OFF"]},
                      {"id": 2, "class_name": "sofa"}, {"id": 3, "class_name": "character"},
                      {"id": 4, "class_name": "lamp"}],
            "edges": [{"from_id": 3, "relation_type": "CLOSE", "to_id": 4}]}
    final = {"nodes": [{"id": 1, "class_name": "tv", "states": ["ON"]},
                       {"id": 2, "class_name": "sofa"}, {"id": 3, "class_name": "character"},
                       {"id": 4, "class_name": "lamp"}],
             "edges": [{"from_id": 3, "relation_type": "CLOSE", "to_id": 2}]}
    assert task_objects(init, final) == {("tv", 1), ("sofa", 2), ("character", 3),
                                         ("lamp", 4)}


def test_grabbing_what_is_held_is_an_additional_step(context):
    walk, grab = '"WALK": ["fridge", "11"]', '"OPEN": ["fridge", "11"]'
    s = score_plan("1_1", plan(walk, grab, '"GRAB": ["cup", "12"]', '"GRAB": ["cup", "12"]',
                               WALK_TV, ON_TV), context)
    assert (s.error, s.additional, s.executable, s.success) == (
        "additional_step", [4], True, True)


def test_a_repeated_step_that_now_fails_is_additional(context, tiny_home):
    walk, open_ = '"WALK": ["fridge", "11"]', '"OPEN": ["fridge", "11"]'
    grab, drop = '"GRAB": ["cup", "12"]', '"DROP": ["cup", "12"]'
    s = score_plan("1_1", plan(walk, open_, grab, drop, drop, WALK_TV, ON_TV), context)
    assert (s.error, s.additional, s.executable, s.success) == (
        "additional_step", [5], True, True)


def test_contexts_are_cached_and_a_torn_cache_is_rebuilt(monkeypatch, tmp_path, context):
    from homesim.goals import contexts

    builds = []
    monkeypatch.setattr(contexts, "_build_contexts", lambda wanted: builds.append(wanted) or {
        k: context for k in ("1_1", "2_1") if wanted is None or f"file{k}" in wanted})
    path = tmp_path / "c.pickle"
    monkeypatch.setattr(contexts, "_cache_path", lambda: path)
    assert set(contexts.load_contexts(["2_1"])) == {"2_1"} and not path.exists()
    assert builds == [{"file2_1"}]  # a small subset without the cache: built alone
    assert set(contexts.load_contexts()) == {"1_1", "2_1"} and path.exists()
    assert set(contexts.load_contexts()) == {"1_1", "2_1"} and len(builds) == 2
    assert set(contexts.load_contexts(["1_1"])) == {"1_1"} and len(builds) == 2  # cached
    path.write_bytes(b"torn")
    assert set(contexts.load_contexts()) == {"1_1", "2_1"} and len(builds) == 3
    assert contexts.load_contexts(cache=False) and len(builds) == 4


def test_a_large_subset_builds_and_caches_them_all(monkeypatch, tmp_path, context):
    from homesim.goals import contexts

    builds = []
    monkeypatch.setattr(contexts, "_build_contexts",
                        lambda wanted: builds.append(wanted) or {"1_1": context, "2_1": context})
    monkeypatch.setattr(contexts, "SUBSET_BUILDS_ALL", 1)
    monkeypatch.setattr(contexts, "_cache_path", lambda: tmp_path / "c.pickle")
    assert set(contexts.load_contexts(["1_1", "2_1"])) == {"1_1", "2_1"}
    assert builds == [None] and (tmp_path / "c.pickle").exists()


@pytest.mark.parametrize("name", ["LOOKAT_SHORT", "LOOKAT_MEDIUM", "LOOKAT_LONG", "SQUEEZE"])
def test_every_action_of_eai_table_is_known(context, name):
    """EAI's valid_actions include the timed LookAt variants: aliases, not hallucinations."""
    s = score_plan("1_1", plan(WALK_TV, '"TURNTO": ["tv", "14"]', f'"{name}": ["tv", "14"]'),
                   context)
    assert s.error != "hallucination" and s.steps[0] == "[WALK] <tv> (1.14)"


@pytest.mark.parametrize(("kind", "expected"), [
    ("ALREADY", "additional_step"), ("AFFORDANCE", "affordance"),
    ("UNREACHABLE", "missing_step"), ("STATE", "missing_step")])
def test_error_kinds_come_from_the_failure_kind_not_its_words(context, monkeypatch, kind,
                                                              expected):
    """The EAI kind is read from the simulator's `FailureKind`: the same words with
    another kind give another EAI kind (no pattern over sentences)."""
    from homesim.sim import effects
    from homesim.sim.failure import Failure, FailureKind

    monkeypatch.setitem(effects.EFFECTS, "SWITCHON",
                        lambda st, n: Failure(FailureKind[kind], "the same words"))
    s = score_plan("1_1", plan(WALK_TV, ON_TV), context)
    assert s.error == expected
    assert s.additional == ([2] if expected == "additional_step" else [])


# ------------------------------------------------------------------ EAI's order and strict mode
@pytest.fixture
def wide(tiny_home):
    goals = TaskGoals("file1_1", "Put away", GoalSet(relations=((16, "ON", 13),)), None, "")
    objects = frozenset({("fridge", 11), ("cup", 12), ("tv", 14), ("sofa", 15),
                         ("kitchen", 1), ("table", 13), ("plate", 16)})
    return TaskContext(goals, tiny_home, objects)


GRAB_PLATE = ('"WALK": ["table", "13"]', '"GRAB": ["plate", "16"]')
PUT_PLATE = '"PUTBACK": ["plate", "16", "table", "13"]'


@pytest.mark.parametrize("strict", [False, True])
def test_hallucination_is_checked_on_the_whole_plan_before_arity(wide, strict):
    """U1: EAI checks every step's action and objects before any step's arity."""
    text = plan('"WALK": ["tv", "14", "tv", "14"]', '"GRAB": ["unicorn", "99999"]')
    s = score_plan("1_1", text, wide, strict_eai=strict)
    assert s.error == "hallucination" and "unicorn" in s.reason
    text = plan('"WALK": ["tv", "14", "tv", "14"]', '"FLY": ["tv", "14"]')
    assert score_plan("1_1", text, wide, strict_eai=strict).error == "hallucination"


def test_put_is_putback_by_default_and_a_hallucination_in_strict_mode(wide):
    """U5: homesim knows PUT as an alias of PUTBACK; EAI's table does not."""
    text = plan(*GRAB_PLATE, '"PUT": ["plate", "16", "table", "13"]')
    assert score_plan("1_1", text, wide).success
    s = score_plan("1_1", text, wide, strict_eai=True)
    assert s.error == "hallucination" and "not in EAI's action table" in s.reason
    text = plan('"PLUGIN": ["tv", "14"]')  # EAI's table lacks it (docs/goals.md fault 6)
    assert score_plan("1_1", text, wide, strict_eai=True).error == "hallucination"


def test_a_repeated_putback_is_additional_by_default_and_wrong_order_in_strict_mode(wide):
    """U7: the second PUTBACK fails (nothing held); EAI calls it wrong_order and stops."""
    text = plan(*GRAB_PLATE, PUT_PLATE, PUT_PLATE)
    s = score_plan("1_1", text, wide)
    assert (s.error, s.additional, s.success) == ("additional_step", [4], True)
    s = score_plan("1_1", text, wide, strict_eai=True)
    assert (s.error, s.failed_step, s.executable) == ("wrong_order", 4, False)


@pytest.mark.parametrize("text", [
    '{"WALK": ["table", "13"], "GRAB": ["plate", "16"],}',   # trailing comma
    '{"WALK": ["table", "13"], "GRAB": ["plate", "16"]',     # no closing brace
])
def test_eai_reader_is_lenient_only_in_strict_mode(wide, text):
    """U2: EAI reads each "KEY": [...] pair on its own."""
    assert score_plan("1_1", text, wide).error == "format"
    s = score_plan("1_1", text, wide, strict_eai=True)
    assert (s.error, s.executable) == (None, True)


def test_strict_mode_drops_zero_argument_steps_as_eai_does(wide):
    text = plan('"STANDUP": []', *GRAB_PLATE)
    assert score_plan("1_1", text, wide).error == "additional_step"  # standing already
    s = score_plan("1_1", text, wide, strict_eai=True)
    assert (s.error, s.steps[0]) == (None, "[WALK] <table> (1.13)")


# ------------------------------------------------------------------ hostile plans (issue 40 D9)
def test_deep_nesting_in_one_plan_is_a_format_error_and_the_others_are_scored(wide):
    deep = '{"WALK": ' + "[" * 5000 + "]" * 5000 + "}"
    medium = '{"WALK": ' + "[" * 20 + "]" * 20 + "}"
    report = score_plans([{"identifier": "1_1", "llm_output": t}
                          for t in (deep, medium, plan(*GRAB_PLATE))], {"1_1": wide})
    errors = [s.error for s in report.scores]
    assert errors == ["format", "format", None]
    assert all("MAX_PLAN_DEPTH" in s.reason for s in report.scores[:2])
    s = score_plan("1_1", deep, wide, strict_eai=True)  # EAI's reader: one bad list
    assert s.error == "format"


def test_a_plan_over_the_step_limit_is_a_format_error_and_the_others_are_scored(wide):
    long = plan(*(['"WALK": ["tv", "14"]'] * 1001))
    report = score_plans([{"identifier": "1_1", "llm_output": t}
                          for t in (long, plan(*GRAB_PLATE))], {"1_1": wide})
    assert [s.error for s in report.scores] == ["format", None]
    assert "MAX_PLAN_STEPS" in report.scores[0].reason


def test_the_additional_step_rate_is_a_share_of_plans(wide):
    repeated = plan(*GRAB_PLATE, *(['"GRAB": ["plate", "16"]'] * 997))
    report = score_plans([{"identifier": "1_1", "llm_output": repeated}], {"1_1": wide})
    assert len(report.scores[0].additional) == 997
    assert report.summary()["trajectory_evaluation"]["runtime_error"]["additional_step"] == 100
    strict = score_plans([{"identifier": "1_1", "llm_output": repeated}], {"1_1": wide},
                         strict_eai=True)  # EAI counts steps: 99 700 %
    assert strict.summary()["trajectory_evaluation"]["runtime_error"]["additional_step"] == 99700
