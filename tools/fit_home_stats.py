"""Fit the statistics procedural homes are drawn from, from the five built-in apartments.

For each of the paper's 8 room kinds it records room sizes (x, z extents of the room's
floor tiles, walls included: the outer size a generated room is drawn with) and the range
of floor areas (the tiles' area: what a generated room's floor must stay within), and
for each object class seen in rooms of its source kinds: how often a room holds it
(``p``), how many when it does (``counts``), how it is held up (``mount``: ``floor``,
``wall``, ``ceiling`` or ``item`` for things ON or INSIDE furniture, with the parent
classes seen), and per class its median box size, height, category, properties, states
and prefab. The four kinds the apartments lack are derived from kinds they have,
restricted to a class list (``RECIPES``). Writes src/homesim/world/procedural/stats.json.

    python tools/fit_home_stats.py
"""

from __future__ import annotations

import json
import statistics
from collections import Counter, defaultdict
from pathlib import Path

from homesim.world import EnvironmentGraph, load_home

OUT = Path(__file__).resolve().parents[1] / "src/homesim/world/procedural/stats.json"
STRUCTURE = frozenset({"Rooms", "Walls", "Floor", "Floors", "Ceiling", "Doors", "Windows",
                       "Characters"})
SKIP = frozenset({"clothespile", "closetdrawer", "hanger", "stall", "curtains"})
"""Parts of composite prefabs (drawers, hangers, shower stall walls) that need their
parent's geometry to make sense; generated homes leave them out."""

OFFICE = ["desk", "chair", "bookshelf", "computer", "cpuscreen", "keyboard", "mouse",
          "mousemat", "cabinet", "wallpictureframe", "ceilinglamp", "walllamp", "tablelamp",
          "lightswitch", "powersocket", "rug", "radio", "book", "folder", "paper", "mug",
          "cellphone", "photoframe", "box", "papertray", "orchid", "candle"]
RECIPES: dict[str, dict] = {
    # kind: room class in generated homes, source kinds, class allow-list, size scale
    "living_room": {"class": "livingroom", "from": ["livingroom"], "scale": 1.0},
    "kitchen": {"class": "kitchen", "from": ["kitchen"], "scale": 1.0},
    "bedroom": {"class": "bedroom", "from": ["bedroom"], "scale": 1.0},
    "bathroom": {"class": "bathroom", "from": ["bathroom"], "scale": 1.0},
    "dining_room": {"class": "dining_room", "from": ["kitchen"], "scale": 0.75, "only": [
        "kitchentable", "bench", "chair", "cabinet", "bookshelf", "wallshelf",
        "wallpictureframe", "ceilinglamp", "walllamp", "rug", "lightswitch", "powersocket",
        "candle", "orchid", "plate", "waterglass", "wineglass", "cutleryfork", "cutleryknife",
        "dishbowl", "condimentbottle", "condimentshaker", "book", "photoframe", "clock"]},
    "home_office": {"class": "home_office", "from": ["livingroom", "bedroom"], "scale": 0.6,
                    "only": OFFICE},
    "kids_bedroom": {"class": "kids_bedroom", "from": ["bedroom"], "scale": 0.75},
    "entrance_hall": {"class": "entrance_hall", "from": ["livingroom", "bedroom"],
                      "scale": 0.45, "only": [
                          "closet", "cabinet", "bookshelf", "rug", "wallpictureframe",
                          "ceilinglamp", "walllamp", "lightswitch", "powersocket",
                          "slippers", "box", "photoframe", "orchid", "candle"]},
}


def _support(g: EnvironmentGraph, n) -> tuple[str, list[tuple[str, str]]]:
    """How a node is held up: mount kind and (parent class, relation) pairs."""
    parents = []
    for rel in ("ON", "INSIDE"):
        for t in g.targets(n.id, rel):
            p = g.node(t)
            if p.category not in STRUCTURE and p.class_name not in SKIP | {"rug"}:
                parents.append((p.class_name, rel))
    if parents:
        return "item", parents
    b = n.bounding_box
    bottom = b.center[1] - b.size[1] / 2
    if bottom < 0.15:
        return "floor", []
    if b.center[1] + b.size[1] / 2 > 2.3 and b.size[1] < 0.8:
        return "ceiling", []
    return "wall", []


