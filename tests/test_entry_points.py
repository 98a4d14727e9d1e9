"""The same programs through every entry point give the same verdict and message.

Entry points (10): the library (`homesim.run_program`), ``homesim run --json``, the web
API (``/api/execute``), the learning reward (`homesim.learn.execution.executable`),
constrained decoding's step-by-step runner (for ungrounded programs), ``homesim
render``, the render library (`homesim.render`), a data set episode
(`homesim.dataset.episode.write_episode`), the Gymnasium environment
(`homesim.agents.HomeEnv`, one grounded step per action) and plan scoring
(`homesim.goals.plans.score_plan`, the program as an EAI plan). Render, episode,
environment and plans also act on the same nodes (bindings) as the library.
"""

from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient
from typer.testing import CliRunner

import homesim
from homesim.cli.main import app as cli_app
from homesim.errors import HomesimError
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


# --------------------------------------------------------------------- render, data set
@pytest.fixture(scope="module")
def gl():
    """Skip without the render extra or an OpenGL context."""
    gl = pytest.importorskip("homesim.render.gl", reason="needs the render extra",
                             exc_type=ImportError)
    if not gl.gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={gl.BACKEND}")
    return gl.BACKEND


RENDER = {"width": 16, "height": 16, "fps": 1, "seed": 0}
"""The smallest recordings that still animate every step (render cost, not quality)."""
DRAWN = [(c, i) for c, i in zip(CASES, IDS, strict=True) if c[0] == "scene1" and i != "grounded"]
"""The cases drawn: in a home with geometry; the 5-step demo left to tests/render (time)."""


def _cli_render(home: str, text: str, tmp_path, capsys) -> tuple[int, str, dict | None]:
    """(exit code, one-line error, meta.json or None) of ``homesim render``."""
    from homesim.cli.main import main

    path = tmp_path / "program.txt"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / "cli"
    options = [f"--{k}={v}" for k, v in RENDER.items()]
    code = main(["render", str(path), "--home", home, "--out", str(out), *options])
    err = " ".join(capsys.readouterr().err.split())
    meta = json.loads((out / "meta.json").read_text()) if code == 0 else None
    return code, err, meta


@pytest.mark.parametrize(("home", "text", "executable", "stage", "message"),
                         [c for c, i in DRAWN] + [CASES[1]], ids=[i for c, i in DRAWN] + [IDS[1]])
def test_render_animates_what_the_library_ran(tmp_path, capsys, home, text, executable,
                                              stage, message, gl):
    """``homesim render`` and `render_program` draw the library's run: the same grounded
    program (bindings), or the same one-line refusal."""
    from homesim.render import render_program

    run = homesim.run_program(homesim.parse_program(text), homesim.load_home(home), trace=True)
    code, err, meta = _cli_render(home, text, tmp_path, capsys)
    if home == "scene1_trimmed" and executable:  # no geometry to draw in
        assert code == 2 and "no floor boxes" in err
        return
    if not executable:
        assert code == 2 and run.message in err
        with pytest.raises(HomesimError, match="does not run") as e:
            render_program(run, tmp_path / "api", **RENDER)
        assert run.message in str(e.value)
        return
    assert code == 0, err
    result = render_program(run, tmp_path / "api", home=home, **RENDER)
    assert meta is not None and meta["program"] == str(run.result.program)
    assert [s["step"] for s in meta["steps"]] == [str(s) for s in run.result.program.steps]
    assert json.loads((result.out_dir / "meta.json").read_text()) == meta
    assert (result.out_dir / "video.mp4").read_bytes() == (tmp_path / "cli/video.mp4").read_bytes()


@pytest.mark.parametrize(("home", "text", "executable", "stage", "message"),
                         [c for c, i in DRAWN], ids=[i for c, i in DRAWN])
def test_a_dataset_episode_records_what_the_library_runs(home, text, executable, stage,
                                                         message, gl):
    """An episode is the library's run in the episode's home (its start drawn by the
    placement seed): the same verdict, reason and grounded program."""
    import io

    from homesim.dataset.episode import build_home, write_episode
    from homesim.dataset.spec import DatasetConfig, EpisodeSpec

    config = DatasetConfig(n=1, width=16, height=16, fps=1, modalities=("rgb", "class"),
                           homes=(home,))
    spec = EpisodeSpec(0, "case", text, home, "male1", 0, 0, 0, 0, 1.0)
    graph, _, _ = build_home(spec, home)
    # An episode runs its program as written (`ground_episode`: no repair).
    run = homesim.run_program(homesim.parse_program(text), graph, seed=spec.ground_seed,
                              repair=False)
    if not executable:
        from homesim.dataset.episode import EpisodeFailed

        with pytest.raises(EpisodeFailed) as e:
            write_episode(spec, config, io.BytesIO())
        assert (e.value.stage, e.value.reason) == (run.stage, run.message)
        return
    import tarfile

    buf = io.BytesIO()
    outcome = write_episode(spec, config, buf)
    assert outcome.ok and outcome.num_steps == len(run.program.steps)
    buf.seek(0)
    with tarfile.open(fileobj=buf) as tar:
        member = tar.extractfile("ep-000000.json")
        assert member is not None
        meta = json.loads(member.read())
    assert run.grounding is not None
    assert meta["grounded_program"] == "\n".join(str(s) for s in run.grounding.program.steps)


