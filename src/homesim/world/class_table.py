"""The class table: one row per object class for what rendering, generated homes and
descriptions need to know of it (`class_table.csv`, shipped with the package).

Columns (lists are space separated, except ``names``, separated by ``;``):

    class     the class, lower case, words run together (``kitchencabinet``); any
              spelling finds its row (``kitchen_cabinet``, ``Kitchen Cabinet``)
    model     the builder that draws it (`homesim.render.models` registers builders by
              name); empty for what render draws itself (walls, floors, doors, rooms) or
              never draws as an object (body parts)
    size      body (a part of the agent: never an object of its own), person, structure
              (rooms, walls, floors, doors, windows), large, medium, small
    family    palette and material family: fabric (sofas, beds), accent (cushions, rugs,
              curtains, towels: the home's accent colour), wood, dark (electronics),
              white (appliances, porcelain), metal, ceramic, glass, paper, food, plant,
              decor, lamp, plastic, structure, room, body, person; a home's theme
              (`homesim.render.palette`) colours each family
    render    how render shapes it beyond its model: hinged (a carcass with a hinged front
              when it can open), screen (lights up when on), lamp (lit by its own
              switch), room_lamp (lit by the room's light switch), enclosure (walls open
              at the front and top: a shower stall)
    mount     where generated homes put it: floor, wall, ceiling (empty: as the built-in
              homes hold it, `homesim.world.procedural.stats`)
    rooms     room kinds generated homes may put it in (empty: any the statistics give)
    required  room kinds whose generated rooms always have it
    beside    classes it stands beside in generated homes (a chair at a desk)
    tags      single (one per room), centre (stands in the room's middle), surface (a
              last resort to put things on), windowed (its front has a glass pane),
              across (stands facing its ``beside`` class across the floor: a sofa
              facing the TV stand), end (stands at an end of its ``beside`` class, not
              before it: a computer tower beside the desk, out of the sitter's legs),
              faced (what stands beside it stands before its front: a desk's chair)
    names     what people call it (empty: its name with spaces)
    color     a fixed base colour, r g b in 0..1, for what keeps its colour in every home
              (an apple; empty: the theme colours it by family and seed)

A contract test checks that every class the knowledge base or a built-in home names has
a row, that every model is registered and that the values come from these lists.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

SIZES = ("body", "person", "structure", "large", "medium", "small")
FAMILIES = ("fabric", "accent", "wood", "dark", "white", "metal", "ceramic", "glass", "paper",
            "food", "plant", "decor", "lamp", "plastic", "structure", "room", "body", "person")
RENDER_KINDS = ("", "hinged", "screen", "lamp", "room_lamp", "enclosure")
MOUNTS = ("", "floor", "wall", "ceiling")
TAGS = ("single", "centre", "surface", "windowed", "across", "end", "faced")


@dataclass(frozen=True, slots=True)
class ClassRow:
    """One row of the class table (see the module docstring for the columns)."""

    name: str
    model: str
    size: str
    family: str
    render: str
    mount: str
    rooms: tuple[str, ...]
    required: tuple[str, ...]
    beside: tuple[str, ...]
    tags: frozenset[str]
    names: tuple[str, ...]
    color: tuple[float, float, float] | None

    @property
    def is_body_part(self) -> bool:
        """A part of the agent's body (teeth, hair, hands...): never a prop of its own."""
        return self.size == "body"


def squash(name: str) -> str:
    """A class name as the table spells it: lower case, no underscores or spaces."""
    return name.lower().replace("_", "").replace(" ", "")


def _row(fields: dict[str, str], line: int) -> ClassRow:
    def words(key: str) -> tuple[str, ...]:
        return tuple(fields[key].split())

    rgb = tuple(float(x) for x in fields["color"].split())
    if rgb and len(rgb) != 3:
        raise ValueError(f"class_table.csv line {line}: color needs 3 numbers, got {rgb}")
    color = (rgb[0], rgb[1], rgb[2]) if rgb else None
    return ClassRow(fields["class"], fields["model"], fields["size"], fields["family"],
                    fields["render"], fields["mount"], words("rooms"), words("required"),
                    words("beside"), frozenset(words("tags")),
                    tuple(n.strip() for n in fields["names"].split(";") if n.strip()),
                    color)


def parse_table(text: str) -> dict[str, ClassRow]:
    """Rows of a class table's CSV text, by class; raises ValueError naming the line of a
    value outside its column's list."""
    rows: dict[str, ClassRow] = {}
    allowed = {"size": SIZES, "family": FAMILIES, "render": RENDER_KINDS, "mount": MOUNTS}
    for line, fields in enumerate(csv.DictReader(io.StringIO(text)), start=2):
        for key, values in allowed.items():
            if fields[key] not in values:
                raise ValueError(f"class_table.csv line {line}: {key} {fields[key]!r} is not "
                                 f"one of {', '.join(v or '(empty)' for v in values)}")
        row = _row(fields, line)
        if row.name != squash(row.name) or row.name in rows:
            raise ValueError(f"class_table.csv line {line}: class {row.name!r} is not spelled "
                             "run together or comes twice")
        if not row.tags <= set(TAGS):
            raise ValueError(f"class_table.csv line {line}: unknown tags "
                             f"{sorted(row.tags - set(TAGS))}")
        rows[row.name] = row
    return rows


@lru_cache(maxsize=1)
def class_table() -> dict[str, ClassRow]:
    """The shipped class table, by class (read once)."""
    text = (resources.files("homesim.world") / "class_table.csv").read_text(encoding="utf-8")
    return parse_table(text)


def class_row(name: str) -> ClassRow | None:
    """The row of a class in any spelling, or None for a class the table lacks."""
    return class_table().get(squash(name))


@lru_cache(maxsize=64)
def classes_where(**column: str) -> frozenset[str]:
    """The classes whose row has these values (``classes_where(render="hinged")``); a tag,
    room kind or neighbour is matched by membership (``classes_where(tags="single")``)."""
    out = set()
    for name, row in class_table().items():
        ok = True
        for key, want in column.items():
            have = getattr(row, key)
            ok = ok and (want in have if isinstance(have, tuple | frozenset) else have == want)
        if ok:
            out.add(name)
    return frozenset(out)


__all__ = ["ClassRow", "class_row", "class_table", "classes_where", "parse_table", "squash"]
