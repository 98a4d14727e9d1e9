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
