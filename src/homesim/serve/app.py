"""The app factory: API routers, error handlers, the body size limit and the editor."""

from __future__ import annotations

from pathlib import Path

from fastapi import FastAPI

from homesim.serve import homes, programs
from homesim.serve.errors import install_error_handlers
from homesim.serve.limits import MAX_BODY_BYTES, BodySizeLimit
from homesim.serve.static import default_static_dir, mount_editor


def create_app(static_dir: Path | None = None,
               max_body_bytes: int = MAX_BODY_BYTES) -> FastAPI:
    """Build the editor's web app.

    Args:
        static_dir: the built editor (default: the package's ``static/``).
        max_body_bytes: larger request bodies get 413.
    """
    from homesim import __version__

    app = FastAPI(title="homesim editor API", version=__version__,
                  description="Check and run homesim programs; serves the block editor.")
    install_error_handlers(app)
    app.include_router(homes.router)
    app.include_router(programs.router)
    app.add_middleware(BodySizeLimit, max_bytes=max_body_bytes)
    mount_editor(app, static_dir or default_static_dir())  # last: "/" catches the rest
    return app
