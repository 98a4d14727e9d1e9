"""Built-in homes: the five VirtualHome apartments shipped with the package.

``scene1`` .. ``scene5`` are the full apartments with 3D boxes (for rendering);
``scene1_trimmed`` .. ``scene5_trimmed`` are the graphs the symbolic simulator was built
on, with room names as programs use them (``dining_room``, ``home_office``). They were
converted from the VirtualHome release by ``tools/convert_homes.py``, which fixes one
fault of the release: in scene1 the character's INSIDE edge named bathroom 1 while its box
(and its CLOSE edges) are in bedroom 67; the edge now follows the box, so ``homesim run``
and the rendered video agree (`character_room_problem` checks every built-in home).

Each home ships as a column file (``<name>.columns.json.gz``, `homesim.world.columns`),
which loads about 4x faster than its VirtualHome JSON; ``tools/pack_homes.py`` writes
them from the JSON (``<name>.json.gz``, kept in the source tree, not in the wheel), and a
test checks that both give exactly the same graph. A home with only its JSON still loads.
"""

from __future__ import annotations

import difflib
from functools import lru_cache
from importlib import resources

from homesim.errors import GraphError
from homesim.world.columns import SUFFIX, read_columns
from homesim.world.graph import EnvironmentGraph
from homesim.world.vocab import INSIDE

_PACKAGE = "homesim.world.builtin"
_JSON = ".json.gz"


def home_names() -> list[str]:
    """Names of the built-in homes, e.g. ``["scene1", "scene1_trimmed", ...]``."""
    names = {p.name.removesuffix(SUFFIX).removesuffix(_JSON)
             for p in resources.files(_PACKAGE).iterdir() if p.name.endswith(_JSON)}
    return sorted(names)


def load_builtin(name: str) -> EnvironmentGraph:
    """A built-in home read afresh (not cached): from its column file, else its JSON."""
    names = home_names()
    if name not in names:
        close = difflib.get_close_matches(name, names, n=1)
        hint = f" (did you mean {close[0]}?)" if close else ""
        raise GraphError(f"unknown home {name!r}{hint}; built-in homes: {', '.join(names)}")
    folder = resources.files(_PACKAGE)
    columns = folder / f"{name}{SUFFIX}"
    if columns.is_file():
        with resources.as_file(columns) as path:
            return read_columns(path)
    with resources.as_file(folder / f"{name}{_JSON}") as path:
        return EnvironmentGraph.load(path)


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
    return load_builtin(name)


def rooms_holding_box(graph: EnvironmentGraph, node_id: int) -> list[int]:
    """Rooms whose box holds the centre of the node's box on the floor (x, z), by id."""
    box = graph.node(node_id).bounding_box
    if box is None:
        return []
    x, _, z = box.center
    return [r.id for r in graph.rooms() if r.bounding_box is not None
            and abs(x - r.bounding_box.center[0]) <= r.bounding_box.size[0] / 2
            and abs(z - r.bounding_box.center[2]) <= r.bounding_box.size[2] / 2]


def character_room_problem(graph: EnvironmentGraph) -> str | None:
    """One line if the character's room edge and its box disagree (both given), else None."""
    char = graph.character_id
    if char is None or graph.node(char).bounding_box is None:
        return None
    by_box = rooms_holding_box(graph, char)
    by_edge = sorted(graph.targets(char, INSIDE) & graph.room_ids)
    if by_box and by_edge and not set(by_box) & set(by_edge):
        edge = ", ".join(graph.node(r).label() for r in by_edge)
        box = ", ".join(graph.node(r).label() for r in by_box)
        return f"character {char} is INSIDE {edge} but its box is in {box}"
    return None
