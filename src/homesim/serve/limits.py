"""Request limits: body size and read time, enforced while the body streams in, and the
nesting depth of a JSON body, checked before it is parsed."""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any

from homesim.limits import (
    BODY_TIMEOUT_S,
    INLINE_PROGRAM_CHARS,
    LARGE_BODIES_AT_ONCE,
    MAX_JSON_DEPTH,
    MAX_REQUEST_BYTES,
    PROGRAM_QUEUE,
)

MAX_BODY_BYTES = MAX_REQUEST_BYTES
"""Largest request body the API accepts (see `homesim.limits`)."""

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


STOPPING = "the server is stopping; retry in a moment"

_BRACKETS = bytes.maketrans(b"[{]}", b"(())")
_NOT_BRACKETS = bytes(b for b in range(256) if b not in b"[]{}")


def _outside_strings(text: bytes) -> bytes:
    """`text` (escaped quotes dropped) less its quoted strings, quotes included; an
    unclosed last string stays. A split, not a regular expression: ten times faster."""
    pieces = text.split(b'"')
    tail = [b'"' + pieces.pop()] if len(pieces) % 2 == 0 else []
    return b"".join(pieces[::2] + tail)


def nested_deeper_than(body: bytes, depth: int) -> bool:
    """Whether arrays and objects in a JSON text nest deeper than `depth`, without
    parsing it (a parser recurses once per level).

    Strings are dropped and only brackets kept; then each pass deletes the innermost
    ``()`` pairs. A run of `depth` + 1 openers, more than `depth` passes needed, or more
    than `depth` unclosed openers left means deeper. Everything runs at C speed: about
    0.1 ms for 256 KiB.

    >>> nested_deeper_than(b'{"a": [1, {"b": "[[["}]}', 3), nested_deeper_than(b"[[[[]]]]", 3)
    (False, True)
    """
    unescaped = body.replace(b"\\\\", b"").replace(b'\\"', b"") if b"\\" in body else body
    rest = _outside_strings(unescaped).translate(_BRACKETS, _NOT_BRACKETS)
    too_deep = b"(" * (depth + 1)
    for _ in range(depth):
        if too_deep in rest:
            return True
        if b"()" not in rest:
            break
        rest = rest.replace(b"()", b"")
    return b"()" in rest or rest.count(b"(") > depth


class BodySizeLimit:
    """ASGI middleware refusing request bodies that are too large, too slow or too deep.

    A declared ``Content-Length`` over `max_bytes` is refused (413) before reading; a
    chunked body is counted as it arrives and refused as soon as it passes the limit, so a
    client cannot get around the limit by omitting the header. A body that has not fully
    arrived `timeout` seconds after the headers gets 408 and the connection is closed (a
    client trickling its body cannot hold a connection). A JSON body nested deeper than
    `MAX_JSON_DEPTH` gets 422.
    """

    def __init__(self, app: ASGIApp, max_bytes: int = MAX_BODY_BYTES,
                 timeout: float = BODY_TIMEOUT_S):
        self.app = app
        self.max_bytes = max_bytes
        self.timeout = timeout

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
        deadline = time.monotonic() + self.timeout
        while True:
            try:
                message = await asyncio.wait_for(receive(), max(deadline - time.monotonic(), 0))
            except asyncio.TimeoutError:
                await _refuse(send, 408, f"request body not received within {self.timeout:g} s "
                              f"({received} bytes arrived)", close=True)
                return
            except asyncio.CancelledError:  # the server is stopping: answer, no traceback
                await _refuse(send, 503, STOPPING, close=True, kind="busy")
                return
            if message["type"] != "http.request":  # the client went away
                return
            chunk = message.get("body", b"")
            received += len(chunk)
            if received > self.max_bytes:
                await _refuse(send, 413, self._message(received, at_least=True), close=True)
                return
            chunks.append(chunk)
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        if body and nested_deeper_than(body, MAX_JSON_DEPTH):
            await _refuse(send, 422, f"request body is nested deeper than {MAX_JSON_DEPTH} "
                          "levels of JSON arrays and objects")
            return
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


