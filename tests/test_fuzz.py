"""Fuzz: what users can send in (program text, graphs, requests) only ever gives a
`HomesimError` (or a 4xx answer), never another exception, and never changes the input.

Bounded and derandomized so the suite stays fast and deterministic: every run tries the
same cases (`derandomize=True`); case counts per target are set by `_cases` (about 20 s
for the whole module).
"""

from __future__ import annotations

import contextlib
import copy
import gzip
import json
from typing import Any

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from homesim.errors import HomesimError
from homesim.ground import prepare_and_ground
from homesim.ground.pipeline import run_program
from homesim.program import Program, parse_program, parse_step
from homesim.program.actions import ACTIONS
from homesim.program.model import ObjectRef, Step
from homesim.serve import create_app
from homesim.sim.execute import execute
from homesim.world import load_home
from homesim.world.graph import EnvironmentGraph
from tests.conftest import tiny_home_dict


def _cases(n: int) -> Any:
    return settings(derandomize=True, max_examples=n, deadline=None, database=None,
                    suppress_health_check=list(HealthCheck))


# ------------------------------------------------------------------ strategies
_FRAGMENTS = ["[", "]", "<", ">", "(", ")", ".", " ", "\t", "\n", "\r\n", "#", "\u2028",
              "Walk", "WALK", "grab", "PutBack", "SwitchOn", "StandUp", "Wlak", "tv", "cup",
              "table", "television", "kitchen", "character", "coffee table", "1", "2",
              "410", "0", "00", "9" * 12, "9" * 5000, "é", "\ud800", "\x00", "٣", "x" * 200]
_ACTION_NAMES = sorted(a.name for a in ACTIONS.values())
_CLASSES = ["tv", "television", "cup", "table", "fridge", "sofa", "plate", "kitchen",
            "living_room", "character", "book", "apple", "bathroom", "no_such_thing"]

texts = st.lists(st.one_of(st.sampled_from(_FRAGMENTS), st.text(max_size=6)),
                 max_size=40).map("".join)


_ODD_IDS = ["0", "007", "1 . 2", "9" * 9, "9" * 10, "9" * 4301, "٣", "1.", ".1", "-1", "1e3"]


@st.composite
def step_lines(draw: Any, grounded: bool = False, ids: list[int] | None = None,
               exact: bool = False) -> str:
    """A step line of a catalog action. Unless `exact`, its arity, names and ids are
    sometimes wrong (odd digits, long names, stray text)."""
    action = draw(st.sampled_from(_ACTION_NAMES))
    arity = ACTIONS[action.upper()].arity
    if not exact:
        action = draw(st.sampled_from([action] * 6 + ["x" * 101, "Wlak", " walk ", ""]))
        arity = draw(st.sampled_from([arity] * 4 + [0, 1, 2, 3]))
    refs = []
    for _ in range(arity):
        name = draw(st.sampled_from(_CLASSES))
        ident = str(draw(st.integers(1, 3)))
        if grounded:
            ident += f".{draw(st.sampled_from(ids or [1]) | st.integers(0, 10**9 - 1))}"
        if not exact:
            name = draw(st.sampled_from([name] * 6 + ["a" * 101, " ", "Coffee  Table"]))
            ident = draw(st.sampled_from([ident] * 4) | st.sampled_from(_ODD_IDS))
        refs.append(f"<{name}> ({ident})")
    line = " ".join([f"[{action}]", *refs])
    return line if exact else line + draw(st.sampled_from([""] * 6 + [" ", " #", " x", "("]))


def _walk_first(line: str) -> str:
    """Walk to a step's first object before it, as programs do (so more steps run)."""
    start = line.find("<")
    return line if start < 0 else f"[Walk] {line[start:line.index(')', start) + 1]}\n{line}"


programs = st.lists(step_lines(exact=True).map(_walk_first), min_size=1, max_size=6
                    ).map("\n".join)
json_scalars = st.one_of(st.none(), st.booleans(), st.integers(-10**20, 10**20),
                         st.sampled_from([0, 1, -1, 2**63, 10**400]),
                         st.floats(allow_nan=True, allow_infinity=True),
                         st.sampled_from([1e308, -1e308, 5e-324]), st.text(max_size=8))
json_values = st.recursive(json_scalars, lambda inner: st.lists(inner, max_size=4)
                           | st.dictionaries(st.text(max_size=6), inner, max_size=4),
                           max_leaves=12)


