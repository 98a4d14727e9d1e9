"""The same programs through every entry point give the same verdict and message.

Entry points: the library (`homesim.run_program`), ``homesim run --json``, the web API
(``/api/execute``), the learning reward (`homesim.learn.execution.executable`) and
constrained decoding's step-by-step runner (for ungrounded programs).
"""

from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

import homesim
from homesim.cli.main import app as cli_app
from homesim.examples import load_example
from homesim.serve import create_app

CASES = [
    # (home, program text, executable, stage, start of the message)
    ("scene1", str(load_example("watch_tv")), True, None, "executable: all 5 steps ran"),
    ("scene1_trimmed",  # wine_glass is not in the home: preparation adds it
     "[Walk] <dining_room> (1)\n[Find] <wine_glass> (1)\n[Grab] <wine_glass> (1)\n",
     True, None, "executable: all 3 steps ran"),
    ("scene1",  # scene1 has no television class: grounded to its tv
     "[Walk] <television> (1)\n[SwitchOn] <television> (1)\n",
     True, None, "executable: all 2 steps ran"),
    ("scene1",  # a grounded ref with the equivalent name of its node's class
     "[Walk] <television> (1.410)\n[SwitchOn] <television> (1.410)\n",
     True, None, "executable: all 2 steps ran"),
    ("scene1_trimmed",  # no tv can be grabbed: repair cannot help
     "[Walk] <tv> (1)\n[Grab] <tv> (1)\n",
     False, "grounding", "step 2 [Grab] <tv> (1): cannot be grounded: "),
    ("scene1_trimmed",  # switched on twice: repair switches it off in between
     "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[SwitchOn] <tv> (1)\n",
     True, None, "executable: all 4 steps ran, 1 of them inserted by repair"),
    ("scene1",  # grounded, fails at a precondition
     "[Walk] <tv> (1.410)\n[Grab] <tv> (1.410)\n",
     False, "execution", "step 2 [Grab] <tv> (1.410): tv 410 cannot be grabbed"),
    ("scene1",  # grounded to a node of another class: refused
     "[Walk] <tv> (1.352)\n",
     False, "grounding", "step 1 [Walk] <tv> (1.352): <tv> (1) is node 352, a sofa, not a tv"),
]
IDS = ["grounded", "prepared", "equivalent-name", "grounded-equivalent", "ungroundable",
       "repaired", "precondition", "wrong-class"]


@pytest.fixture(scope="module")
def client() -> TestClient:
    return TestClient(create_app(), base_url="http://127.0.0.1", raise_server_exceptions=False)


def _library(home: str, text: str) -> tuple[bool, str | None, str]:
    run = homesim.run_program(homesim.parse_program(text), homesim.load_home(home))
    return run.executable, run.stage, run.message


def _cli(home: str, text: str, tmp_path) -> tuple[bool, str | None, str]:
    path = tmp_path / "program.txt"
    path.write_text(text, encoding="utf-8")
    out = CliRunner().invoke(cli_app, ["run", str(path), "--home", home, "--json"])
    data = json.loads(out.stdout)
    assert out.exit_code == (0 if data["executable"] else 1)
    return data["executable"], data["stage"], data["message"]


def _api(client: TestClient, home: str, text: str) -> tuple[bool, str | None, str]:
    r = client.post("/api/execute", json={"program": text, "home": home})
    assert r.status_code == 200, r.text
    data = r.json()
    return data["executable"], data["stage"], data["message"]


@pytest.mark.parametrize(("home", "text", "executable", "stage", "message"), CASES, ids=IDS)
def test_every_entry_point_gives_the_same_verdict_and_message(
        client, tmp_path, home, text, executable, stage, message):
    from homesim.learn.data import Example
    from homesim.learn.execution import executable as reward_executable
    from homesim.learn.execution import runs_greedily

    library = _library(home, text)
    assert library[:2] == (executable, stage) and library[2].startswith(message)
    assert "\n" not in library[2]
    assert _cli(home, text, tmp_path) == library
    assert _api(client, home, text) == library
    program = homesim.parse_program(text)
    example = Example("case", program, home=home)
    # The learning reward and decoding judge the program as written (no repair).
    as_written = homesim.run_program(program, home, repair=False).executable
    assert as_written == (executable and "inserted by repair" not in message)
    assert reward_executable(program, example) == as_written
    if not program.is_grounded:  # decoding builds ungrounded programs step by step
        assert runs_greedily(program, example) == as_written


def test_the_issue_example_runs_everywhere(client):
    """Issue 11: this ran in the CLI and got 422 "the home has no wine_glass" from the API."""
    text = "[Walk] <dining_room> (1)\n[Find] <wine_glass> (1)\n[Grab] <wine_glass> (1)"
    assert _api(client, "scene1_trimmed", text) == _library("scene1_trimmed", text)
    assert _library("scene1_trimmed", text)[0] is True