def _floor(g: EnvironmentGraph, room: int) -> tuple[list[float], list[float], float]:
    """(x, z) lower and upper corners of a room's floor tiles and their area (tiles
    listed twice counted once)."""
    seen, lo, hi, area = set(), [1e9, 1e9], [-1e9, -1e9], 0.0
    for nid in g.sources(room, "INSIDE"):
        n = g.node(nid)
        if n.class_name != "floor" or n.bounding_box is None:
            continue
        (cx, _, cz), (sx, _, sz) = n.bounding_box.center, n.bounding_box.size
        key = (round(cx, 2), round(cz, 2), round(sx, 2), round(sz, 2))
        if key in seen:
            continue
        seen.add(key)
        area += sx * sz
        lo = [min(lo[0], cx - sx / 2), min(lo[1], cz - sz / 2)]
        hi = [max(hi[0], cx + sx / 2), max(hi[1], cz + sz / 2)]
    return lo, hi, area


def main() -> None:
    per_kind: dict[str, list[dict[str, list]]] = defaultdict(list)  # kind -> rooms
    sizes: dict[str, list[list[float]]] = defaultdict(list)
    areas: dict[str, list[float]] = defaultdict(list)
    boxes: dict[str, list[tuple[float, ...]]] = defaultdict(list)
    info: dict[str, Counter] = defaultdict(Counter)
    for i in range(1, 6):
        g = load_home(f"scene{i}")
        for room in g.rooms():
            lo, hi, area = _floor(g, room.id)
            sizes[room.class_name].append([round(hi[0] - lo[0], 2), round(hi[1] - lo[1], 2)])
            areas[room.class_name].append(round(area, 2))
            found: dict[str, list] = defaultdict(list)
            for nid in g.sources(room.id, "INSIDE"):
                n = g.node(nid)
                if n.category in STRUCTURE or n.class_name in SKIP or not n.bounding_box:
                    continue
                mount, parents = _support(g, n)
                found[n.class_name].append((mount, parents))
                nb = n.bounding_box
                boxes[n.class_name].append((*nb.size, nb.center[1]))
                info[n.class_name][json.dumps([n.category, sorted(n.properties),
                                               sorted(n.states), n.prefab_name])] += 1
            per_kind[room.class_name].append(found)
    classes = {}
    for cls, seen in sorted(info.items()):
        category, properties, states, prefab = json.loads(seen.most_common(1)[0][0])
        sx, sy, sz, cy = (statistics.median(v) for v in zip(*boxes[cls], strict=True))
        classes[cls] = {"category": category, "properties": properties, "states": states,
                        "prefab": prefab, "size": [round(max(sx, sz), 3), round(sy, 3),
                                                   round(min(sx, sz), 3)],
                        "height": round(cy - sy / 2, 3)}
    kinds = {}
    for kind, recipe in RECIPES.items():
        rooms = [r for src in recipe["from"] for r in per_kind[src]]
        only = set(recipe.get("only", classes))
        objects = []
        for cls in sorted({c for r in rooms for c in r} & only):
            present = [r[cls] for r in rooms if cls in r]
            mounts = Counter(m for entries in present for m, _ in entries)
            parents = Counter(f"{p}|{rel}" for entries in present for _, ps in entries
                              for p, rel in ps if p in only)
            mount = mounts.most_common(1)[0][0]
            if mount == "item" and not parents:
                mount = "floor"
            objects.append({"class": cls, "p": round(len(present) / len(rooms), 3),
                            "counts": sorted(len(e) for e in present), "mount": mount,
                            "parents": dict(sorted(parents.items()))})
        scale = recipe["scale"]
        room_sizes = [[round(w * scale ** 0.5, 2), round(d * scale ** 0.5, 2)]
                      for src in recipe["from"] for w, d in sizes[src]]
        src_areas = [a * scale for src in recipe["from"] for a in areas[src]]
        kinds[kind] = {"class": recipe["class"], "sizes": room_sizes, "objects": objects,
                       "area": [round(min(src_areas), 2), round(max(src_areas), 2)]}
    OUT.write_text(json.dumps({"source": "tools/fit_home_stats.py on scene1..scene5",
                               "kinds": kinds, "classes": classes}, indent=1,
                              sort_keys=True) + "\n")
    print(f"wrote {OUT} ({len(classes)} classes, "
          + ", ".join(f"{k}: {len(v['objects'])}" for k, v in kinds.items()) + ")")


if __name__ == "__main__":
    main()