@st.composite
def mutated_home(draw: Any) -> dict:
    """The tiny home with a few random changes: a value replaced, a key dropped, a node
    or edge added (fields of the right and of wrong types)."""
    d = tiny_home_dict()
    d["nodes"][3]["bounding_box"] = {"center": [0.0, 0.5, 0.0], "size": [1.0, 1.0, 1.0]}
    for _ in range(draw(st.integers(1, 3))):
        what = draw(st.sampled_from(["node", "edge", "drop", "add_node", "add_edge"]))
        if what in ("node", "drop"):
            target = draw(st.sampled_from(d["nodes"])) if d["nodes"] else d
        else:
            target = draw(st.sampled_from(d["edges"])) if d["edges"] else d
        keys = ["id", "class_name", "category", "properties", "states", "bounding_box",
                "from_id", "to_id", "relation_type", "prefab_name", "extra"]
        key = draw(st.sampled_from(keys))
        if what == "drop":
            target.pop(key, None)
        elif what == "add_node":
            d["nodes"].append({"id": draw(st.integers(0, 30)),
                               "class_name": draw(st.sampled_from(_CLASSES)),
                               "category": draw(st.sampled_from([None, "Rooms", "Characters",
                                                                 "Furniture"]))})
        elif what == "add_edge":
            d["edges"].append({"from_id": draw(st.integers(0, 30)),
                               "relation_type": draw(st.sampled_from(
                                   ["INSIDE", "ON", "CLOSE", "FACING", "HOLDS_RH", "BETWEEN",
                                    "inside", "X"])),
                               "to_id": draw(st.integers(0, 30))})
        else:
            target[key] = draw(json_values)
    return d


def _snapshot(graph: EnvironmentGraph) -> str:
    return json.dumps(graph.to_dict(), sort_keys=True)


# ------------------------------------------------------------------ parser
@_cases(400)
@given(texts)
def test_parser_gives_only_program_errors(text):
    try:
        program = parse_program(text)
    except HomesimError:
        return
    for step in program.steps:  # what parses prints back to the same step
        assert parse_step(str(step)) == step


@_cases(300)
@given(st.lists(step_lines(grounded=True) | texts, min_size=1, max_size=6).map("\n".join))
@example("[Walk] <tv> (" + "9" * 4301 + ")")  # issue 12: ValueError from int()
@example("[Walk] " + "<tv> (1) " * 5000)
def test_parser_on_step_like_lines(text):
    with contextlib.suppress(HomesimError):
        parse_program(text)


# ------------------------------------------------------------------ graphs
@_cases(300)
@given(mutated_home())
def test_graph_from_dict_gives_only_graph_errors_and_keeps_its_input(data):
    before = copy.deepcopy(data)
    try:
        graph = EnvironmentGraph.from_dict(data)
    except HomesimError:
        graph = None
    assert data == before or json.dumps(data) == json.dumps(before)  # nan != nan
    if graph is not None:
        again = EnvironmentGraph.from_dict(graph.to_dict())
        assert _snapshot(again) == _snapshot(graph)


@_cases(60)
@given(st.one_of(st.binary(max_size=64), mutated_home().map(lambda d: json.dumps(d).encode()),
                 st.integers(1, 5000).map(lambda n: b"[" * n + b"]" * n),
                 st.sampled_from([b'{"nodes": [{"id": ' + b"9" * 5000 + b"}]}",
                                  b'{"nodes": [], "edges": [], "x": 1e999}', b"\xef\xbb\xbf{}"])),
       st.booleans())
def test_graph_load_gives_only_graph_errors(tmp_path_factory, raw, gz):
    path = tmp_path_factory.mktemp("g") / ("g.json.gz" if gz else "g.json")
    path.write_bytes(gzip.compress(raw) if gz else raw)
    with contextlib.suppress(HomesimError):
        EnvironmentGraph.load(path)


# ------------------------------------------------------------------ execute, prepare, ground
_TINY = EnvironmentGraph.from_dict(tiny_home_dict())
_TINY_IDS = sorted(_TINY.nodes)


@_cases(300)
@given(st.lists(step_lines(grounded=True, ids=_TINY_IDS, exact=True), min_size=1, max_size=8)
       .map("\n".join))
