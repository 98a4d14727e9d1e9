"""Running the app with uvicorn: timeouts that slow clients cannot hold open.

uvicorn closes an idle keep-alive connection after a while, but a client that sends a
request's headers one byte at a time keeps it forever (each byte resets the idle timer),
and a stopping server waits for it. `HeaderTimeoutProtocol` gives every request's headers
a deadline; `homesim.serve.limits.BodySizeLimit` gives its body one; the graceful
shutdown waits `SHUTDOWN_GRACE_S` for requests in flight, then cancels them.
"""

from __future__ import annotations

import asyncio
from typing import Any

import h11
import uvicorn
from uvicorn.protocols.http.h11_impl import H11Protocol

from homesim.limits import HEADER_TIMEOUT_S, KEEP_ALIVE_S, SHUTDOWN_GRACE_S

_TIMEOUT_TEXT = b"request headers not received in time"
_TIMEOUT_ANSWER = (b"HTTP/1.1 408 Request Timeout\r\ncontent-type: text/plain\r\n"
                   b"connection: close\r\ncontent-length: %d\r\n\r\n%s"
                   % (len(_TIMEOUT_TEXT), _TIMEOUT_TEXT))


class HeaderTimeoutProtocol(H11Protocol):
    """uvicorn's h11 protocol, closing connections whose request headers do not arrive
    within `header_timeout` seconds of the connection (or of the previous answer)."""

    header_timeout: float = HEADER_TIMEOUT_S
    _head_timer: asyncio.TimerHandle | None = None

    def connection_made(self, transport: Any) -> None:  # Any: uvicorn narrows the base type
        super().connection_made(transport)
        self._start_head_timer()

    def connection_lost(self, exc: Exception | None) -> None:
        self._stop_head_timer()
        super().connection_lost(exc)

    def handle_events(self) -> None:
        super().handle_events()
        if self.conn.their_state is not h11.IDLE:  # the headers are in (or the end)
            self._stop_head_timer()

    def on_response_complete(self) -> None:
        self._start_head_timer()  # before: the next request may already be buffered
        super().on_response_complete()

    def _start_head_timer(self) -> None:
        self._stop_head_timer()
        self._head_timer = self.loop.call_later(self.header_timeout, self._head_timed_out)

    def _stop_head_timer(self) -> None:
        if self._head_timer is not None:
            self._head_timer.cancel()
            self._head_timer = None

    def _head_timed_out(self) -> None:
        self._head_timer = None
        if self.transport.is_closing():
            return
        if self.cycle is not None and not self.cycle.response_complete:
            return  # a request is being answered; its body has its own deadline
        self.transport.write(_TIMEOUT_ANSWER)
        self.transport.close()


def protocol_with_header_timeout(seconds: float) -> type[HeaderTimeoutProtocol]:
    """`HeaderTimeoutProtocol` with another deadline (tests use short ones)."""
    return type("HeaderTimeoutProtocol", (HeaderTimeoutProtocol,), {"header_timeout": seconds})


def uvicorn_config(app: Any, host: str, port: int, log_level: str = "warning",
                   header_timeout: float = HEADER_TIMEOUT_S) -> uvicorn.Config:
    """The uvicorn settings of ``homesim serve``: h11 with header, keep-alive and
    shutdown deadlines."""
    return uvicorn.Config(
        app, host=host, port=port, log_level=log_level,
        http=protocol_with_header_timeout(header_timeout),
        timeout_keep_alive=KEEP_ALIVE_S,
        timeout_graceful_shutdown=SHUTDOWN_GRACE_S,
    )
