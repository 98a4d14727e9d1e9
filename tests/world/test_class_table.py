"""Contract tests of the class table: a row for every class the knowledge base or a
built-in home names, values from the columns' lists, and the registries it names."""

from __future__ import annotations

import pytest

from homesim.knowledge.objects import load_kb
from homesim.world.class_table import (
    FAMILIES,
    class_row,
    class_table,
    classes_where,
    parse_table,
    squash,
)
from homesim.world.homes import load_home
from homesim.world.procedural.stats import KINDS

BUILT_IN = [f"scene{i}" for i in range(1, 6)] + [f"scene{i}_trimmed" for i in range(1, 6)]
HEADER = "class,model,size,family,render,mount,rooms,required,beside,tags,names,color\n"


def test_every_class_the_knowledge_base_or_a_built_in_home_names_has_a_row():
    names = set(load_kb().classes())
    for home in BUILT_IN:
        names |= {n.class_name for n in load_home(home)}
    assert len(names) > 500
    assert sorted(c for c in names if class_row(c) is None) == []


def test_rooms_and_neighbours_name_room_kinds_and_classes_of_the_table():
    table = class_table()
    for row in table.values():
        assert set(row.rooms) <= set(KINDS) and set(row.required) <= set(KINDS), row.name
        assert all(b in table for b in row.beside), row.name
    assert {"fridge", "stove", "sink"} <= classes_where(required="kitchen")


def test_body_parts_are_never_objects_of_their_own():
    kb = load_kb()
    parts = {squash(c) for c in kb.classes() if kb.has_property(c, "BODY_PART")}
    assert parts <= classes_where(size="body")
    assert class_row("teeth").is_body_part and not class_row("toothbrush").is_body_part
    assert all(class_table()[c].model == "" for c in classes_where(size="body"))


def test_any_spelling_finds_the_row():
    assert class_row("Kitchen Cabinet") is class_row("kitchen_cabinet") is class_row(
        "kitchencabinet")
    assert class_row("no_such_thing") is None


@pytest.mark.parametrize("line, message", [
    ("sofa,sofa,huge,fabric,,,,,,,,", "size 'huge'"),
    ("sofa,sofa,large,velvet,,,,,,,,", "family 'velvet'"),
    ("sofa,sofa,large,fabric,,,,,,shiny,,", "unknown tags"),
    ("sofa,sofa,large,fabric,,,,,,,,1 2", "color needs 3 numbers"),
    ("so_fa,sofa,large,fabric,,,,,,,,", "not spelled run together"),
])
def test_bad_rows_name_their_line(line, message):
    with pytest.raises(ValueError, match=f"line 2: .*{message}"):
        parse_table(HEADER + line + "\n")


def test_families_cover_the_electronics_dark():
    assert {"tv", "computer", "remotecontrol", "keyboard"} <= classes_where(family="dark")
    assert set(FAMILIES) >= {r.family for r in class_table().values()}