# ------------------------------------------------------------------ agents, goals
def _grounded_steps(run, text: str) -> list[str] | None:
    """The program as it names nodes: grounded by the run, or as given when it carries
    ids; None when it names no nodes (nothing for an agent or a plan to act on)."""
    if run.grounding is not None:
        return [str(s) for s in run.grounding.program.steps]
    program = homesim.parse_program(text)
    return [str(s) for s in program.steps] if program.is_grounded else None


@pytest.mark.parametrize(("home", "text", "executable", "stage", "message"), CASES, ids=IDS)
def test_the_gym_environment_takes_the_grounded_steps_as_the_library(
        home, text, executable, stage, message):
    """One grounded step per action: the same steps run, on the same nodes, and the same
    step fails for the same reason."""
    from homesim.agents import HomeEnv

    run = homesim.run_program(homesim.parse_program(text), homesim.load_home(home), trace=True)
    steps = _grounded_steps(run, text)
    if steps is None:
        pytest.skip("an ungrounded program names no nodes to act on")
    env = HomeEnv(run.graph)
    env.reset(seed=0)
    failed, reason = None, None
    for i, step in enumerate(steps):
        _, _, _, _, info = env.step(step)
        if not info["ok"]:
            failed, reason = i + 1, info["reason"]
            break
    assert (failed is None) == run.executable
    assert failed == run.failed_step
    if run.stage == "execution":  # the library says where; the environment only why
        assert reason is not None and run.message.endswith(f": {reason}")
    ran = [r.nodes for r in run.result.trace if r.ok] if run.result is not None else []
    assert [r.nodes for r in env.history] == ran


@pytest.mark.parametrize(("home", "text", "executable", "stage", "message"), CASES, ids=IDS)
def test_a_plan_of_the_program_is_scored_as_the_library_runs_it(
        home, text, executable, stage, message):
    """The program written as an EAI plan (its grounded steps, names and ids): the same
    verdict and message, and its action goals met exactly when every step ran."""
    from homesim.goals.check import GoalSet
    from homesim.goals.eai import TaskGoals
    from homesim.goals.plans import TaskContext, score_plan

    run = homesim.run_program(homesim.parse_program(text), homesim.load_home(home), trace=True)
    steps = _grounded_steps(run, text)
    if steps is None:
        pytest.skip("an ungrounded program names no nodes to write a plan with")
    program = homesim.parse_program("\n".join(steps))
    pairs = [(s.action.key, [x for ref in s.args for x in (ref.name, str(ref.node_id))])
             for s in program.steps]
    plan = "{" + ", ".join(f"{json.dumps(a)}: {json.dumps(v)}" for a, v in pairs) + "}"
    objects = frozenset((ref.name, ref.node_id) for s in program.steps for ref in s.args)
    goals = GoalSet(actions=tuple((s.action.key,) for s in program.steps))
    context = TaskContext(TaskGoals("case", "case", goals, None, ""), run.graph, objects)
    score = score_plan("case", plan, context)
    assert [str(homesim.Step.parse(x)) for x in score.steps] == steps  # the same nodes
    assert score.executable == run.executable
    assert score.success == run.executable
    if not run.executable:
        assert (score.failed_step, score.reason) == (run.failed_step, run.message)


def test_a_program_rendered_from_the_cli_meets_the_simulator_once(tmp_path, capsys,
                                                                  monkeypatch, gl):
    """From ``homesim render`` to the frames, the program is executed once (by
    `run_program`): render animates that run's trace."""
    import importlib

    sim = importlib.import_module("homesim.sim.execute")  # the module, not its function

    calls = []
    execute_on = sim.execute_on

    def counted(*args, **kwargs):
        calls.append(args[0])
        return execute_on(*args, **kwargs)

    monkeypatch.setattr(sim, "execute_on", counted)
    code, err, meta = _cli_render("scene1", str(load_example("watch_tv")), tmp_path, capsys)
    assert code == 0, err
    assert meta is not None and meta["num_frames"] > len(meta["steps"])
    assert len(calls) == 1 and str(calls[0]) == meta["program"]
