from homesim.program import parse_program
from homesim.serve.results import program_json, step_lines
from homesim.sim import execute


def test_step_lines_skip_title_description_comments_and_blanks():
    text = "Title\nA description\nwrapped\n\n# comment\n[Walk] <tv> (1)\n\n  [Sit] <sofa> (2)\n"
    assert step_lines(text) == [6, 8]


def test_program_json_keeps_grounding(tiny_home):
    p = parse_program("[Walk] <tv> (1.14)\n[Sit] <sofa> (1)")
    data = program_json(p, [1, 2])
    assert data["grounded"] is False
    assert data["steps"][0]["args"] == [{"name": "tv", "instance": 1, "node_id": 14}]


def test_execution_to_dict_on_tiny_home(tiny_home):
    p = parse_program("[Walk] <tv> (1.14)\n[SwitchOn] <tv> (1.14)\n[Grab] <sofa> (1.15)\n"
                      "[Sit] <sofa> (1.15)")
    result = execute(p, tiny_home, trace=True)
    data = result.to_dict([1, 2, 3, 4])
    assert [s["ok"] for s in data["steps"]] == [True, True, False]
    assert data["steps"][1]["summary"] == "tv 14: OFF → ON"
    assert data["steps"][2]["summary"] == data["reason"] and "sofa 15" in data["reason"]
    assert data["failed_line"] == 3 and data["not_run"][0]["line"] == 4


def test_describe_changes_counts_close_edges(tiny_home):
    result = execute(parse_program("[Walk] <fridge> (1.11)"), tiny_home, trace=True)
    text = result.trace[0].changes.describe(result.state.label)
    assert "CLOSE" in text and "fridge 11 CLOSE" not in text
