"""The one place that picks the OpenGL backend and imports mujoco.

`MUJOCO_GL` must be set before mujoco is first imported, so every module of
`homesim.render` imports mujoco from here. When the variable is unset we pick `egl`
where a GPU render node exists and `osmesa` (software, Debian `libosmesa6`) otherwise.
"""

from __future__ import annotations

import os
from pathlib import Path


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

__all__ = ["BACKEND", "gl_available", "mujoco"]

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
