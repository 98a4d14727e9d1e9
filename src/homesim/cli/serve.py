"""`homesim serve`: run the block editor and its JSON API (FastAPI + uvicorn)."""

from __future__ import annotations

import multiprocessing.util
import os
import shutil
import signal
import sys
import tempfile
from pathlib import Path
from typing import Annotated, Any

import typer

from homesim.cli.common import console
from homesim.errors import HomesimError
from homesim.processes import Reaper

LOOPBACK = "127.0.0.1"


def served_names(host: str) -> list[str]:
    """The Host name of the listening address itself (not of a wildcard address).

    >>> served_names("192.168.1.5"), served_names("::1"), served_names("0.0.0.0")
    (['192.168.1.5'], ['[::1]'], [])
    """
    if host in ("0.0.0.0", "::", ""):
        return []
    return [f"[{host}]" if ":" in host else host]


def serve(
    host: Annotated[str, typer.Option(
        help="Address to listen on; the default only accepts connections from this "
             "machine. Use 0.0.0.0 to share it on your network (no authentication!).")]
    = LOOPBACK,
    port: Annotated[int, typer.Option(help="TCP port.")] = 8000,
    log_level: Annotated[str, typer.Option(help="uvicorn log level.")] = "warning",
    allowed_host: Annotated[list[str] | None, typer.Option(
        help="A Host name the server answers to (repeatable; '*' for any). Default: "
             "localhost, 127.0.0.1, [::1] and the --host address. Other names get 400, "
             "which stops DNS-rebinding pages from reaching the server.")] = None,
) -> None:
    """Serve the block editor and the JSON API (docs at /docs)."""
    try:
        import uvicorn

        from homesim.serve import create_app
        from homesim.serve.hosts import LOOPBACK_HOSTS
        from homesim.serve.renders import RenderJobs
        from homesim.serve.static import BUILD_HINT, default_static_dir, is_built
    except ModuleNotFoundError as e:
        # No brackets in the text: the CLI prints errors as rich markup.
        raise HomesimError(f"'homesim serve' needs the serve extra ({e}); install "
                           "homesim with its 'serve' extra (fastapi, uvicorn)") from None
    if not 0 < port < 65536:
        raise HomesimError(f"--port {port}: not a TCP port (1-65535)")
    if not is_built(default_static_dir()):
        console.print(f"[yellow]note[/]: {BUILD_HINT}; serving the API only")
    console.print(f"homesim editor on [bold]http://{host}:{port}/[/] (API docs at /docs); "
                  "Ctrl-C stops it")
    hosts = allowed_host or [*LOOPBACK_HOSTS, *served_names(host)]
    # Killed with SIGKILL, the server runs no clean-up: the reaper then stops its workers
    # (fork server, resource tracker, render and pool workers) and removes the frames.
    with Reaper() as reaper:
        frames = Path(tempfile.mkdtemp(prefix="homesim-render-"))
        reaper.remove_on_death(frames)
        reaper.remove_on_death(multiprocessing.util.get_temp_dir())  # the fork server's
        try:
            _run(uvicorn, create_app(allowed_hosts=hosts, render_jobs=RenderJobs(root=frames)),
                 host, port, log_level, reaper)
        finally:
            shutil.rmtree(frames, ignore_errors=True)


def _run(uvicorn: Any, app: Any, host: str, port: int, log_level: str, reaper: Reaper
         ) -> None:
    from homesim.serve.server import uvicorn_config

    server = uvicorn.Server(uvicorn_config(app, host, port, log_level))
    try:
        server.run()
    except OSError as e:
        raise HomesimError(f"cannot listen on {host}:{port} ({e.strerror or e})") from None
    except (SystemExit, KeyboardInterrupt) as e:  # uvicorn re-raises SIGTERM / Ctrl-C
        if server.started:
            exit_now(128 + signal.SIGINT if isinstance(e, KeyboardInterrupt)
                     else e.code if isinstance(e.code, int) else 1, reaper)
        raise
    if server.started:
        exit_now(0, reaper)


def exit_now(code: int, reaper: Reaper | None = None) -> None:
    """End a server that has shut down (workers stopped, frames deleted) without the
    interpreter's teardown of its ~800 modules (mujoco, numpy, ...), which takes 0.5-3 s
    on a busy machine and would make a stop slower than `SHUTDOWN_GRACE_S` promises."""
    if reaper is not None:
        reaper.close()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
