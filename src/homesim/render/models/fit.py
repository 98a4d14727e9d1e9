"""A class's model fitted to a node's box: the builder the class table names, its variant
for a seed, every shape clamped into the box and turned to face the room."""

from __future__ import annotations

import zlib

import numpy as np

from homesim.render.models.kit import BUILDERS, VARIANTS, Builder, Kit, Shape
from homesim.world.class_table import class_row

_WORDS: tuple[tuple[str, str], ...] = (
    ("food", "generic_food"), ("cloth", "clothes_flat"), ("lamp", "tablelamp"),
    ("glass", "glass"), ("cup", "mug"), ("bottle", "bottle"), ("table", "table"),
    ("chair", "chair"), ("sofa", "sofa"), ("cabinet", "cabinet"), ("shelf", "shelf"),
    ("book", "book"), ("knife", "utensil"), ("spoon", "utensil"), ("soap", "rounded"),
    ("paper", "slab"),
)
"""Words inside a class name (checked in order) for classes the class table lacks (a
home file's own classes)."""

_CATEGORIES: dict[str, str] = {
    "Furniture": "generic_furniture", "Appliances": "appliance", "Electronics": "radio",
    "Lamps": "tablelamp", "Food": "generic_food", "Foods": "generic_food",
    "Decor": "generic_prop", "Props": "generic_prop",
}
"""A node's category -> the builder of classes without a row or a telling word."""


def model_name(class_name: str, category: str | None = None) -> str:
    """The name of a class's builder: its row's ``model``, else by a word of the name,
    else by the node's category, else ``generic_prop``."""
    row = class_row(class_name)
    if row is not None and row.model:
        return row.model
    name = class_name.lower().replace("_", "").replace(" ", "")
    for word, model in _WORDS:
        if word in name:
            return model
    return _CATEGORIES.get(category or "", "generic_prop")


def builder_for(class_name: str, category: str | None = None) -> Builder:
    """The builder of a class (see `model_name`)."""
    return BUILDERS[model_name(class_name, category)]


def variant_of(class_name: str, seed: int, key: int = 0) -> int:
    """The variant a class gets for a seed (objects sharing `key`, e.g. a room, match)."""
    n = VARIANTS[model_name(class_name)]
    return zlib.crc32(f"{class_name}:{seed}:{key}".encode()) % n


def _clamp(s: Shape, half: np.ndarray) -> Shape:
    """Shrink a shape so its box stays inside [-half, half]."""
    lo = np.clip(s.center - s.half, -half, half - 2e-3)
    hi = np.clip(s.center + s.half, lo + 2e-3, half)
    hs = (hi - lo) / 2
    if s.kind in ("cylinder", "capsule"):  # keep the section round
        across = [a for a in range(3) if a != s.axis]
        r = float(min(hs[across[0]], hs[across[1]]))
        hs[across] = r
        if s.kind == "capsule":
            hs[s.axis] = max(hs[s.axis], r)
    return Shape(s.kind, (lo + hi) / 2, hs, s.role, s.axis)


def local_model(class_name: str, category: str | None, half: np.ndarray,
                variant: int = 0) -> list[Shape]:
    """A class's shapes in the local frame of a box with half sizes (w, d, h)."""
    w, d, h = (max(float(x), 0.004) for x in half)
    kit = Kit(w, d, h, variant)
    builder_for(class_name, category)(kit)
    bound = np.array([w, d, h])
    return [_clamp(s, bound) for s in kit.shapes]


def fit_model(class_name: str, category: str | None, center: np.ndarray, half: np.ndarray,
              front: tuple[int, float], variant: int = 0) -> list[Shape]:
    """A class's model fitted to a box (MuJoCo frame), its local +y facing `front`
    (axis 0 or 1 and sign, as `layout._front_axis` gives)."""
    axis, sign = front
    side = 1 - axis
    local_half = np.array([half[side], half[axis], half[2]])
    perm = np.array([side, axis, 2])  # local axis k -> world axis perm[k]
    flip = np.array([sign if axis == 1 else -sign, sign, 1.0])  # a turn about z
    out = []
    for s in local_model(class_name, category, local_half, variant):
        c = np.zeros(3)
        h = np.zeros(3)
        c[perm] = s.center * flip
        h[perm] = s.half
        out.append(Shape(s.kind, np.asarray(center, float) + c, h, s.role, int(perm[s.axis])))
    return out


