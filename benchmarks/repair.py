"""Repair: executable rate of the real programs without and with `homesim.ground.repair`.

The 518 real programs, in ungrounded form (`homesim.ground.unground`), run in each
built-in home (five apartments, trimmed and full) through `homesim.run_program`, then
through `homesim.ground.repair.repair`, on two inputs:

- ``as written``: the programs as collected (preparation and grounding already make
  nearly all of them run);
- ``no Walk/Find``: the same programs with every Walk, Run and Find step removed, the
  paper's "missing minor steps" made systematic (a harder input for repair).

Printed per home and input: executable % without and with repair (goal with repair:
>= 99 % in every home), mean steps inserted per program and per repaired program, mean
pipeline runs per program, and seconds.

    nice python benchmarks/repair.py [--homes scene1_trimmed,...] [--limit N] [--workers 2]
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import time

from _real_programs import ungrounded_texts

HOMES = [f"scene{i}{t}" for t in ("_trimmed", "") for i in range(1, 6)]
MINOR = frozenset({"WALK", "RUN", "FIND"})


def _run_home(job: tuple[str, list[str], bool]) -> tuple[tuple[str, bool], dict]:
    """Every program in one home, without and with repair (in a worker process)."""
    home, texts, strip = job
    from homesim.ground.repair import repair
    from homesim.program import parse_program
    from homesim.world import load_home

    graph = load_home(home)
    c = {"n": 0, "before": 0, "after": 0, "inserted": 0, "repaired": 0, "runs": 0,
         "failures": []}
    t0 = time.perf_counter()
    for text in texts:
        program = parse_program(text)
        if strip:
            program = program.with_steps([s for s in program.steps
                                          if s.action.key not in MINOR])
        r = repair(program, graph)
        c["n"] += 1
        c["before"] += r.before.executable
        c["after"] += r.executable
        c["inserted"] += len(r.insertions)
        c["repaired"] += r.executable and not r.before.executable
        c["runs"] += r.runs
        if not r.executable and len(c["failures"]) < 2:
            c["failures"].append(r.run.message[:110])
    c["seconds"] = time.perf_counter() - t0
    return (home, strip), c


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--homes", default=",".join(HOMES))
    parser.add_argument("--limit", type=int, default=0, help="first N programs only")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()

    texts = ungrounded_texts(args.limit)
    homes = args.homes.split(",")
    jobs = [(h, texts, strip) for strip in (False, True) for h in homes]
    with mp.get_context("spawn").Pool(args.workers) as pool:
        results = dict(pool.map(_run_home, jobs, chunksize=1))
    print(f"{len(texts)} real programs, ungrounded; executable % without / with repair")
    print(f"{'input':13} {'home':16} {'without':>8} {'with':>8} {'ins/prog':>9} "
          f"{'ins/fixed':>9} {'runs/prog':>9} {'s':>5}")
    for strip in (False, True):
        label = "no Walk/Find" if strip else "as written"
        for home in homes:
            c = results[(home, strip)]
            n = max(c["n"], 1)
            fixed = c["inserted"] / max(c["repaired"], 1)
            print(f"{label:13} {home:16} {100 * c['before'] / n:8.1f} "
                  f"{100 * c['after'] / n:8.1f} {c['inserted'] / n:9.2f} {fixed:9.2f} "
                  f"{c['runs'] / n:9.2f} {c['seconds']:5.0f}")
            for f in c["failures"]:
                print(f"    still failing: {f}")
    worst = min(100 * c["after"] / max(c["n"], 1) for c in results.values())
    print(f"lowest executable % with repair: {worst:.1f} (goal >= 99 in every home)")


if __name__ == "__main__":
    main()
