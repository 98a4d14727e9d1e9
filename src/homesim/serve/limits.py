"""Request limits: a cap on body size, enforced while the body streams in."""

from __future__ import annotations

import json
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any

from homesim.limits import MAX_REQUEST_BYTES

MAX_BODY_BYTES = MAX_REQUEST_BYTES
"""Largest request body the API accepts (see `homesim.limits`)."""

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


class BodySizeLimit:
    """ASGI middleware answering 413 when a request body is over `max_bytes`.

    A declared ``Content-Length`` over the limit is refused before reading; a chunked
    body is counted as it arrives and refused as soon as it passes the limit, so a client
    cannot get around the limit by omitting the header.
    """

    def __init__(self, app: ASGIApp, max_bytes: int = MAX_BODY_BYTES):
        self.app = app
        self.max_bytes = max_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        for name, value in scope.get("headers", ()):
            if name == b"content-length":
                try:
                    declared = int(value)
                except ValueError:
                    await _refuse(send, 400, "the Content-Length header is not a number")
                    return
                if declared > self.max_bytes:
                    await _refuse(send, 413, self._message(declared))
                    return
        # Read the whole body first (it is small), so the app never sees a partial one and
        # a refusal happens before any route runs; then replay it to the app.
        chunks: list[bytes] = []
        received = 0
        while True:
            message = await receive()
            if message["type"] != "http.request":  # the client went away
                return
            chunk = message.get("body", b"")
            received += len(chunk)
            if received > self.max_bytes:
                await _refuse(send, 413, self._message(received, at_least=True))
                return
            chunks.append(chunk)
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        replayed = False

        async def replay() -> Message:
            nonlocal replayed
            if not replayed:
                replayed = True
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()  # after the body: wait for a disconnect, as ASGI does

        await self.app(scope, replay, send)

    def _message(self, size: int, at_least: bool = False) -> str:
        more = "at least " if at_least else ""
        return (f"request body is {more}{size} bytes, over the {self.max_bytes // 1024} KiB "
                "limit of this server")


async def _refuse(send: Send, status: int, message: str) -> None:
    body = json.dumps({"error": {"kind": "request", "message": message}}).encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body})
