"""The version of homesim (pyproject.toml's), for what records which homesim made it."""

__version__ = "0.1.0"
