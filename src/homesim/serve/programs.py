"""Routes that check and run programs: ``/api/validate``, ``/api/execute``, ``/api/render``."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

from fastapi import APIRouter

from homesim.ground.pipeline import Run, run_program
from homesim.ground.search import unground
from homesim.program.model import Program
from homesim.program.parse import parse_program
from homesim.serve.errors import ApiError
from homesim.serve.homes import get_home
from homesim.serve.images import png_data_url
from homesim.serve.results import program_json, step_lines
from homesim.serve.schemas import ExecuteRequest, ProgramRequest, RenderRequest
from homesim.sim.execute import binding_problems
from homesim.world.graph import EnvironmentGraph

router = APIRouter(prefix="/api", tags=["programs"])

_SOURCE = None  # messages read "line 3: ..."; the editor has one text


def parse_request(text: str) -> tuple[Program, list[int]]:
    """Parse a program from a request, with the line of each step; 422 when it is empty.

    A ProgramError answers 422 with its line, a LimitError (over `homesim.limits`) 413 or
    422 naming the limit."""
    program = parse_program(text, source=_SOURCE)
    if not program.steps:
        raise ApiError(422, "program", "the program has no steps")
    return program, step_lines(text)


def ref_problems(program: Program, lines: list[int], graph: EnvironmentGraph) -> list[dict]:
    """Node ids the program carries that name no node of the home or one of another class
    (equivalent names allowed, as in grounding). Refs without a node id are fine: they
    are grounded when the program runs."""
    problems = []
    for e in binding_problems(program, graph):
        if e.node is None:
            continue
        index = e.step - 1
        message = str(e).split(": ", 1)[1]  # drop "step N [...]", the line says where
        problems.append({"index": index, "line": lines[index], "step": str(program.steps[index]),
                         "message": f"line {lines[index]}: {message}"})
    return problems


def run_request(program: Program, graph: EnvironmentGraph, ground: bool | None, seed: int,
                trace: bool) -> Run:
    """`run_program` as a request asks: ground None runs it as `homesim run` does (grounded
    programs as they are, others prepared and grounded); True grounds it anew; False
    reads (N) as node N, as the reference simulator does."""
    if ground:
        program = unground(program)
    return run_program(program, graph, seed=seed, trace=trace, reference=ground is False)


@router.post("/validate")
def validate(request: ProgramRequest) -> dict[str, Any]:
    """Parse a program; with a home, also check the node ids it carries there."""
    program, lines = parse_request(request.program)
    answer = program_json(program, lines)
    problems: list[dict] = []
    if request.home is not None:
        problems = ref_problems(program, lines, get_home(request.home))
    return {"ok": not problems, "problems": problems, **answer}


@router.post("/execute")
def run(request: ExecuteRequest) -> dict[str, Any]:
    """Run a program in a home (`run_program`): every step ✓/✗ with its reason and changes."""
    program, lines = parse_request(request.program)
    graph = get_home(request.home)
    ran = run_request(program, graph, request.ground, request.seed, trace=True)
    return {**ran.to_dict(lines), "home": request.home}


def keyframe_renderer() -> Callable[..., Any]:
    """`homesim.render.render_keyframes`; 501 when the render extra is not installed."""
    try:
        from homesim.render import render_keyframes
    except ImportError as e:  # mujoco or a system library missing
        raise ApiError(501, "render", f"rendering is not available on this server: {e} "
                       "(install the 'render' extra)") from None
    return render_keyframes


@router.post("/render")
def render(request: RenderRequest) -> dict[str, Any]:
    """Key frames of a program (the frame at the end of each step), as PNG data URLs."""
    function = keyframe_renderer()
    program, lines = parse_request(request.program)
    graph = get_home(request.home)
    ran = run_request(program, graph, None, request.seed, trace=False)
    if ran.grounding is None:
        index = None if ran.failed_step is None else ran.failed_step - 1
        raise ApiError(422, "grounding", ran.message,
                       **({} if index is None else {"line": lines[index], "index": index}))
    extra = {}
    # Where grounding stood the agent for each step, once the renderer walks there.
    if ran.grounding.standing and "standing" in inspect.signature(function).parameters:
        extra["standing"] = ran.grounding.standing
    frames = function(ran.grounding.program, ran.graph, width=request.width,
                      height=request.height, seed=request.seed, **extra)
    return {"home": request.home, "width": request.width, "height": request.height,
            "frames": [{"index": int(i), "line": lines[int(i)], "image": png_data_url(rgb)}
                       for i, rgb in frames]}
