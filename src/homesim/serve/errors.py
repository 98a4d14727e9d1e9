"""How the API reports errors: always JSON ``{"error": {"kind", "message", ...}}``, one line.

`HomesimError` messages already name where and why; a `ProgramError` also gives the line
number, so the editor can mark the block. Anything else is a bug of ours and answers 500
with one line; the server keeps running and the client's connection stays usable.
Every answer serialises: lone surrogates (``"\\ud800"`` in a request) become U+FFFD.
"""

from __future__ import annotations

import json
import logging
from collections.abc import Mapping
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException

from homesim.errors import HomesimError, LimitError, ProgramError
from homesim.limits import MAX_JSON_DEPTH, MAX_MESSAGE_CHARS

log = logging.getLogger(__name__)


def without_surrogates(text: str) -> str:
    """`text` with each lone surrogate (not UTF-8 encodable) replaced by U+FFFD.

    >>> without_surrogates("a\\ud800b") == "a\\ufffdb"
    True
    """
    return text.encode("utf-16", "surrogatepass").decode("utf-16", "replace")


def json_bytes(content: Any) -> bytes:
    """Compact UTF-8 JSON of `content`; lone surrogates become U+FFFD instead of failing."""
    text = json.dumps(content, ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    try:
        return text.encode("utf-8")
    except UnicodeEncodeError:  # a lone surrogate from the request made it into the answer
        return without_surrogates(text).encode("utf-8")


class SafeJSONResponse(JSONResponse):
    """A JSON answer that always serialises (see `json_bytes`)."""

    def render(self, content: Any) -> bytes:
        return json_bytes(content)


class ApiError(Exception):
    """An error with an HTTP status, a kind (``home``, ``program``, ...) and extra fields;
    `headers` go into the answer (``Retry-After`` of a 503)."""

    def __init__(self, status: int, kind: str, message: str,
                 headers: Mapping[str, str] | None = None, **extra: Any):
        super().__init__(message)
        self.status = status
        self.kind = kind
        self.message = message
        self.headers = dict(headers or {})
        self.extra = extra


def clip(text: str, limit: int = MAX_MESSAGE_CHARS) -> str:
    """`text` cut to `limit` characters with an ellipsis, so answers stay small."""
    return text if len(text) <= limit else text[:limit - 1] + "…"


def error_body(kind: str, message: str, **extra: Any) -> dict[str, Any]:
    """``{"error": {...}}`` with long texts clipped."""
    fields = {k: clip(v) if isinstance(v, str) else v for k, v in extra.items()}
    return {"error": {"kind": kind, "message": clip(message), **fields}}


def error_response(status: int, kind: str, message: str,
                   headers: Mapping[str, str] | None = None, **extra: Any) -> JSONResponse:
    return SafeJSONResponse(error_body(kind, message, **extra), status_code=status,
                            headers=dict(headers) if headers else None)


def program_error_fields(e: ProgramError) -> dict[str, Any]:
    """The fields the editor needs to mark the block of a bad line."""
    return {"line": e.line, "text": e.text, "expected": e.expected}


def error_of(e: Exception) -> tuple[int, dict[str, Any]]:
    """Status and body of the answer to an error raised while handling a program, the
    same as the handlers below give (for answers built in a worker process)."""
    if isinstance(e, ApiError):
        return e.status, error_body(e.kind, e.message, **e.extra)
    if isinstance(e, ProgramError):
        return 422, error_body("program", str(e), **program_error_fields(e))
    if isinstance(e, LimitError):
        return limit_status(e), error_body("limit", str(e), limit=e.limit)
    if isinstance(e, HomesimError):
        return 422, error_body(type(e).__name__, str(e))
    log.error("internal error", exc_info=e)
    return 500, error_body("internal", bug_message(e))


def limit_status(e: LimitError) -> int:
    """413 for a size in bytes over its limit, 422 for other limits."""
    return 413 if e.limit.endswith("_BYTES") else 422


def bug_message(e: BaseException) -> str:
    return f"internal error: {type(e).__name__}: {e} (please report it)"


def _location(loc: tuple[Any, ...]) -> str:
    return ".".join(str(p) for p in loc if p != "body") or "body"


def validation_message(exc: RequestValidationError) -> str:
    """One line for a request body that does not fit the schema."""
    errors = exc.errors()
    if not errors:
        return "invalid request"
    first = errors[0]
    if first.get("type") == "json_invalid":
        why = first.get("ctx", {}).get("error", "parse error")
        return f"request body is not valid JSON ({why})"
    where = _location(tuple(first.get("loc", ())))
    more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
    return f"{where}: {first.get('msg', 'invalid')}{more}"


def install_error_handlers(app: FastAPI) -> None:
    """Register the JSON error handlers on `app`."""

    @app.exception_handler(ApiError)
    async def _api(_: Request, e: ApiError) -> JSONResponse:
        return error_response(e.status, e.kind, e.message, e.headers, **e.extra)

    @app.exception_handler(ProgramError)
    async def _program(_: Request, e: ProgramError) -> JSONResponse:
        return error_response(422, "program", str(e), **program_error_fields(e))

    @app.exception_handler(LimitError)
    async def _limit(_: Request, e: LimitError) -> JSONResponse:
        return error_response(limit_status(e), "limit", str(e), limit=e.limit)

    @app.exception_handler(HomesimError)
    async def _homesim(_: Request, e: HomesimError) -> JSONResponse:
        return error_response(422, type(e).__name__, str(e))

    @app.exception_handler(RequestValidationError)
    async def _invalid(_: Request, e: RequestValidationError) -> JSONResponse:
        return error_response(422, "request", validation_message(e))

    @app.exception_handler(HTTPException)
    async def _http(request: Request, e: HTTPException) -> JSONResponse:
        message = str(e.detail)
        if e.status_code == 400 and isinstance(e.__cause__, RecursionError):
            # FastAPI answers 400 when json.loads gives up on deep nesting; the JSON-depth
            # check of `limits.BodySizeLimit` normally refuses such bodies first.
            return error_response(422, "request", f"request body is nested deeper than "
                                  f"{MAX_JSON_DEPTH} levels")
        if e.status_code == 404:
            message = f"no such page or API route: {request.url.path}"
        elif e.status_code == 405:
            message = f"{request.method} is not allowed on {request.url.path}"
        return error_response(e.status_code, "http", message, getattr(e, "headers", None))

    @app.exception_handler(Exception)
    async def _bug(_: Request, e: Exception) -> JSONResponse:
        # Reached only for bugs outside `CatchBugs` (which `create_app` adds outermost).
        log.exception("internal error")
        return error_response(500, "internal", bug_message(e))


class CatchBugs:
    """ASGI middleware turning an exception into a one-line 500 without re-raising it.

    Starlette's own last-resort handler answers and then re-raises, and uvicorn closes the
    connection when an app raises: the client's next request on that keep-alive connection
    then fails. Here the exception ends with the answer, so the connection stays usable.
    """

    def __init__(self, app: Any):
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = False

        async def watch(message: Any) -> None:
            nonlocal started
            started = started or message["type"] == "http.response.start"
            await send(message)

        try:
            await self.app(scope, receive, watch)
        except Exception as e:  # a bug of ours: one line to the client, the trace to the log
            log.error("internal error", exc_info=e)
            if not started:
                await error_response(500, "internal", bug_message(e))(scope, receive, send)