class LargeBodyGate:
    """ASGI middleware letting `at_once` requests with large bodies in at a time.

    A large body (over `threshold` bytes, or of unknown length) costs the server's event
    loop milliseconds to receive, check and decode even when a worker process handles
    the program; many at once would make every small request wait behind them. Here at
    most `at_once` are read and answered at a time; up to `waiting` more wait unread
    (costing nothing); further ones are read to their end unparsed and get 503.
    """

    def __init__(self, app: ASGIApp, threshold: int = INLINE_PROGRAM_CHARS,
                 at_once: int = LARGE_BODIES_AT_ONCE, waiting: int = PROGRAM_QUEUE,
                 retry_after: int = 2):
        self.app = app
        self.threshold = threshold
        self.at_once = at_once
        self.waiting = waiting
        self.retry_after = retry_after
        self._waiters = 0
        self._gate: tuple[asyncio.AbstractEventLoop, asyncio.Semaphore] | None = None

    def _is_large(self, scope: Scope) -> bool:
        if scope["type"] != "http" or scope["method"] not in ("POST", "PUT", "PATCH"):
            return False
        length = next((v for k, v in scope.get("headers", ()) if k == b"content-length"), None)
        return length is None or not length.isdigit() or int(length) > self.threshold

    def _semaphore(self) -> asyncio.Semaphore:
        loop = asyncio.get_running_loop()
        if self._gate is None or self._gate[0] is not loop:  # one per event loop (tests)
            self._gate = (loop, asyncio.Semaphore(self.at_once))
        return self._gate[1]

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if not self._is_large(scope):
            await self.app(scope, receive, send)
            return
        gate = self._semaphore()
        if gate.locked() and self._waiters >= self.waiting:
            drained = await _drain(receive, MAX_REQUEST_BYTES)
            await _refuse(send, 503, f"the server is busy: {self.at_once + self._waiters} large "
                          f"requests are being handled or waiting; retry in {self.retry_after} s",
                          close=not drained, kind="busy", retry_after=self.retry_after)
            return
        self._waiters += 1
        try:
            await gate.acquire()
        except asyncio.CancelledError:  # the server is stopping: answer, no traceback
            await _refuse(send, 503, STOPPING, close=True, kind="busy")
            return
        finally:
            self._waiters -= 1
        try:
            await self.app(scope, receive, send)
        finally:
            gate.release()


async def _drain(receive: Receive, limit: int, timeout: float = BODY_TIMEOUT_S) -> bool:
    """Read a request body to its end without keeping it; False when it did not end
    within `limit` bytes and `timeout` seconds (or the client went away)."""
    received = 0
    deadline = time.monotonic() + timeout
    while received <= limit:
        try:
            message = await asyncio.wait_for(receive(), max(deadline - time.monotonic(), 0))
        except asyncio.TimeoutError:
            return False
        if message["type"] != "http.request":
            return False
        received += len(message.get("body", b""))
        if not message.get("more_body", False):
            return True
    return False


async def _refuse(send: Send, status: int, message: str, close: bool = False,
                  kind: str = "request", retry_after: int | None = None) -> None:
    """Answer `status` with a one-line error; `close` when the body was not read to its
    end (the connection cannot carry another request then)."""
    body = json.dumps({"error": {"kind": kind, "message": message}}).encode()
    headers = [(b"content-type", b"application/json"),
               (b"content-length", str(len(body)).encode())]
    if close:
        headers.append((b"connection", b"close"))
    if retry_after is not None:
        headers.append((b"retry-after", str(retry_after).encode()))
    await send({"type": "http.response.start", "status": status, "headers": headers})
    await send({"type": "http.response.body", "body": body})
