"""Serving the built editor (``web/`` built by Vite into this package's ``static/``)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from fastapi import FastAPI
from fastapi.responses import HTMLResponse
from fastapi.staticfiles import StaticFiles

BUILD_HINT = ("the editor is not built: run 'make setup' in the homesim checkout "
              "(or 'cd web && npm install && npm run build')")


def default_static_dir() -> Path:
    """Where the build lands: ``src/homesim/serve/static`` (package data in a wheel)."""
    return Path(str(resources.files("homesim.serve") / "static"))


def is_built(static_dir: Path) -> bool:
    return (static_dir / "index.html").is_file()


def mount_editor(app: FastAPI, static_dir: Path) -> None:
    """Serve the editor at ``/``, or a page saying how to build it."""
    if is_built(static_dir):
        app.mount("/", StaticFiles(directory=static_dir, html=True), name="editor")
        return

    @app.get("/", response_class=HTMLResponse, include_in_schema=False)
    def not_built() -> str:
        return (f"<!doctype html><title>homesim editor</title><p>homesim: {BUILD_HINT}. "
                "The JSON API is at <a href='/docs'>/docs</a>.</p>")
