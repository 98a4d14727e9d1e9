"""Knowledge base: activity data sets, object knowledge and the real program data."""

from homesim.knowledge.fetch import data_root, dataset_dir, fetch_dataset, is_fetched
from homesim.knowledge.objects import ObjectKB, Placement, load_kb
from homesim.knowledge.realdata import RealProgram, real_programs

__all__ = [
    "ObjectKB",
    "Placement",
    "RealProgram",
    "data_root",
    "dataset_dir",
    "fetch_dataset",
    "is_fetched",
    "load_kb",
    "real_programs",
]
