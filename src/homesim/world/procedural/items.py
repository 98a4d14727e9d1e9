"""Small objects on and in furniture: the parent is one seen for the class in the
built-in homes, else one the placement knowledge base allows, else any surface."""

from __future__ import annotations

import random

from homesim.world.class_table import classes_where
from homesim.world.classes import ClassKnowledge, class_names_for
from homesim.world.procedural.furnish import Entry
from homesim.world.procedural.parts import Part, box3, overlap3
from homesim.world.procedural.stats import class_info

FRONT_DEPTH = 0.55
"""Metres: what stands on or in a piece against a wall stands this near its front."""
HAND_HIGH = 1.8
"""Metres: no item stands higher than this (on top of a 2.2 m bookshelf, or on its top
shelf), where a person's hand does not take it."""


def place_items(rng: random.Random, parts: list[Part], room: int, entries: list[Entry],
                kb: ClassKnowledge) -> None:
    """Put every item of `entries` on or in something of the room (in up to 3 passes,
    so a faucet finds the sink placed before it); an item with no possible parent is
    left out."""
    here = _Room(parts, room)
    todo = [(e, n) for e in entries for n in range(e.count)]
    for _ in range(3):
        later = []
        for e, n in todo:
            if not _place(rng, here, e, kb, final=False):
                later.append((e, n))
        todo = later
    for e, _ in todo:
        _place(rng, here, e, kb, final=True)


class _Room:
    """The parts of one room that can hold items, by class, and what each holds."""

    def __init__(self, parts: list[Part], room: int):
        self.parts, self.room = parts, room
        self.holders: list[int] = []
        self.by_class: dict[str, list[int]] = {}
        self.held: dict[int, list[int]] = {}
        for k, p in enumerate(parts):
            if p.room == room and p.kind in ("fixture", "item"):
                self._note(k)
            if p.support is not None:
                self.held.setdefault(p.support[0], []).append(k)

    def _note(self, k: int) -> None:
        self.holders.append(k)
        self.by_class.setdefault(self.parts[k].cls, []).append(k)

    def add(self, part: Part) -> None:
        self.parts.append(part)
        k = len(self.parts) - 1
        self._note(k)
        assert part.support is not None
        self.held.setdefault(part.support[0], []).append(k)


def _candidates(here: _Room, e: Entry, kb: ClassKnowledge, final: bool
                ) -> list[tuple[int, str, int]]:
    """(part, relation, weight) for each part of the room that may hold the item, in part
    order per parent class."""
    out = []
    for key, n in e.parents.items():
        cls, rel = key.split("|")[:2]
        if cls != e.cls and _may_hold(cls, rel):
            out += [(k, rel, n) for k in here.by_class.get(cls, ())]
    if out or not final:
        return out
    parts = here.parts
    others = [k for k in here.holders if parts[k].cls != e.cls]
    for pl in kb.placements(e.cls):
        names = set(class_names_for(pl.destination, kb))
        out += [(k, pl.relation, 1) for k in others
                if parts[k].cls in names and _may_hold(parts[k].cls, pl.relation)]
    if out:
        return out
    surfaces = classes_where(tags="surface")
    return [(k, "ON", 1) for k in others if parts[k].cls in surfaces]


def _may_hold(parent: str, relation: str) -> bool:
    """Nothing goes ON what people sit or lie on: the simulator counts what is ON a
    sofa against its seats, so a sofa under five shirts could not be sat on."""
    props = class_info(parent)["properties"]
    return relation != "ON" or not ("SITTABLE" in props or "LIEABLE" in props)


def _within_hand(parent: tuple[float, ...], relation: str) -> bool:
    """Whether an item ON or INSIDE a part with this box stands within `HAND_HIGH`."""
    return (parent[4] if relation == "ON" else parent[1]) <= HAND_HIGH


def _within_front(parent: tuple[float, ...], normal: tuple[float, float] | None,
                  w: float, d: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """The ranges of an item's centre (x, z) on or in a part: anywhere over it, but
    within `FRONT_DEPTH` of the front of one that stands against a wall (the keyboard of
    a 1 m deep desk is not put at its back, out of the arm's reach)."""
    ranges = [[parent[0] + w / 2, parent[3] - w / 2], [parent[2] + d / 2, parent[5] - d / 2]]
    if normal is not None:
        axis = 0 if normal[0] else 1
        half = (w if axis == 0 else d) / 2
        lo, hi = ranges[axis]
        if normal[axis] > 0:
            ranges[axis][0] = max(lo, min(hi, parent[3 + 2 * axis] - FRONT_DEPTH + half))
        else:
            ranges[axis][1] = min(hi, max(lo, parent[2 * axis] + FRONT_DEPTH - half))
    return (ranges[0][0], ranges[0][1]), (ranges[1][0], ranges[1][1])


def _place(rng: random.Random, here: _Room, e: Entry, kb: ClassKnowledge,
           final: bool) -> bool:
    options = [o for o in _candidates(here, e, kb, final)
               if _within_hand(here.parts[o[0]].box, o[1])]
    if not options:
        return False
    k, rel, _ = rng.choices(options, weights=[n for _, _, n in options])[0]
    parts = here.parts
    parent, normal = parts[k].box, parts[k].normal
    w, h, d = class_info(e.cls)["size"]
    if normal is not None and normal[0]:  # its width along the front (a screen faces out)
        w, d = d, w
    px, py, pz = parent[3] - parent[0], parent[4] - parent[1], parent[5] - parent[2]
    w, d = min(w, 0.9 * px), min(d, 0.9 * pz)
    if rel == "INSIDE":
        h = min(h, 0.9 * py)
        top = min(py - h - 0.02 * py, HAND_HIGH - parent[1])
        y0 = parent[1] + rng.uniform(min(0.02 * py, top), top)
    else:
        y0 = parent[4]
    siblings = [parts[s].box for s in here.held.get(k, ())]
    xs, zs = _within_front(parent, normal, w, d)
    for _ in range(8):
        x = rng.uniform(*xs)
        z = rng.uniform(*zs)
        box = box3(x - w / 2, y0, z - d / 2, x + w / 2, y0 + h, z + d / 2)
        if not any(overlap3(box, s) for s in siblings):
            break
    else:  # no room beside what the parent holds already: not in one another
        return False
    here.add(Part(e.cls, here.room, box, (k, rel), parts[k].normal, kind="item",
                  states=tuple(class_info(e.cls)["states"])))
    return True
