import json

import pytest

from homesim.cli.main import main


def test_demo_runs_and_succeeds(capsys):
    assert main(["run"]) == 0
    out = capsys.readouterr().out
    assert "[SwitchOn] <tv> (1.410)" in out and "tv 410: OFF → ON" in out
    assert "executable" in out


def test_json_output(capsys):
    assert main(["run", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["executable"] is True and len(data["steps"]) == 5
    assert data["steps"][1]["changes"]["states"] == [
        {"node": 410, "before": ["OFF"], "after": ["ON"]}]
    assert data["stage"] is None and data["preparation"] is None  # came grounded


def test_failing_program_exits_1_with_reason(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text("[Walk] <tv> (1.410)\n[Grab] <tv> (1.410)\n")
    assert main(["run", str(p), "--home", "scene1"]) == 1
    out = capsys.readouterr().out
    assert "✗" in out and "tv 410 cannot be grabbed" in out


@pytest.mark.parametrize(
    ("content", "args", "pattern"),
    [
        ("[Wlak] <tv> (1)\n", [], "unknown action 'Wlak' (did you mean Walk?)"),
        ("[Walk] <tv>\n", [], "expected an id"),
        ("[Walk] <tv> (1.410)\n", ["--home", "nowhere"], "unknown home 'nowhere'"),
        ("[Walk] <tv> (1.410)\n", ["--graph", "missing.json"], "cannot read graph file"),
        ("Title\nDesc\n\n", [], "the program has no steps"),
        (b"\xff\xfe\xfa", [], "not UTF-8"),
        ("[Walk] <tv> (" + "9" * 4301 + ")", [], "over the limit of 9 (MAX_ID_DIGITS)"),
        ("[Walk] <tv> (1)\n" * 1001, [], "over the limit of 1000 steps (MAX_STEPS)"),
        ("[Walk] " + "<tv> (1) " * 120_000, [], "over the limit of 256 KiB for a program "
                                                "(MAX_PROGRAM_BYTES)"),
        ("[Walk] " + "<tv> (1) " * 25_000, [], "[Walk] takes 1 object, got 25000"),
    ],
)
def test_bad_input_gives_one_line_and_no_traceback(tmp_path, capsys, content, args, pattern):
    p = tmp_path / "p.txt"
    if isinstance(content, bytes):
        p.write_bytes(content)
    else:
        p.write_text(content)
    assert main(["run", str(p), *args]) == 2
    err = capsys.readouterr().err
    assert pattern in " ".join(err.split())
    assert "Traceback" not in err
    assert len(err) < 500  # user text is quoted as a short excerpt


def test_broken_graph_file(tmp_path, capsys):
    g = tmp_path / "g.json"
    g.write_text('{"nodes": [{"id": 1}], "edges": []}')
    assert main(["run", "--graph", str(g)]) == 2
    assert "'class_name' must be a non-empty string" in " ".join(capsys.readouterr().err.split())


def test_missing_program_file(capsys):
    assert main(["run", "no-such-file.txt"]) == 2
    assert "cannot read program" in capsys.readouterr().err


def test_homes_lists_built_ins(capsys):
    assert main(["homes"]) == 0
    assert "scene1_trimmed" in capsys.readouterr().out


DRINK = ("Have a drink\nFind a glass and drink.\n\n[Walk] <dining_room> (1)\n"
         "[Find] <wine_glass> (1)\n[Grab] <wine_glass> (1)\n[Drink] <wine_glass> (1)\n"
         "[Walk] <television> (1)\n[SwitchOn] <television> (1)\n")


def test_ungrounded_program_is_prepared_grounded_and_run(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text(DRINK)
    assert main(["run", str(p), "--home", "scene3"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "added wine_glass 1000 ON" in out
    assert "<television> (1) → tv 216 in livingroom 161" in out
    assert "agent stands at" in out
    assert "[SwitchOn] <television> (1.216)" in out and "executable" in out


def test_ungrounded_program_json_has_the_grounding(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text(DRINK)
    assert main(["run", str(p), "--home", "scene3_trimmed", "--json", "--seed", "2"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [a["class_name"] for a in data["preparation"]["added"]] == ["wine_glass"]
    grounding = data["grounding"]
    assert {"name": "television", "instance": 1, "node_id": 216} in grounding["bindings"]
    assert grounding["standing"] is None and data["executable"] is True
    assert "[SwitchOn] <television> (1.216)" in grounding["program"]


def test_grounded_program_of_the_wrong_class_is_refused(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text("[Walk] <tv> (1.410)\n[SwitchOn] <tv> (1.352)\n")
    assert main(["run", str(p), "--home", "scene1", "--json"]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["stage"] == "grounding" and data["failed_step"] == 2
    assert data["message"] == ("step 2 [SwitchOn] <tv> (1.352): <tv> (1) is node 352 here "
                               "but node 410 at an earlier step; one object is one node")
    p.write_text("[Walk] <tv> (1.410)\n[Walk] <tv> (2.352)\n")
    assert main(["run", str(p), "--home", "scene1"]) == 1
    out = " ".join(capsys.readouterr().out.split())
    assert "cannot ground in scene1: step 2 [Walk] <tv> (2.352): <tv> (2) is node 352, a sofa, " \
           "not a tv" in out


def test_program_that_cannot_be_grounded_exits_1_with_reason(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text("[Walk] <television> (1)\n[SwitchOn] <television> (1)\n"
                 "[SwitchOn] <television> (1)\n")
    assert main(["run", str(p), "--home", "scene1_trimmed", "--no-repair"]) == 1
    out = " ".join(capsys.readouterr().out.split())
    assert "cannot ground in scene1_trimmed: step 3 [SwitchOn] <television> (1)" in out
    assert "is not off" in out


def test_no_ground_reads_ids_as_nodes(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text("[Walk] <tv> (410)\n[SwitchOn] <tv> (410)\n")
    assert main(["run", str(p), "--home", "scene1", "--no-ground"]) == 0
    assert "tv 410: OFF → ON" in capsys.readouterr().out


def test_errors_keep_bracketed_text_and_stay_on_one_line(tmp_path, capsys):
    """Text from the user's file is printed as is (no rich markup), on one line."""
    p = tmp_path / "[bold]odd name with a long path to make the line wide.txt"
    assert main(["run", str(p)]) == 2
    err = capsys.readouterr().err
    assert f"{p}: cannot read program" in err
    assert err.count("\n") == 1


def test_version(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == "homesim 0.1.0"


def test_a_parse_error_with_json_is_json(tmp_path, capsys):
    p = tmp_path / "p.txt"
    p.write_text("[Wlak] <tv> (1)\n")
    assert main(["run", str(p), "--json"]) == 2
    data = json.loads(capsys.readouterr().out)
    assert "unknown action 'Wlak' (did you mean Walk?)" in data["error"]


@pytest.mark.parametrize("command", [[], ["run"], ["synth"], ["data"], ["data", "stats"],
                                     ["learn", "train"], ["learn", "eval"], ["render"]])
def test_help_has_no_hard_line_breaks_or_rst(command, capsys, monkeypatch):
    from homesim.cli.main import app, tidy_help

    monkeypatch.setenv("COLUMNS", "400")  # one line per paragraph
    assert main([*command, "--help"]) == 0
    out = capsys.readouterr().out
    assert "``" not in out
    group = app
    for name in command:  # the command's docstring: each paragraph is one printed line
        sub = {g.name: g.typer_instance for g in group.registered_groups}
        if name in sub:
            group = sub[name]
            continue
        cmd = next(c for c in group.registered_commands
                   if (c.name or c.callback.__name__) == name)
        for paragraph in tidy_help(cmd.help).split("\n\n"):
            assert paragraph.replace("\\[", "[") in out  # rich prints \[ as [


@pytest.mark.parametrize("args", [
    ["run", "{dev}", "--home", "scene1"],
    ["run", "{fifo}", "--home", "scene1"],
    ["run", "{program}", "--graph", "{dev}"],
    ["run", "{program}", "--graph", "{fifo}"],
    ["goals", "check", "{dev}", "--task", "27_2"],
    ["eval", "plans", "{fifo}"],
])
def test_devices_and_fifos_are_refused_at_once(tmp_path, capsys, args):
    """D2: /dev/zero was read until the OOM killer came; a FIFO without a writer hung."""
    import os
    import time

    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    program = tmp_path / "p.txt"
    program.write_text("[Walk] <tv> (1)\n")
    names = {"dev": "/dev/zero", "fifo": str(fifo), "program": str(program)}
    t0 = time.monotonic()
    assert main([a.format(**names) for a in args]) == 2
    assert time.monotonic() - t0 < 5
    err = capsys.readouterr().err
    assert "not a regular file" in err and "\n" not in err.strip()
