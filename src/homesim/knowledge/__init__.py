"""Knowledge base: activity data sets, object knowledge and the real program data."""

from homesim.knowledge.datasets import ActivityDataset, ActivityProgram
from homesim.knowledge.fetch import data_root, dataset_dir, fetch_dataset, is_fetched
from homesim.knowledge.objects import ObjectKB, Placement, load_kb
from homesim.knowledge.realdata import real_programs

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
