"""How the API reports errors: always JSON ``{"error": {"kind", "message", ...}}``, one line.

`HomesimError` messages already name where and why; a `ProgramError` also gives the line
number, so the editor can mark the block. Anything else is a bug of ours and answers 500
with one line (the server keeps running).
"""

from __future__ import annotations

import logging
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException

from homesim.errors import HomesimError, LimitError, ProgramError

log = logging.getLogger(__name__)


class ApiError(Exception):
    """An error with an HTTP status, a kind (``home``, ``program``, ...) and extra fields."""

    def __init__(self, status: int, kind: str, message: str, **extra: Any):
        super().__init__(message)
        self.status = status
        self.kind = kind
        self.message = message
        self.extra = extra


def error_response(status: int, kind: str, message: str, **extra: Any) -> JSONResponse:
    return JSONResponse({"error": {"kind": kind, "message": message, **extra}}, status_code=status)


def program_error_fields(e: ProgramError) -> dict[str, Any]:
    """The fields the editor needs to mark the block of a bad line."""
    return {"line": e.line, "text": e.text, "expected": e.expected}


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
        return error_response(e.status, e.kind, e.message, **e.extra)

    @app.exception_handler(ProgramError)
    async def _program(_: Request, e: ProgramError) -> JSONResponse:
        return error_response(422, "program", str(e), **program_error_fields(e))

    @app.exception_handler(LimitError)
    async def _limit(_: Request, e: LimitError) -> JSONResponse:
        status = 413 if e.limit.endswith("_BYTES") else 422
        return error_response(status, "limit", str(e), limit=e.limit)

    @app.exception_handler(HomesimError)
    async def _homesim(_: Request, e: HomesimError) -> JSONResponse:
        return error_response(422, type(e).__name__, str(e))

    @app.exception_handler(RequestValidationError)
    async def _invalid(_: Request, e: RequestValidationError) -> JSONResponse:
        return error_response(422, "request", validation_message(e))

    @app.exception_handler(HTTPException)
    async def _http(request: Request, e: HTTPException) -> JSONResponse:
        message = str(e.detail)
        if e.status_code == 404:
            message = f"no such page or API route: {request.url.path}"
        elif e.status_code == 405:
            message = f"{request.method} is not allowed on {request.url.path}"
        return error_response(e.status_code, "http", message)

    @app.exception_handler(Exception)
    async def _bug(_: Request, e: Exception) -> JSONResponse:
        log.exception("internal error")
        return error_response(500, "internal",
                              f"internal error: {type(e).__name__}: {e} (please report it)")
