"""A labelled top-down plan of a home (rooms, furniture, doors, windows) as a PNG.

Works for every home with boxes, built-in or generated. x runs right, z up; matplotlib is
imported only here (the ``stats`` extra)."""

from __future__ import annotations

from pathlib import Path

from homesim.errors import HomesimError
from homesim.files import write_bytes
from homesim.world.graph import EnvironmentGraph, Node

_SKIP = frozenset({"Rooms", "Walls", "Floor", "Floors", "Ceiling", "Characters", "Props",
                   "Food"})
"""Categories left out of the plan (small things would clutter it)."""
_COLOURS = ["#fde2c8", "#d6ecd2", "#d4e4f7", "#f6d5e5", "#efe8c4", "#dcd3f0", "#cdeeea",
            "#f2d0c4"]


def _rect(n: Node) -> tuple[float, float, float, float] | None:
    b = n.bounding_box
    if b is None:
        return None
    return (b.center[0] - b.size[0] / 2, b.center[2] - b.size[2] / 2, b.size[0], b.size[2])


def draw_plan(graph: EnvironmentGraph, path: str | Path, title: str = "") -> None:
    """Draw the plan of `graph` into a PNG at `path`."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.patches import Rectangle
    except ImportError:
        raise HomesimError("homes show needs matplotlib: pip install 'homesim[stats]'") from None
    rooms = [r for r in graph.rooms() if r.bounding_box is not None]
    if not rooms:
        raise HomesimError("this home has no boxes to draw (a trimmed home?)")
    fig, ax = plt.subplots(figsize=(12, 9))
    for k, room in enumerate(rooms):
        x, z, w, d = _rect(room)  # type: ignore[misc]
        ax.add_patch(Rectangle((x, z), w, d, facecolor=_COLOURS[k % len(_COLOURS)],
                               edgecolor="black", linewidth=2, zorder=0))
        ax.text(x + w / 2, z + d - 0.3, room.class_name.upper(), ha="center", va="top",
                fontsize=10, weight="bold", zorder=5)
    for n in graph:
        r = _rect(n)
        if r is None or n.category in _SKIP:
            continue
        x, z, w, d = r
        if n.category == "Doors":
            ax.add_patch(Rectangle((x, z), w, d, facecolor="saddlebrown", zorder=3))
        elif n.category == "Windows":
            ax.add_patch(Rectangle((x, z), w, d, facecolor="deepskyblue", zorder=3))
        elif (w * d >= 0.12 and n.bounding_box.center[1] - n.bounding_box.size[1] / 2 < 0.3
              and (n.category != "Decor" or n.class_name == "rug")):
            flat = n.class_name == "rug"
            ax.add_patch(Rectangle((x, z), w, d, facecolor="none" if flat else "#8899aa",
                                   alpha=0.6, edgecolor="#334455",
                                   linestyle=":" if flat else "-", zorder=1 if flat else 2))
            if not flat:
                ax.text(x + w / 2, z + d / 2, n.class_name, ha="center", va="center",
                        fontsize=6, zorder=4)
    char = graph.character_id
    if char is not None and graph.node(char).bounding_box is not None:
        c = graph.node(char).bounding_box.center
        ax.plot(c[0], c[2], "r*", markersize=14, zorder=6)
    xs = [v for r in rooms for v in (_rect(r)[0], _rect(r)[0] + _rect(r)[2])]
    zs = [v for r in rooms for v in (_rect(r)[1], _rect(r)[1] + _rect(r)[3])]
    ax.set_xlim(min(xs) - 0.5, max(xs) + 0.5)
    ax.set_ylim(min(zs) - 0.5, max(zs) + 0.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title(title or f"{len(graph)} objects, {len(rooms)} rooms")
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    plt.close(fig)
    write_bytes(Path(path), buf.getvalue())
