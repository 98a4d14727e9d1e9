"""Optional parts the API uses when they are installed: grounding and rendering.

Both are looked up at request time, so the server picks them up as soon as they land
(``homesim.ground.search``, ``homesim.render``) and says clearly when they are missing.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any


def _optional_function(module: str, name: str) -> tuple[Callable[..., Any] | None, str]:
    """`module.name` if the module imports, else None and why it does not."""
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as e:
        return None, f"{module} is not available ({e})"
    except ImportError as e:  # e.g. a compiled dependency without its system library
        return None, f"{module} cannot be imported ({e})"
    function = getattr(mod, name, None)
    if function is None:
        return None, f"{module} has no {name}()"
    return function, ""


def grounding() -> tuple[Callable[..., Any] | None, str]:
    """``ground(program, graph, seed=0) -> Grounding`` from `homesim.ground.search`, if any."""
    return _optional_function("homesim.ground.search", "ground")


def keyframe_renderer() -> tuple[Callable[..., Any] | None, str]:
    """``iter_keyframes(program, graph, *, width, height, seed)`` from `homesim.render`."""
    return _optional_function("homesim.render", "iter_keyframes")
