"""Fixtures of the web server tests: an in-process client and a live uvicorn server."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from homesim.examples import load_example
from homesim.serve import create_app


@pytest.fixture(scope="session")
def client() -> TestClient:
    return TestClient(create_app(), base_url="http://127.0.0.1", raise_server_exceptions=False)


@pytest.fixture(scope="session")
def watch_tv() -> str:
    """The demo program on scene1, in the ActivityPrograms format."""
    return str(load_example("watch_tv"))


def start_server(static_dir: Path | None = None, app=None, **config
                 ) -> tuple[str, object, threading.Thread]:
    """uvicorn with the settings of ``homesim serve`` in a thread; `config` goes to
    `uvicorn_config` (e.g. a short ``header_timeout``)."""
    import uvicorn

    from homesim.serve.server import uvicorn_config

    # Port 0: the OS picks a free port when uvicorn binds, so parallel runs cannot collide.
    app = app or create_app(static_dir=static_dir)
    server = uvicorn.Server(uvicorn_config(app, "127.0.0.1", 0, **config))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 20
    while not server.started:
        if time.monotonic() > deadline or not thread.is_alive():
            raise RuntimeError("uvicorn did not start")
        time.sleep(0.05)
    port = server.servers[0].sockets[0].getsockname()[1]
    return f"http://127.0.0.1:{port}", server, thread


@pytest.fixture(scope="session")
def live_server() -> Iterator[str]:
    """A real uvicorn server on a free loopback port, for the whole session."""
    url, server, thread = start_server()
    yield url
    server.should_exit = True  # type: ignore[attr-defined]
    thread.join(timeout=10)
