"""The model library: a 3D model per object class, built from MuJoCo primitives.

A model is a list of `Shape` (box, cylinder, capsule, ellipsoid), each with a material
`role` (``body`` takes the class colour; ``wood``, ``fabric``, ``metal``, ``glass``,
``screen``, ``glow``... take the home's materials, see `homesim.render.materials`).
Builders (`kit`) draw in a local frame fitted to the node's box and are registered by
name (`builder`); the class table (`homesim.world.class_table`) names each class's builder.
`fit_model` turns a model into the MuJoCo frame, every shape kept inside the box
(clamped), so depth and segmentation stay exact against the graph's boxes. Builders
registered with variants draw several; `variant_of` picks one from the seed.
"""

from __future__ import annotations

from homesim.render.models import electronics, furniture, objects  # noqa: F401  (register)
from homesim.render.models.fit import builder_for, fit_model, local_model, model_name, variant_of
from homesim.render.models.kit import BUILDERS, KINDS, VARIANTS, Builder, Kit, Shape, builder

__all__ = ["BUILDERS", "KINDS", "VARIANTS", "Builder", "Kit", "Shape", "builder",
           "builder_for", "fit_model", "local_model", "model_name", "variant_of"]
