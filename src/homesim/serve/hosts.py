"""The Host header check: answers only to names the server was started for.

A server bound to loopback is still reachable from a web page through DNS rebinding: the
page's own name is made to resolve to 127.0.0.1, and the browser then sends requests with
``Host: attacker.example``. Refusing unknown Host names closes that door.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from homesim.serve.errors import error_response

LOOPBACK_HOSTS = ("localhost", "127.0.0.1", "[::1]")
"""Names a loopback server answers to by default."""


_HOST = re.compile(r"(\[[0-9a-f:.]+\]|[^\[\]:]+)(?::[0-9]{1,5})?")
"""A Host header: a bracketed IPv6 address or a name, then at most a numeric port."""


def host_name(header: str) -> str:
    """The name in a Host header, without the port, lower case; IPv6 keeps its brackets.
    A header of another shape (``[::1]evil.com``, ``localhost:x``) is returned whole, so
    it matches no allowed name.

    >>> host_name("LocalHost:8000"), host_name("[::1]:8000"), host_name("127.0.0.1")
    ('localhost', '[::1]', '127.0.0.1')
    >>> host_name("[::1]evil.com")
    '[::1]evil.com'
    """
    header = header.strip().lower()
    match = _HOST.fullmatch(header)
    return match.group(1) if match else header


class HostCheck:
    """ASGI middleware answering 400 to requests whose Host is not an allowed name.

    `allowed` holds names (``localhost``, ``[::1]``, ``192.168.1.5``) or ``*`` for any.
    """

    def __init__(self, app: Any, allowed: Iterable[str] = LOOPBACK_HOSTS):
        self.app = app
        self.allowed = frozenset(host_name(h) for h in allowed)

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] not in ("http", "websocket") or "*" in self.allowed:
            await self.app(scope, receive, send)
            return
        header = next((v for k, v in scope.get("headers", ()) if k == b"host"), b"")
        name = host_name(header.decode("latin-1"))
        if name in self.allowed:
            await self.app(scope, receive, send)
            return
        allowed = ", ".join(sorted(self.allowed))
        if not name:
            message = f"the request has no Host header (allowed: {allowed})"
        else:
            shown = name[:100]
            message = (f"Host {shown!r} is not served here (allowed: {allowed}); start the "
                       f"server with 'homesim serve --allowed-host {shown}' to serve it")
        await error_response(400, "host", message)(scope, receive, send)
