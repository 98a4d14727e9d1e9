"""Knowledge base: activity data sets, object knowledge and the real program data.

Importing the package loads none of it: each name below is imported from its module on
first use (PEP 562 ``__getattr__``), so what needs the object knowledge
(`homesim.knowledge.kbtypes`) does not pull in the data set readers, which read homes.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the same names, for type checkers
    from homesim.knowledge.datasets import ActivityDataset, ActivityProgram, real_programs
    from homesim.knowledge.fetch import data_root, dataset_dir, fetch_dataset, is_fetched
    from homesim.knowledge.objects import ObjectKB, Placement, load_kb

_MODULE_OF = {
    "ActivityDataset": "datasets", "ActivityProgram": "datasets", "real_programs": "datasets",
    "data_root": "fetch", "dataset_dir": "fetch", "fetch_dataset": "fetch",
    "is_fetched": "fetch", "ObjectKB": "objects", "Placement": "objects", "load_kb": "objects",
}

__all__ = [
    "ActivityDataset",
    "ActivityProgram",
    "ObjectKB",
    "Placement",
    "data_root",
    "dataset_dir",
    "fetch_dataset",
    "is_fetched",
    "load_kb",
    "real_programs",
]


def __getattr__(name: str) -> Any:
    module = _MODULE_OF.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(f"{__name__}.{module}"), name)
