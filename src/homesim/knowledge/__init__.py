"""Knowledge base: activity data sets, object knowledge and the real program data."""

from homesim.knowledge.fetch import data_root, dataset_dir, fetch_dataset, is_fetched
from homesim.knowledge.realdata import RealProgram, real_programs

__all__ = [
    "RealProgram",
    "data_root",
    "dataset_dir",
    "fetch_dataset",
    "is_fetched",
    "real_programs",
]
