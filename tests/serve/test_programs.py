import pytest

from homesim.serve import programs


def test_validate_returns_steps_with_their_lines(client, watch_tv):
    r = client.post("/api/validate", json={"program": watch_tv, "home": "scene1"})
    assert r.status_code == 200
    data = r.json()
    assert data["ok"] is True and data["problems"] == [] and data["title"] == "Watch TV"
    assert [s["line"] for s in data["steps"]] == [4, 5, 6, 7, 8]
    assert data["steps"][1]["action"] == "SWITCHON"
    assert data["steps"][1]["args"] == [{"name": "tv", "instance": 1, "node_id": 410}]
    assert data["program"] == watch_tv


def test_validate_reports_node_ids_missing_or_of_another_class(client):
    text = ("[Walk] <tv> (1.410)\n[Walk] <sofa> (1.9999)\n[Sit] <television> (1.410)\n"
            "[Walk] <tv> (2.352)\n[Walk] <cup> (1)\n")
    data = client.post("/api/validate", json={"program": text, "home": "scene1"}).json()
    assert data["ok"] is False
    # television and tv are equivalent names (as in grounding); <cup> (1) gets grounded
    assert [(p["line"], p["message"]) for p in data["problems"]] == [
        (2, "line 2: the home has no node 9999 for <sofa> (1)"),
        (4, "line 4: <tv> (2) is node 352, a sofa, not a tv or television")]


@pytest.mark.parametrize(
    ("text", "line", "fragment"),
    [
        ("[Walk] <tv> (1.410)\n[Wlak] <tv> (1.410)\n", 2, "unknown action 'Wlak' (did you mean Walk?)"),
        ("Title\nDesc\n\n[Walk] <tv> (1.410)\n[Grab] <tv>\n", 5, "expected an id"),
        ("[PutBack] <cup> (1.1)\n", 1, "[PutBack] takes 2 objects, got 1"),
    ],
)
@pytest.mark.parametrize("route", ["/api/validate", "/api/execute"])
def test_malformed_program_is_422_with_line(client, route, text, line, fragment):
    r = client.post(route, json={"program": text, "home": "scene1"})
    assert r.status_code == 422
    error = r.json()["error"]
    assert error["kind"] == "program" and error["line"] == line
    assert fragment in error["message"] and error["message"].startswith(f"line {line}:")


def test_empty_program_is_422(client):
    r = client.post("/api/execute", json={"program": "Title\nDesc\n\n", "home": "scene1"})
    assert r.status_code == 422 and r.json()["error"]["message"] == "the program has no steps"


def test_too_many_steps_is_422(client):
    text = "[Walk] <tv> (1.410)\n" * 1001
    r = client.post("/api/execute", json={"program": text, "home": "scene1"})
    assert r.status_code == 422
    error = r.json()["error"]
    assert "more than 1000 steps, over the limit of 1000 steps" in error["message"]
    assert error["kind"] == "limit" and error["limit"] == "MAX_STEPS"


def test_execute_watch_tv_every_step_passes(client, watch_tv):
    r = client.post("/api/execute", json={"program": watch_tv, "home": "scene1"})
    assert r.status_code == 200
    data = r.json()
    assert data["executable"] is True and data["failed_step"] is None
    assert [s["ok"] for s in data["steps"]] == [True] * 5 and data["not_run"] == []
    switch = data["steps"][1]
    assert switch["changes"]["states"] == [{"node": 410, "before": ["OFF"], "after": ["ON"]}]
    assert switch["summary"] == "tv 410: OFF → ON" and switch["line"] == 5
    sit = data["steps"][3]
    assert [65, "ON", 352] in sit["changes"]["added"]


def test_execute_failing_step_has_reason_and_line(client, watch_tv):
    text = watch_tv + "\n[Grab] <tv> (1.410)\n[Walk] <sofa> (1.352)\n"
    data = client.post("/api/execute", json={"program": text, "home": "scene1"}).json()
    assert data["executable"] is False and data["failed_step"] == 6 and data["failed_line"] == 9
    last = data["steps"][-1]
    assert last["ok"] is False and last["reason"] == "tv 410 cannot be grabbed (not GRABBABLE)"
    assert last["changes"] == {"added": [], "removed": [], "states": [], "nodes": []}
    assert data["not_run"] == [{"index": 6, "line": 10, "step": "[Walk] <sofa> (1.352)"}]
    assert data["message"].startswith("step 6 [Grab] <tv> (1.410): tv 410 cannot be grabbed")


def test_execute_on_unknown_home_is_404(client, watch_tv):
    r = client.post("/api/execute", json={"program": watch_tv, "home": "nowhere"})
    assert r.status_code == 404 and "unknown home 'nowhere'" in r.json()["error"]["message"]


def test_ground_false_reads_instance_as_node_id_like_the_reference(client):
    text = "[Walk] <tv> (410)\n[SwitchOn] <tv> (410)\n"
    data = client.post("/api/execute",
                       json={"program": text, "home": "scene1", "ground": False}).json()
    assert data["executable"] is True and data["grounding"] is None


