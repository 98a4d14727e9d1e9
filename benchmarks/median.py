"""Median search speed: every single-step move scored at once from prefix and suffix LCS
tables (`median.Medians.move_scores`) against scoring the moves one by one with
`expected_lcs`, the same search on the same programs, measured in the same run.

The reranker searches a median for each of its four neighbour weightings and for the
title's activity on every query (docs/learn.md, "Medians"): on the writer's fit, the
one-by-one scorer took about half of the 150 s. Both scorers give the same floats, so the
same medians (checked here).

    python benchmarks/median.py [--sets 150] [--repeat 3]
"""

from __future__ import annotations

import argparse
from collections import defaultdict

import numpy as np

from _timing import best_of
from homesim.learn.data import real_examples
from homesim.learn.rerank.median import Medians
from homesim.program.model import Program

Job = tuple[list[Program], np.ndarray, Program]


def jobs(sets: int) -> list[Job]:
    """The real activities' programs weighted alike, and `sets` random draws of 25 programs
    under seeded Dirichlet weights (like a query's nearest neighbours)."""
    examples = real_examples()
    by_activity: dict[str, list[Program]] = defaultdict(list)
    for e in examples:
        by_activity[e.title].append(e.program)
    out: list[Job] = [(ps, np.ones(len(ps)), ps[0]) for ps in by_activity.values()]
    programs = [e.program for e in examples]
    rng = np.random.default_rng(0)
    for _ in range(sets):
        pick = rng.choice(len(programs), 25, replace=False)
        out.append(([programs[i] for i in pick], rng.dirichlet(np.full(25, 0.3)),
                    programs[pick[0]]))
    return out


def search(work: list[Job], at_once: bool) -> list[str]:
    """Each job's median (as text), with the moves scored at once or one by one."""
    out = []
    for references, weights, start in work:
        medians = Medians(references, weights)
        if not at_once:
            medians._tables = None  # the one-by-one scorer
        out.append(str(medians.median(start)))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", type=int, default=150, help="random weighted sets")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    work = jobs(args.sets)
    same = search(work, True) == search(work, False)
    t_fast = best_of(lambda: search(work, True), args.repeat)
    t_slow = best_of(lambda: search(work, False), args.repeat)
    print(f"median search, {len(work)} sets: moves at once {t_fast:.2f} s, one by one "
          f"{t_slow:.2f} s; speed-up {t_slow / t_fast:.1f}x; same medians: {same}")


if __name__ == "__main__":
    main()
