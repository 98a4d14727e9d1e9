"""Routes that check and run programs: ``/api/validate``, ``/api/execute``; and the steps
of ``/api/render`` (its jobs are in `homesim.serve.renders`).

Handlers are plain functions of a request model. `answer` runs them one at a time in the
small-request lane (`run_small`) for normal programs and in a worker process
(`homesim.serve.workers.ProgramPool`) for programs over `INLINE_PROGRAM_CHARS`, so a
large program never slows other requests.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import Response

from homesim.ground.pipeline import Run, run_program
from homesim.ground.search import unground
from homesim.limits import (
    INLINE_PROGRAM_CHARS,
    MAX_RENDER_PIXEL_FRAMES,
    MAX_RENDER_VIDEO_PIXEL_FRAMES,
)
from homesim.program.model import Program
from homesim.program.parse import parse_program
from homesim.serve.errors import ApiError, SafeJSONResponse
from homesim.serve.homes import get_home
from homesim.serve.pool import answer_or_gone, run_small
from homesim.serve.results import program_json, step_lines
from homesim.serve.schemas import ExecuteRequest, ProgramRequest, RenderRequest, VideoRequest
from homesim.sim.execute import binding_problems
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import is_generated

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
                trace: bool, repair: bool = True) -> Run:
    """`run_program` as a request asks: ground None runs it as `homesim run` does (grounded
    programs as they are, others prepared and grounded); True grounds it anew; False
    reads (N) as node N, as the reference simulator does. `repair` as `run_program`."""
    if ground:
        program = unground(program)
    return run_program(program, graph, seed=seed, trace=trace, reference=ground is False,
                       repair=repair)


def validate(request: ProgramRequest) -> dict[str, Any]:
    """Parse a program; with a home, also check the node ids it carries there."""
    program, lines = parse_request(request.program)
    answer = program_json(program, lines)
    problems: list[dict] = []
    if request.home is not None:
        problems = ref_problems(program, lines, get_home(request.home))
    return {"ok": not problems, "problems": problems, **answer}


def run(request: ExecuteRequest) -> dict[str, Any]:
    """Run a program in a home (`run_program`): every step ✓/✗ with its reason and changes."""
    program, lines = parse_request(request.program)
    graph = get_home(request.home)
    ran = run_request(program, graph, request.ground, request.seed, trace=True,
                      repair=request.repair)
    return {**ran.to_dict(lines), "home": request.home}


def keyframe_renderer() -> Callable[..., Any]:
    """`homesim.render.iter_keyframes`; 501 when the render extra is not installed."""
    try:
        from homesim.render import iter_keyframes
    except ImportError as e:  # mujoco or a system library missing
        raise ApiError(501, "render", f"rendering is not available on this server: {e} "
                       "(install the 'render' extra)") from None
    return iter_keyframes


def video_renderer() -> Callable[..., Any]:
    """`homesim.render.render_video`; 501 when the render extra is not installed."""
    keyframe_renderer()  # the same import, the same message
    from homesim.render import render_video

    return render_video


def render_plan(request: RenderRequest) -> dict[str, Any]:
    """Check a render request before queueing it: a video's sides are even, the program
    parses, the home exists and frames x pixels are within `MAX_RENDER_PIXEL_FRAMES`; the
    line of each key frame."""
    if isinstance(request, VideoRequest) and (request.width % 2 or request.height % 2):
        raise ApiError(422, "render", f"image size {request.width}x{request.height}: width "
                       "and height of a video must be even (H.264)")
    program, lines = parse_request(request.program)
    get_home(request.home)
    pixel_frames = len(program.steps) * request.width * request.height
    if pixel_frames > MAX_RENDER_PIXEL_FRAMES:
        raise ApiError(422, "render", f"{len(program.steps)} key frames of "
                       f"{request.width}x{request.height} pixels are {pixel_frames:,} "
                       f"pixel-frames, over the limit of {MAX_RENDER_PIXEL_FRAMES:,}; render "
                       "fewer steps or smaller frames")
    return {"lines": lines}


def _grounded(request: RenderRequest) -> Run:
    """A render request's program run as `run_program` runs it, with its trace (422 with
    the line when it cannot be grounded): render animates this run, never runs it again."""
    program, lines = parse_request(request.program)
    graph = get_home(request.home)
    ran = run_request(program, graph, None, request.seed, trace=True, repair=request.repair)
    if ran.grounding is None:
        index = None if ran.failed_step is None else ran.failed_step - 1
        where: dict[str, Any] = {} if index is None else {"line": lines[index], "index": index}
        raise ApiError(422, "grounding", ran.message, None, **where)
    return ran


def render_frames(request: RenderRequest) -> Iterable[tuple[int, Any]]:
    """Key frames of a program (the frame at the end of each step), one at a time, as
    (step index, RGB array); runs in a render worker process."""
    function = keyframe_renderer()
    return function(_grounded(request), width=request.width, height=request.height,
                    seed=request.seed)


def render_video_file(request: VideoRequest, path: str,
                      progress: Callable[[int, int], None]) -> int:
    """The video of a whole program into the MP4 file `path` (the frames `homesim render`
    records), calling ``progress(done, total)`` per frame; returns the frame count.
    Runs in a render worker process."""
    function = video_renderer()
    limit = (MAX_RENDER_VIDEO_PIXEL_FRAMES, "MAX_RENDER_VIDEO_PIXEL_FRAMES")
    return function(_grounded(request), path, width=request.width, height=request.height,
                    fps=request.fps, seed=request.seed, progress=progress, limit=limit)


def is_large(request: ProgramRequest | ExecuteRequest | RenderRequest) -> bool:
    return len(request.program) > INLINE_PROGRAM_CHARS


def is_heavy(request: ProgramRequest | ExecuteRequest | RenderRequest) -> bool:
    """A request for a program worker: a large program, or a generated home (making one
    takes ~0.5 s of CPU, which the server process must not spend)."""
    return is_large(request) or (request.home is not None and is_generated(request.home))


async def answer(http: Request, handler: Callable[[Any], dict[str, Any]], request: Any
                 ) -> Response:
    """`handler(request)` as a JSON answer: in a thread, or in a program worker process
    when the request is heavy (`is_heavy`)."""
    if is_heavy(request):
        return await answer_or_gone(http.app.state.programs, handler, request,
                                    http.is_disconnected)
    return SafeJSONResponse(await run_small(handler, request))


@router.post("/validate", response_class=SafeJSONResponse)
async def validate_route(request: ProgramRequest, http: Request) -> Response:
    """Parse a program; with a home, also check that its node ids exist there."""
    return await answer(http, validate, request)


@router.post("/execute", response_class=SafeJSONResponse)
async def run_route(request: ExecuteRequest, http: Request) -> Response:
    """Execute a program on a home: every step ✓/✗ with its reason and state changes.

    A small program is run as written in the small-request lane; only when it fails there
    and may be repaired does it go to a program worker, where repair runs: repair may
    ground it dozens of times (over a second for a 1 KiB program), which the lane must
    not spend while other small requests wait. The answer is the same either way
    (`run_program` answers a program that runs as written without repairing it)."""
    if is_heavy(request) or not request.repair or request.ground is False:
        return await answer(http, run, request)
    strict = await run_small(run, request.model_copy(update={"repair": False}))
    if strict["executable"]:
        return SafeJSONResponse(strict)
    return await answer_or_gone(http.app.state.programs, run, request, http.is_disconnected)
