"""The programs and homes issue 43's figures are measured on, fixed by seed before any
tuning began (2026-12, commit of this file): "measure where you did not tune".

Programs: the fetched real programs (`homesim data fetch`) with at least one hands-on step
(a `reach`, `use_held` or `let_go` motion), shuffled by `random.Random(43)`; the first 20
are the development set (looked at while tuning), the next 20 the fresh set (only
measured). Homes: built-in scene1, scene3, scene5 and generated seeds 0-4 for development;
scene2, scene4 and generated seeds 5-9 fresh (dev programs #21, 156, 387, 425, 80, 256,
204, 373, 388, 441, 55, 252, 335, 279, 340, 11, 288, 241, 322, 205; fresh #348, 473, 307,
421, 242, 218, 98, 31, 472, 60, 456, 70, 207, 86, 504, 90, 286, 464, 277, 72).
Interpenetration is reported on both (all five built-in homes and generated seeds 0-9).

A third set, `fresh2` (issue 43's sixth round, fixed before that round's tuning): the next
20 programs of the same order (order[40:60]: #430, 214, 334, 283, 149, 321, 101, 479, 34,
27, 323, 33, 103, 460, 92, 161, 150, 42, 292, 492) in scene2, scene4 and generated seeds
10-14; only measured, never looked at.
"""

from __future__ import annotations

import random

from _real_programs import ungrounded_texts

DEV_HOMES = ("scene1", "scene3", "scene5", "gen-0", "gen-1", "gen-2", "gen-3", "gen-4")
FRESH_HOMES = ("scene2", "scene4", "gen-5", "gen-6", "gen-7", "gen-8", "gen-9")
FRESH2_HOMES = ("scene2", "scene4", "gen-10", "gen-11", "gen-12", "gen-13", "gen-14")
SET_SEED = 43
SET_SIZE = 20
HANDS_ON = ("reach", "use_held", "let_go")


def hands_on(text: str) -> bool:
    """Whether a program has a step whose motion puts a hand on an object."""
    from homesim.program.actions import ACTIONS
    from homesim.program.parse import parse_program

    program = parse_program(text)
    return any(ACTIONS[s.action.key].motion in HANDS_ON for s in program.steps)


def program_sets(size: int = SET_SIZE) -> dict[str, list[tuple[int, str]]]:
    """{"dev": [(index, text)...], "fresh": [...], "fresh2": [...]}: indices into the
    fetched programs."""
    texts = ungrounded_texts()
    pool = [k for k, t in enumerate(texts) if hands_on(t)]
    order = random.Random(SET_SEED).sample(pool, len(pool))
    return {"dev": [(k, texts[k]) for k in order[:size]],
            "fresh": [(k, texts[k]) for k in order[size:2 * size]],
            "fresh2": [(k, texts[k]) for k in order[2 * size:3 * size]]}


HOMES = {"dev": DEV_HOMES, "fresh": FRESH_HOMES, "fresh2": FRESH2_HOMES}
