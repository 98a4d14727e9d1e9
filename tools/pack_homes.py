"""Write the column file of every built-in home from its VirtualHome JSON.

Each ``src/homesim/world/builtin/<name>.json.gz`` is loaded with full validation
(`EnvironmentGraph.load`), written as ``<name>.columns.json.gz`` (`homesim.world.columns`,
what `load_home` reads) and read back to check that it gives the same graph.
``tools/convert_homes.py`` runs this after converting; run it by hand after editing a
home's JSON (tests/world/test_columns.py fails until then). From the repo root:

    python tools/pack_homes.py
"""

from __future__ import annotations

from pathlib import Path

from homesim.world.columns import SUFFIX, read_columns, write_columns
from homesim.world.graph import EnvironmentGraph

BUILTIN = Path(__file__).resolve().parents[1] / "src" / "homesim" / "world" / "builtin"


def pack_all(folder: Path = BUILTIN) -> None:
    """Write `<name>.columns.json.gz` beside every `<name>.json.gz` of `folder`."""
    for source in sorted(folder.glob("*.json.gz")):
        if source.name.endswith(SUFFIX):
            continue
        graph = EnvironmentGraph.load(source)
        target = source.with_name(source.name.removesuffix(".json.gz") + SUFFIX)
        write_columns(graph, target)
        assert read_columns(target).to_dict() == graph.to_dict(), f"{target}: round trip"
        print(f"{source.name} ({source.stat().st_size // 1024} KiB) -> {target.name} "
              f"({target.stat().st_size // 1024} KiB)")


if __name__ == "__main__":
    pack_all()