def test_ungrounded_program_is_prepared_and_grounded_like_the_cli(client):
    text = "[Walk] <dining_room> (1)\n[Find] <wine_glass> (1)\n[Grab] <wine_glass> (1)\n"
    data = client.post("/api/execute",
                       json={"program": text, "home": "scene1_trimmed", "seed": 0}).json()
    assert data["executable"] is True and data["stage"] is None
    assert [a["class_name"] for a in data["preparation"]["added"]] == ["wine_glass"]
    node = data["preparation"]["added"][0]["node_id"]
    assert {"name": "wine_glass", "instance": 1, "node_id": node} in data["grounding"]["bindings"]
    assert data["program"].endswith(f"[Grab] <wine_glass> (1.{node})")


def test_ground_true_grounds_a_grounded_program_anew(client):
    text = "[Walk] <tv> (1.352)\n"  # 352 is the sofa: refused as it is, fine when grounded
    data = client.post("/api/execute", json={"program": text, "home": "scene1"}).json()
    assert data["executable"] is False and data["stage"] == "grounding"
    assert data["failed_line"] == 1 and data["steps"] == [] and len(data["not_run"]) == 1
    data = client.post("/api/execute",
                       json={"program": text, "home": "scene1", "ground": True}).json()
    assert data["executable"] is True and data["grounding"]["bindings"][0]["node_id"] != 352


def test_program_that_cannot_be_grounded_is_an_answer_with_its_line(client):
    text = "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[SwitchOn] <tv> (1)\n"
    r = client.post("/api/execute", json={"program": text, "home": "scene1_trimmed",
                                          "repair": False})
    assert r.status_code == 200
    data = r.json()
    assert data["executable"] is False and data["stage"] == "grounding"
    assert data["failed_step"] == 3 and data["failed_line"] == 3
    assert data["message"].startswith("step 3 [SwitchOn] <tv> (1): cannot be grounded")
    assert data["kind"] == "already" and data["repair"] is None


def test_a_program_is_repaired_by_default_and_inserted_steps_have_no_line(client):
    text = "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n\n[SwitchOn] <tv> (1)\n"
    data = client.post("/api/execute", json={"program": text, "home": "scene1_trimmed"}
                       ).json()
    assert data["executable"] is True and data["kind"] is None
    assert [s["line"] for s in data["steps"]] == [1, 2, None, 4]
    assert data["repair"]["insertions"][0]["step"] == "[SwitchOff] <tv> (1)"
    assert data["repair"]["executable_before"] is False


def test_repair_runs_in_a_program_worker_and_a_program_that_runs_never_goes_there(
        client, watch_tv, monkeypatch):
    """Repair may ground a program dozens of times (over a second): not in the server's
    small-request lane, where other small requests wait behind it."""
    from homesim.serve.pool import ProgramPool

    sent = []
    real = ProgramPool.answer

    async def recording(self, handler, request, gone=None):
        sent.append(request)
        return await real(self, handler, request, gone)

    monkeypatch.setattr(ProgramPool, "answer", recording)
    text = "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n\n[SwitchOn] <tv> (1)\n"
    data = client.post("/api/execute", json={"program": text, "home": "scene1_trimmed"}
                       ).json()
    assert data["executable"] is True and data["repair"]["insertions"]
    assert len(sent) == 1 and sent[0].repair is True
    ran = client.post("/api/execute", json={"program": watch_tv, "home": "scene1"}).json()
    assert ran["executable"] is True and ran["repair"] is None
    assert len(sent) == 1  # a program that runs as written is answered in the server


def test_render_without_renderer_is_501(client, watch_tv, monkeypatch):
    def missing():
        raise programs.ApiError(501, "render", "rendering is not available on this server: x")

    monkeypatch.setattr(programs, "keyframe_renderer", missing)
    r = client.post("/api/render", json={"program": watch_tv, "home": "scene1"})
    assert r.status_code == 501
    assert r.json()["error"]["message"].startswith("rendering is not available on this server")


@pytest.mark.dataset
def test_every_real_program_file_validates_with_its_lines(client, real_data):
    from homesim.knowledge import real_programs

    files = sorted((real_data / "programs").glob("*.txt"))
    assert len(files) == len(list(real_programs(real_data))) == 518
    for path in files:
        text = path.read_text(encoding="utf-8")
        r = client.post("/api/validate", json={"program": text})
        assert r.status_code == 200, (path.name, r.json())
        data = r.json()
        lines = text.splitlines()
        assert all(lines[s["line"] - 1].strip().startswith("[") for s in data["steps"]), path.name


@pytest.mark.parametrize("route", ["/api/validate", "/api/execute"])
def test_huge_id_is_422_naming_the_limit(client, route):
    text = "[Walk] <tv> (" + "9" * 4301 + ")"  # was a 500 (ValueError from int())
    r = client.post(route, json={"program": text, "home": "scene1"})
    assert r.status_code == 422
    error = r.json()["error"]
    assert "MAX_ID_DIGITS" in error["message"] and error["line"] == 1
    assert len(error["text"]) <= 81
