"""Built-in homes: the five VirtualHome apartments shipped with the package.

``scene1`` .. ``scene5`` are the full apartments with 3D boxes (for rendering);
``scene1_trimmed`` .. ``scene5_trimmed`` are the graphs the symbolic simulator was built
on, with room names as programs use them (``dining_room``, ``home_office``). They were
converted from the VirtualHome release by ``tools/convert_homes.py``.
"""

from __future__ import annotations

import difflib
from functools import lru_cache
from importlib import resources

from homesim.errors import GraphError
from homesim.world.graph import EnvironmentGraph

_PACKAGE = "homesim.world.builtin"


def home_names() -> list[str]:
    """Names of the built-in homes, e.g. ``["scene1", "scene1_trimmed", ...]``."""
    names = [p.name.removesuffix(".json.gz") for p in resources.files(_PACKAGE).iterdir()
             if p.name.endswith(".json.gz")]
    return sorted(names)


@lru_cache(maxsize=16)
def load_home(name: str) -> EnvironmentGraph:
    """Load a built-in home by name (cached: graphs are read-only)."""
    names = home_names()
    if name not in names:
        close = difflib.get_close_matches(name, names, n=1)
        hint = f" (did you mean {close[0]}?)" if close else ""
        raise GraphError(f"unknown home {name!r}{hint}; built-in homes: {', '.join(names)}")
    with resources.as_file(resources.files(_PACKAGE) / f"{name}.json.gz") as path:
        return EnvironmentGraph.load(path)
