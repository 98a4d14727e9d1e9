import json

from homesim.cli.main import main

STEPS = "[Walk] <tv> (1.410)\n[SwitchOn] <tv> (1.410)\n"


def test_goals_check_a_formula_on_a_home(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text(STEPS)
    assert main(["goals", "check", str(p), "--home", "scene1", "--json",
                 "--formula", "OFF(tv.410) then ON(tv.410)"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["executable"] and out["given_formula_holds"] is True


def test_goals_check_bad_formula_is_one_line(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text(STEPS)
    assert main(["goals", "check", str(p), "--home", "scene1", "--formula", "ON(tv.410) or"]
                ) != 0
    err = capsys.readouterr().err
    assert "formula column 14: expected an atom" in err and "Traceback" not in err


def test_goals_check_task_and_eval_plans(real_data, tmp_path, capsys):
    program = real_data / "programs" / "file27_2.txt"
    assert main(["goals", "check", str(program), "--task", "27_2"]) == 0
    out = capsys.readouterr().out
    assert "met   CLOSED(washing_machine.1001)" in out and "formula holds" in out

    plans = tmp_path / "plans.json"
    plans.write_text(json.dumps([
        {"identifier": "27_2", "llm_output": '{"SWITCHON": ["washing_machine", "1001"]}'},
        {"identifier": "27_2", "llm_output": "no plan"}]))
    report = tmp_path / "report.json"
    assert main(["eval", "plans", str(plans), "--out", str(report)]) == 0
    data = json.loads(report.read_text())
    assert [p["error"] for p in data["plans"]] == ["missing_step", "format"]
    assert data["summary"]["trajectory_evaluation"]["grammar_error"]["parsing"] == 50.0


def test_goals_check_hostile_formulas_give_json_errors(tmp_path, capsys):
    """Issue 40 D8: deep nesting and huge ids were a RecursionError / ValueError (exit 70,
    no JSON); now one line, as JSON with --json."""
    p = tmp_path / "p.txt"
    p.write_text(STEPS)
    for formula, words in (("(" * 200 + "ON(tv.410)" + ")" * 200, "nested deeper"),
                           ("ON(tv." + "9" * 4400 + ")", "digits, over the limit"),
                           ("forn " + "9" * 4400 + ". x. (GRAB(x))", "digits, over the limit"),
                           (" and ".join(["ON(tv.410)"] * 100_000), "MAX_FORMULA_CHARS")):
        code = main(["goals", "check", str(p), "--home", "scene1", "--json",
                     "--formula", formula])
        assert code not in (0, 70)
        out = json.loads(capsys.readouterr().out)
        assert words in out["error"] and "\n" not in out["error"]


def test_eval_plans_refuses_a_deeply_nested_file_in_one_line(tmp_path, capsys):
    """Issue 40 D9: a RecursionError stopped the run."""
    for body in ("[" * 100_000 + "]" * 100_000, "[" * 20 + "]" * 20):
        plans = tmp_path / "plans.json"
        plans.write_text(body)
        code = main(["eval", "plans", str(plans)])
        err = capsys.readouterr().err
        assert code not in (0, 70) and "MAX_PLAN_DEPTH" in err and "Traceback" not in err


def test_eval_plans_writes_out_through_a_temporary_file(real_data, tmp_path, monkeypatch,
                                                        capsys):
    """Issue 40 D9: --out was written in place (a kill left half a report)."""
    import os

    plans = tmp_path / "plans.json"
    plans.write_text(json.dumps([{"identifier": "27_2", "llm_output": "no plan"}]))
    report = tmp_path / "report.json"
    moved = []
    real_replace = os.replace
    monkeypatch.setattr(os, "replace", lambda a, b: (moved.append((a, b)),
                                                     real_replace(a, b)))
    assert main(["eval", "plans", str(plans), "--out", str(report), "--strict-eai"]) == 0
    assert [b for _, b in moved] == [report] or [str(b) for _, b in moved] == [str(report)]
    assert json.loads(report.read_text())["plans"][0]["error"] == "format"
