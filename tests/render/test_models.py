from collections import Counter

import numpy as np
import pytest

from homesim.knowledge.objects import load_kb
from homesim.render.layout import SKIP_CATEGORIES, Box, Part, build_layout, to_mujoco
from homesim.render.models import (
    BUILDERS,
    VARIANTS,
    builder_for,
    fit_model,
    local_model,
    model_name,
    variant_of,
)
from homesim.world.class_table import class_row
from homesim.world.homes import load_home

HOMES = ["scene1", "scene2", "scene3", "scene4", "scene5"]
STRUCTURE = {"floor", "ceiling", "wall", "doorjamb", "door", "window"}
"""Classes whose look varies by material (per seed and room), not by model variant."""
TOL = 1e-6


def _home_classes() -> Counter:
    count: Counter = Counter()
    for name in HOMES:
        for node in load_home(name):
            if node.bounding_box is not None and node.category not in SKIP_CATEGORIES:
                count[node.class_name] += 1
    return count


def test_every_class_of_the_homes_has_a_model_of_its_own():
    classes = set(_home_classes())
    assert len(classes) >= 120
    drawn_elsewhere = STRUCTURE - {"window"}  # slabs, leaves, posts: layout draws them
    missing = sorted(c for c in classes - drawn_elsewhere
                     if (row := class_row(c)) is None or row.model not in BUILDERS)
    assert missing == []


def test_every_class_the_knowledge_base_can_add_gets_a_model():
    kb = load_kb()
    added = [c for c in kb.classes() if kb.placements(c) and not class_row(c).is_body_part]
    assert len(added) > 300
    for cls in added:
        shapes = local_model(cls, None, np.array([0.1, 0.1, 0.1]))
        assert shapes, cls
    named = sum((row := class_row(c)) is not None and row.model in BUILDERS for c in added)
    assert named == len(added)  # the class table has a model for each


def test_classes_without_a_row_go_by_word_then_category():
    assert builder_for("kitchen_cabinet") is BUILDERS["cabinet"]  # its row
    assert model_name("tall_drinking_glass") == "glass"  # no row: a word of the name
    assert builder_for("food_kiwiberry").__name__ == "generic_food"
    assert builder_for("zzz", "Furniture").__name__ == "generic_furniture"
    assert builder_for("zzz", None).__name__ == "generic_prop"


def test_the_30_most_common_object_classes_have_3_variants_that_differ():
    common = [c for c, _ in _home_classes().most_common() if c not in STRUCTURE][:30]
    half = np.array([0.3, 0.25, 0.2])
    for cls in common:
        assert VARIANTS[model_name(cls)] >= 3, cls
        looks = {tuple(np.round(np.concatenate([s.center for s in shapes] + [
            s.half for s in shapes]), 4)) + tuple(s.role + s.kind for s in shapes)
            for shapes in (local_model(cls, None, half, v) for v in range(3))}
        assert len(looks) == 3, cls


def test_variant_is_chosen_by_seed_and_stable():
    assert variant_of("chair", 3, 7) == variant_of("chair", 3, 7)
    assert len({variant_of("chair", seed) for seed in range(20)}) == 3
    assert variant_of("floor", 5) == 0  # one model


@pytest.mark.parametrize("front", [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)])
def test_fitted_models_stay_in_the_box_for_every_front(front):
    center, half = np.array([1.0, -2.0, 0.5]), np.array([0.4, 0.9, 0.5])
    for cls in ("sofa", "chair", "bed", "tv", "fridge", "mug", "bookshelf", "toilet"):
        for s in fit_model(cls, None, center, half, front, 1):
            assert np.all(s.center - s.half >= center - half - TOL), cls
            assert np.all(s.center + s.half <= center + half + TOL), cls


def test_sofa_faces_the_room():
    center, half = np.zeros(3), np.array([1.0, 0.45, 0.45])
    shapes = fit_model("sofa", None, center, half, (1, 1.0), 0)
    back = max(shapes, key=lambda s: s.center[2] + s.half[2])  # the tallest: backrest
    assert back.center[1] < 0  # at the back, away from the front (+y)


def _drawn(part: Part) -> list[tuple[np.ndarray, np.ndarray]]:
    """(lo, hi) of every shape of a part as drawn at the start (doors closed)."""
    out = [(s.center - s.half, s.center + s.half) for s in part.shapes]
    if part.movable is not None:
        c = part.movable.center
        out += [(c + s.center - s.half, c + s.center + s.half) for s in part.movable_shapes]
    if part.hinge is not None:
        p = part.hinge.pivot
        out += [(p + s.center - s.half, p + s.center + s.half) for s in part.hinge.shapes]
    return out


@pytest.mark.parametrize("home", HOMES)
def test_every_drawn_shape_lies_in_its_nodes_graph_box(home):
    graph = load_home(home)
    layout = build_layout(graph, seed=1)
    for part in layout.parts:
        box = to_mujoco(graph.node(part.node_id))
        assert box is not None
        lo, hi = box.lo - 0.0101, box.hi + 0.0101  # thin boxes are drawn 2 cm thick
        for a, b in _drawn(part):
            assert np.all(a >= lo) and np.all(b <= hi), (home, part.node_id, part.class_name)


def test_hinged_fronts_are_inside_their_box_and_doors_swing_inside_theirs():
    graph = load_home("scene1")
    layout = build_layout(graph)
    kinds = Counter()
    for part in layout.parts:
        if part.hinge is None:
            continue
        kinds[part.class_name] += 1
        box = to_mujoco(graph.node(part.node_id))
        h = part.hinge
        leaf = Box(h.pivot + h.panel.center, h.panel.half)
        tol = 1e-4  # the graph's boxes are rounded to 0.1 mm
        assert np.all(leaf.lo >= box.lo - tol) and np.all(leaf.hi <= box.hi + tol)
        if part.class_name == "door":  # open, the leaf still lies in the door's box
            c, s = np.cos(h.open_angle), np.sin(h.open_angle)
            off = h.panel.center
            opened = Box(h.pivot + np.array([c * off[0] - s * off[1], s * off[0] + c * off[1], off[2]]),
                         h.panel.half[[1, 0, 2]])
            assert np.all(opened.lo >= box.lo - tol) and np.all(opened.hi <= box.hi + tol)
    assert kinds["door"] >= 2 and kinds["fridge"] == 1


def test_screens_and_lamps_come_from_their_models():
    layout = build_layout(load_home("scene1"))
    tv = next(p for p in layout.parts if p.class_name == "tv")
    assert tv.screen is not None and sum(s.role == "screen" for s in tv.shapes) == 1
    lamps = [p for p in layout.parts if p.lamp]
    assert lamps and all(any(s.role == "glow" for s in p.shapes) for p in lamps)


def test_every_model_the_class_table_names_is_registered():
    from homesim.world.class_table import class_table

    named = {row.model for row in class_table().values() if row.model}
    assert sorted(named - set(BUILDERS)) == []
    assert set(VARIANTS) == set(BUILDERS)
