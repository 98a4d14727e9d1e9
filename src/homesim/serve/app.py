"""The app factory: API routers, error handlers, request limits, workers and the editor."""

from __future__ import annotations

import contextlib
import sys
import threading
from collections.abc import AsyncIterator, Iterable
from contextlib import asynccontextmanager
from pathlib import Path

from fastapi import FastAPI

from homesim.limits import BODY_TIMEOUT_S
from homesim.serve import homes, programs, renders, writer
from homesim.serve.errors import ApiError, CatchBugs, SafeJSONResponse, install_error_handlers
from homesim.serve.hosts import LOOPBACK_HOSTS, HostCheck
from homesim.serve.limits import MAX_BODY_BYTES, BodySizeLimit, LargeBodyGate
from homesim.serve.pool import ProgramPool, WriterPool, settle_memory
from homesim.serve.static import default_static_dir, mount_editor
from homesim.serve.workers import worker_context

SWITCH_INTERVAL_S = 0.0005
"""How long a thread of the server holds the interpreter lock while another waits for it
(Python's default: 5 ms). Small requests run in their own thread (`run_small`) beside
the event loop: each hand-over would cost them up to the whole interval."""


def warm_up() -> None:
    """Start the fork server now (it imports `PRELOAD`, a second or two), not on the
    first request that needs a worker; and look for the renderer (imports mujoco).
    Here, not in `workers`, which the routers' modules import."""
    with contextlib.suppress(ApiError):  # no renderer: POST /api/render answers 501
        programs.keyframe_renderer()
    if worker_context().get_start_method() == "forkserver":
        from multiprocessing import forkserver

        forkserver.ensure_running()
    settle_memory()


@asynccontextmanager
async def _lifespan(app: FastAPI) -> AsyncIterator[None]:
    before = sys.getswitchinterval()
    sys.setswitchinterval(SWITCH_INTERVAL_S)  # process-wide: put back when the app stops
    threading.Thread(target=warm_up, name="homesim-warm-up", daemon=True).start()
    yield
    sys.setswitchinterval(before)
    app.state.renders.close()
    app.state.programs.close()
    app.state.writer.close()


def create_app(static_dir: Path | None = None,
               max_body_bytes: int = MAX_BODY_BYTES,
               body_timeout: float = BODY_TIMEOUT_S,
               allowed_hosts: Iterable[str] = LOOPBACK_HOSTS,
               render_jobs: renders.RenderJobs | None = None,
               writer_pool: WriterPool | None = None) -> FastAPI:
    """Build the editor's web app.

    Args:
        static_dir: the built editor (default: the package's ``static/``).
        max_body_bytes: larger request bodies get 413.
        body_timeout: bodies not received within this many seconds get 408.
        allowed_hosts: Host header names served (default: loopback names; ``*``: any).
        render_jobs: the render queue (default: one with the limits of `homesim.limits`).
        writer_pool: the writer workers (default: the limits of `homesim.limits`).
    """
    from homesim.version import __version__

    app = FastAPI(title="homesim editor API", version=__version__, lifespan=_lifespan,
                  default_response_class=SafeJSONResponse,
                  description="Check and run homesim programs; serves the block editor.")
    app.state.programs = ProgramPool()
    app.state.writer = writer_pool or WriterPool()
    app.state.renders = render_jobs or renders.RenderJobs()
    install_error_handlers(app)
    app.include_router(homes.router)
    app.include_router(programs.router)
    app.include_router(renders.router)
    app.include_router(writer.router)
    app.add_middleware(BodySizeLimit, max_bytes=max_body_bytes, timeout=body_timeout)
    app.add_middleware(LargeBodyGate)  # outside BodySizeLimit: waiting bodies stay unread
    app.add_middleware(HostCheck, allowed=allowed_hosts)
    app.add_middleware(CatchBugs)  # last: outermost, so a bug anywhere answers 500
    mount_editor(app, static_dir or default_static_dir())  # last: "/" catches the rest
    return app
