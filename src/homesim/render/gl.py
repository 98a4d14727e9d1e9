"""The one place that picks the OpenGL backend and imports mujoco.

`MUJOCO_GL` must be set before mujoco is first imported, so every module of
`homesim.render` imports mujoco from here. When the variable is unset we pick `egl`
where a GPU render node exists and `osmesa` (software, Debian `libosmesa6`) otherwise.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import threading
from pathlib import Path
from typing import Any


def _default_backend() -> str:
    has_gpu = Path("/dev/nvidia0").exists() or Path("/dev/dri/renderD128").exists()
    return "egl" if has_gpu and not os.environ.get("DISPLAY") else "osmesa"


BACKEND = os.environ.setdefault("MUJOCO_GL", _default_backend()).lower()
"""The OpenGL backend in use (`osmesa`, `egl`, `glfw`, ...)."""

try:
    import mujoco
except ImportError as e:  # pragma: no cover - depends on the installed extras
    raise ImportError("rendering needs the 'render' extra: pip install 'homesim[render]' "
                      f"({e})", name="mujoco") from None

__all__ = ["BACKEND", "gl_available", "mujoco", "thread_context"]

_gl_ok: bool | None = None


def gl_available() -> bool:
    """True when an offscreen OpenGL context can be created with the chosen backend."""
    global _gl_ok
    if _gl_ok is None:
        try:
            ctx = mujoco.GLContext(16, 16)
            ctx.make_current()
            ctx.free()
            _gl_ok = True
        except Exception:  # any backend failure means: no GL here
            _gl_ok = False
    return _gl_ok


_threads = threading.local()
_contexts: list[Any] = []  # every thread's context, freed at exit
_lock = threading.Lock()
CONTEXT_SIDE = 64
"""Pixels per side of the context's own buffer: renderers draw into MuJoCo's offscreen
framebuffer (sized by the model), never into this one."""


def thread_context() -> Any:
    """This thread's offscreen OpenGL context, made current. It is created once and kept
    (freed at exit): every `Renderer` of the thread shares it, so a renderer after the
    first creates no context, and llvmpipe (OSMesa) reuses the shaders it compiled for the
    first instead of compiling them again (~80 ms per renderer)."""
    ctx = getattr(_threads, "context", None)
    if ctx is None:
        ctx = mujoco.GLContext(CONTEXT_SIDE, CONTEXT_SIDE)
        _threads.context = ctx
        with _lock:
            _contexts.append(ctx)
    ctx.make_current()
    return ctx


@atexit.register
def _free_contexts() -> None:
    """Free the contexts before the interpreter tears down the modules their `__del__`
    needs (else it prints an ignored exception at exit)."""
    with _lock:
        while _contexts:
            ctx = _contexts.pop()
            with contextlib.suppress(Exception):  # at exit: nothing more to do about it
                ctx.free()
