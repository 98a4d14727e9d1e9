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


GENERATED_PREFIX = "gen-"
"""``gen-42`` names the home `homesim.world.procedural.generate_home` makes from seed 42."""


def is_generated(name: str) -> bool:
    """Whether `name` names a generated home: ``gen-`` and a seed of up to 9 digits."""
    seed = name.removeprefix(GENERATED_PREFIX)
    return name.startswith(GENERATED_PREFIX) and seed.isascii() and seed.isdigit() and (
        len(seed) <= 9)


def open_home(name_or_path: str) -> EnvironmentGraph:
    """A home by name (`load_home`) or from a file (a name ending in ``.json`` or
    ``.json.gz``, read afresh each time): what the CLI's ``--home`` takes."""
    if name_or_path.endswith((".json", ".json.gz")):
        return EnvironmentGraph.load(name_or_path)
    return load_home(name_or_path)


@lru_cache(maxsize=16)
def load_home(name: str) -> EnvironmentGraph:
    """A built-in home, or a generated one (``gen-SEED``), by name (cached: graphs are
    read-only). Never reads a file the name points to: servers pass names from clients."""
    if is_generated(name):
        from homesim.world.procedural import generate_home

        return generate_home(int(name.removeprefix(GENERATED_PREFIX)))
    names = home_names()
    if name not in names:
        close = difflib.get_close_matches(name, names, n=1)
        hint = f" (did you mean {close[0]}?)" if close else ""
        raise GraphError(f"unknown home {name!r}{hint}; built-in homes: {', '.join(names)}")
    with resources.as_file(resources.files(_PACKAGE) / f"{name}.json.gz") as path:
        return EnvironmentGraph.load(path)
