"""Convert the VirtualHome apartments of ../shared/data into homesim's built-in homes.

Each scene is validated by `EnvironmentGraph.from_dict` and written, canonically sorted
and gzip-compressed, to src/homesim/world/builtin/<name>.json.gz. Run from the repo root:

    python tools/convert_homes.py [../shared/data/virtualhome/scenes]
"""

from __future__ import annotations

import sys
from pathlib import Path

from homesim.world.graph import EnvironmentGraph

OUT = Path(__file__).resolve().parents[1] / "src" / "homesim" / "world" / "builtin"


def main(scenes: Path) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    for path in sorted(scenes.glob("scene*.json")):
        graph = EnvironmentGraph.load(path)
        target = OUT / (path.stem + ".json.gz")
        graph.save(target)
        print(f"{path.name}: {len(graph)} nodes, {graph.num_edges()} edges -> {target.name} "
              f"({target.stat().st_size // 1024} KiB)")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "../shared/data/virtualhome/scenes"))
