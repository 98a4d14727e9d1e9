import random

from homesim.synth.templates import PHRASES, TITLES, join, phrase, spoken


def test_spoken_names():
    assert spoken("coffe_maker") == "coffe maker"


def test_every_phrasing_fills_its_slots():
    for kind, options in PHRASES.items():
        for template in options:
            slots = {k: "kitchen_table" for k in ("room", "x", "y", "c") if "{" + k + "}" in template}
            text = template.format(**{k: spoken(v) for k, v in slots.items()})
            assert "{" not in text, kind


def test_phrase_and_join_are_seeded():
    a = join([phrase("fetch", random.Random(1), x="cup", y="table"), "sit down"], random.Random(2))
    b = join([phrase("fetch", random.Random(1), x="cup", y="table"), "sit down"], random.Random(2))
    assert a == b and a[0].isupper() and a.endswith(".") and "cup" in a and "sit down" in a


def test_titles_cover_the_task_kinds():
    assert all(any(kind.startswith(t) for t in TITLES) for kind in PHRASES if kind != "stand_up")
