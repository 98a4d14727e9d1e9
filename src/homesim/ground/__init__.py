"""Preparation and grounding: run a program written for no particular home in a given one.

Glossary:
    prepare: add the objects a program needs and the home lacks; set presupposed states.
    ground: bind each program object (``<cup> (1)``) to a node of the home.
    placement: where an added object may go (the placement knowledge base).
    standing: free floor next to an object where the agent stands to act on it
        (`homesim.world.standing`).
    run_program: the one pipeline every entry point uses (prepare, ground, execute).
    repair: insert the commonsense steps a program misses (walk to an object first, ...).
"""

from homesim.ground.pipeline import Run, run_program
from homesim.ground.prepare import Addition, Prepared, prepare
from homesim.ground.repair import Insertion, Repair, repair
from homesim.ground.search import Grounding, ground, prepare_and_ground, unground

__all__ = [
    "Addition",
    "Grounding",
    "Insertion",
    "Prepared",
    "Repair",
    "Run",
    "ground",
    "prepare",
    "prepare_and_ground",
    "repair",
    "run_program",
    "unground",
]
