"""Preparation and grounding: run a program written for no particular home in a given one.

Glossary:
    prepare: add the objects a program needs and the home lacks; set presupposed states.
    ground: bind each program object (``<cup> (1)``) to a node of the home.
    placement: where an added object may go (the placement knowledge base).
    standing: free floor next to an object where the agent stands to act on it.
"""

from homesim.ground.prepare import Addition, Prepared, prepare
from homesim.ground.search import Grounding, ground, prepare_and_ground, unground

__all__ = [
    "Addition",
    "Grounding",
    "Prepared",
    "ground",
    "prepare",
    "prepare_and_ground",
    "unground",
]