def test_execute_gives_only_homesim_errors_and_keeps_the_graph(text):
    before = _snapshot(_TINY)
    program = parse_program(text)
    with contextlib.suppress(HomesimError):
        execute(program, _TINY, trace=True)
    assert _snapshot(_TINY) == before


@_cases(150)
@given(programs, st.integers(0, 2**64))
def test_prepare_and_ground_give_only_homesim_errors_and_keep_the_graph(text, seed):
    before = _snapshot(_TINY)
    program = parse_program(text)
    with contextlib.suppress(HomesimError):
        prepare_and_ground(program, _TINY, seed=seed)
    run = run_program(program, _TINY, seed=seed)
    assert run.executable in (True, False) and "\n" not in run.message
    assert _snapshot(_TINY) == before


@_cases(150)
@given(mutated_home(), st.sampled_from(["[Walk] <tv> (1)\n[SwitchOn] <tv> (1)",
                                        "[Walk] <character> (1)\n[Grab] <book> (1)",
                                        "[Grab] <cup> (1)\n[PutBack] <cup> (1) <table> (1)",
                                        "[Walk] <kitchen> (1)\n[Open] <fridge> (1)"]))
def test_runs_on_odd_graphs_give_only_homesim_errors(data, text):
    try:
        graph = EnvironmentGraph.from_dict(data)
    except HomesimError:
        return
    before = _snapshot(graph)
    program = parse_program(text)
    for run in (lambda: run_program(program, graph),
                lambda: execute(Program(tuple(Step(s.action, tuple(
                    ObjectRef(r.name, r.instance, r.instance) for r in s.args))
                    for s in program.steps)), graph)):
        with contextlib.suppress(HomesimError):
            run()
    assert _snapshot(graph) == before


# ------------------------------------------------------------------ API
@pytest.fixture(scope="module")
def client() -> TestClient:
    return TestClient(create_app(), base_url="http://127.0.0.1", raise_server_exceptions=False)


_HOMES = ["scene1_trimmed", "scene2_trimmed", "nowhere", ""]


@_cases(120)
@given(st.sampled_from(["/api/validate", "/api/execute"]),
       st.one_of(programs, texts,
                 st.lists(step_lines() | step_lines(grounded=True, ids=[1, 410, 10**9 - 1]),
                          min_size=1, max_size=4).map("\n".join)),
       st.sampled_from(_HOMES), st.sampled_from([None, True, False]),
       st.one_of(st.integers(0, 9), st.integers(-2**70, 2**70)))
@example("/api/validate", "[Walk] <tv> (" + "9" * 4301 + ")", "scene1_trimmed", None, 0)
@example("/api/execute", "[Walk] <tv> (" + "9" * 4301 + ")", "scene1_trimmed", None, 0)
@example("/api/execute", "[Walk] <tv> (1)\n" * 1000, "scene1_trimmed", True, 0)
@example("/api/execute", "[Walk] <tv> (1)\n" * 1001, "scene1_trimmed", None, 0)
@example("/api/execute", "[Walk] <tv\ud800> (1)", "scene1_trimmed", None, 0)
def test_api_answers_4xx_never_500(client, route, text, home, ground, seed):
    body = {"program": text, "home": home, "seed": seed}
    if ground is not None:
        body["ground"] = ground
    r = client.post(route, content=json.dumps(body),
                    headers={"content-type": "application/json"})
    assert r.status_code < 500, r.text
    assert r.status_code == 200 or r.json()["error"]["kind"] != "host"  # routes were reached


@_cases(60)
@given(st.sampled_from(["/api/validate", "/api/execute"]), json_values)
def test_api_odd_bodies_answer_4xx(client, route, value):
    r = client.post(route, content=json.dumps(value),
                    headers={"content-type": "application/json"})
    assert 400 <= r.status_code < 500 or r.status_code == 200, r.text
    assert r.status_code == 200 or r.json()["error"]["kind"] != "host"


def test_api_keeps_its_homes():
    client = TestClient(create_app(), base_url="http://127.0.0.1", raise_server_exceptions=False)
    home = load_home("scene1_trimmed")
    before = _snapshot(home)
    for text in ("[Walk] <cup> (1)\n[Grab] <cup> (1)", "[Walk] <novel> (1)\n[Grab] <novel> (1)"):
        r = client.post("/api/execute", json={"program": text, "home": "scene1_trimmed"})
        assert r.status_code == 200
    assert _snapshot(load_home("scene1_trimmed")) == before
