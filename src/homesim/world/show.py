"""A labelled top-down plan of a home (rooms, furniture, doors, windows) as a PNG.

Works for every home with boxes, built-in or generated. x runs right, z up; matplotlib is
imported only here (the ``stats`` extra)."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

from homesim.errors import HomesimError
from homesim.files import write_bytes
from homesim.world.graph import EnvironmentGraph, Node

_SKIP = frozenset({"Rooms", "Walls", "Floor", "Floors", "Ceiling", "Characters", "Props",
                   "Food"})
"""Categories left out of the plan (small things would clutter it)."""
_COLOURS = ["#fde2c8", "#d6ecd2", "#d4e4f7", "#f6d5e5", "#efe8c4", "#dcd3f0", "#cdeeea",
            "#f2d0c4"]


Rect = tuple[float, float, float, float]
"""A footprint: x, z of the low corner, then width (x) and depth (z)."""


def _rect(n: Node) -> Rect | None:
    b = n.bounding_box
    if b is None:
        return None
    return (b.center[0] - b.size[0] / 2, b.center[2] - b.size[2] / 2, b.size[0], b.size[2])


def _pyplot() -> tuple[Any, Any]:
    """matplotlib's pyplot (headless) and Rectangle, or a one-line error when missing."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.patches import Rectangle
    except ImportError:
        raise HomesimError("homes show needs matplotlib: pip install 'homesim[stats]'") from None
    return plt, Rectangle


def _room_rects(graph: EnvironmentGraph) -> list[tuple[Node, Rect]]:
    """Every room with a box, with its footprint; an error when there is none."""
    rooms = [(r, rect) for r in graph.rooms() if (rect := _rect(r)) is not None]
    if not rooms:
        raise HomesimError("this home has no boxes to draw (a trimmed home?)")
    return rooms


def _draw_rooms(ax: Any, box: Any, rooms: list[tuple[Node, Rect]]) -> None:
    """Coloured room floors with their names along the top edge."""
    for k, (room, (x, z, w, d)) in enumerate(rooms):
        ax.add_patch(box((x, z), w, d, facecolor=_COLOURS[k % len(_COLOURS)],
                         edgecolor="black", linewidth=2, zorder=0))
        ax.text(x + w / 2, z + d - 0.3, room.class_name.upper(), ha="center", va="top",
                fontsize=10, weight="bold", zorder=5)


def _on_floor(n: Node, r: Rect) -> bool:
    """Whether `n` is big furniture standing on the floor (or a rug), worth drawing."""
    b = n.bounding_box
    if b is None:
        return False
    low = b.center[1] - b.size[1] / 2
    return (r[2] * r[3] >= 0.12 and low < 0.3
            and (n.category != "Decor" or n.class_name == "rug"))


def _draw_furniture(ax: Any, box: Any, n: Node, r: Rect) -> None:
    """One piece of furniture: a grey labelled block, or a dotted outline for a rug."""
    x, z, w, d = r
    flat = n.class_name == "rug"
    ax.add_patch(box((x, z), w, d, facecolor="none" if flat else "#8899aa",
                     alpha=0.6, edgecolor="#334455",
                     linestyle=":" if flat else "-", zorder=1 if flat else 2))
    if not flat:
        ax.text(x + w / 2, z + d / 2, n.class_name, ha="center", va="center",
                fontsize=6, zorder=4)


def _draw_objects(ax: Any, box: Any, graph: EnvironmentGraph) -> None:
    """Doors, windows and floor-standing furniture."""
    fills = {"Doors": "saddlebrown", "Windows": "deepskyblue"}
    for n in graph:
        r = _rect(n)
        if r is None or n.category in _SKIP:
            continue
        x, z, w, d = r
        if n.category in fills:
            ax.add_patch(box((x, z), w, d, facecolor=fills[n.category], zorder=3))
        elif _on_floor(n, r):
            _draw_furniture(ax, box, n, r)


def _draw_character(ax: Any, graph: EnvironmentGraph) -> None:
    """A red star where the character stands, when it has a box."""
    char = graph.character_id
    b = graph.node(char).bounding_box if char is not None else None
    if b is not None:
        ax.plot(b.center[0], b.center[2], "r*", markersize=14, zorder=6)


def _frame(ax: Any, rooms: list[tuple[Node, Rect]], title: str) -> None:
    """Limits round the rooms (0.5 m margin), equal aspect, axis labels and title."""
    xs = [v for _, r in rooms for v in (r[0], r[0] + r[2])]
    zs = [v for _, r in rooms for v in (r[1], r[1] + r[3])]
    ax.set_xlim(min(xs) - 0.5, max(xs) + 0.5)
    ax.set_ylim(min(zs) - 0.5, max(zs) + 0.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title(title)


def draw_plan(graph: EnvironmentGraph, path: str | Path, title: str = "") -> None:
    """Draw the plan of `graph` into a PNG at `path`."""
    plt, box = _pyplot()
    rooms = _room_rects(graph)
    fig, ax = plt.subplots(figsize=(12, 9))
    _draw_rooms(ax, box, rooms)
    _draw_objects(ax, box, graph)
    _draw_character(ax, graph)
    _frame(ax, rooms, title or f"{len(graph)} objects, {len(rooms)} rooms")
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    plt.close(fig)
    write_bytes(Path(path), buf.getvalue())
