"""Routes that check and run programs: ``/api/validate``, ``/api/execute``, ``/api/render``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from fastapi import APIRouter

from homesim.program.model import Program
from homesim.program.parse import parse_program
from homesim.serve import optional
from homesim.serve.errors import ApiError
from homesim.serve.homes import get_home
from homesim.serve.images import png_data_url
from homesim.serve.results import execution_json, program_json, step_lines
from homesim.serve.schemas import ExecuteRequest, ProgramRequest, RenderRequest
from homesim.sim.execute import execute
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


def ref_problems(program: Program, lines: list[int], graph: EnvironmentGraph,
                 can_ground: bool) -> list[dict]:
    """Grounded refs that name no node of the home or a node of another class; refs
    without a node id when there is no grounding to bind them."""
    problems = []
    for index, step in enumerate(program.steps):
        for ref in step.args:
            if ref.node_id is None:
                if can_ground:
                    continue
                message = (f"<{ref.name}> ({ref.instance}) has no node id, and grounding is "
                           "not available to choose one")
                problems.append({"index": index, "line": lines[index], "step": str(step),
                                 "message": f"line {lines[index]}: {message}"})
                continue
            node = graph.get(ref.node_id)
            if node is None:
                message = f"the home has no node {ref.node_id} for <{ref.name}> ({ref.instance})"
            elif node.class_name != ref.name:
                message = (f"node {ref.node_id} is a {node.class_name}, "
                           f"not a {ref.name}")
            else:
                continue
            problems.append({"index": index, "line": lines[index], "step": str(step),
                             "message": f"line {lines[index]}: {message}"})
    return problems


@dataclass(frozen=True)
class Grounded:
    program: Program
    bindings: dict[tuple[str, int], int] | None


def ground_if_needed(program: Program, lines: list[int], graph: EnvironmentGraph,
                     ground: bool | None, seed: int) -> Grounded:
    """Bind the program's objects to nodes when asked, or when some ref lacks a node id."""
    needed = ground if ground is not None else not program.is_grounded
    if not needed:
        return Grounded(program, None)
    function, why = optional.grounding()
    if function is None:
        if ground:
            raise ApiError(501, "grounding", f"grounding is not available: {why}")
        index, ref = next((i, r) for i, s in enumerate(program.steps) for r in s.args
                          if r.node_id is None)
        raise ApiError(
            422, "grounding",
            f"line {lines[index]}: <{ref.name}> ({ref.instance}) names no node of the home, "
            f"and grounding is not available ({why}); pick the object from the block's "
            f"dropdown or write it as <{ref.name}> ({ref.instance}.NODE_ID), or send "
            "ground=false to read (N) as node N like the reference simulator",
            line=lines[index], index=index)
    grounding = function(program, graph, seed=seed)  # GroundingError answers 422
    return Grounded(grounding.program, {tuple(k): v for k, v in grounding.bindings.items()})


@router.post("/validate")
def validate(request: ProgramRequest) -> dict[str, Any]:
    """Parse a program; with a home, also check that its node ids exist there."""
    program, lines = parse_request(request.program)
    answer = program_json(program, lines)
    function, _ = optional.grounding()
    problems: list[dict] = []
    if request.home is not None:
        problems = ref_problems(program, lines, get_home(request.home), function is not None)
    return {"ok": not problems, "problems": problems,
            "grounding_available": function is not None, **answer}


@router.post("/execute")
def run(request: ExecuteRequest) -> dict[str, Any]:
    """Execute a program on a home: every step ✓/✗ with its reason and state changes."""
    program, lines = parse_request(request.program)
    graph = get_home(request.home)
    grounded = ground_if_needed(program, lines, graph, request.ground, request.seed)
    result = execute(grounded.program, graph, trace=True)
    answer = execution_json(result, lines)
    answer["home"] = request.home
    answer["bindings"] = None if grounded.bindings is None else [
        {"name": n, "instance": i, "node_id": v} for (n, i), v in grounded.bindings.items()]
    return answer


@router.post("/render")
def render(request: RenderRequest) -> dict[str, Any]:
    """Key frames of a program (the frame at the end of each step), as PNG data URLs."""
    function, why = optional.keyframe_renderer()
    if function is None:
        raise ApiError(501, "render", f"rendering is not available on this server: {why} "
                       "(install the 'render' extra)")
    program, lines = parse_request(request.program)
    graph = get_home(request.home)
    grounded = ground_if_needed(program, lines, graph, None, request.seed)
    frames = function(grounded.program, graph, width=request.width, height=request.height,
                      seed=request.seed)
    return {"home": request.home, "width": request.width, "height": request.height,
            "frames": [{"index": int(i), "line": lines[int(i)], "image": png_data_url(rgb)}
                       for i, rgb in frames]}
