"""Real programs in every home: executable % as written and with repair (`run_program`).

The 518 real programs, in ungrounded form (`homesim.ground.unground`), run through
`homesim.run_program` (prepare, ground, execute; repair by default) in each home, on two
inputs:

- ``as written``: the programs as collected;
- ``no Walk/Find``: the same programs with every Walk, Run and Find step removed, the
  paper's "missing minor steps" made systematic (a harder input for repair).

Homes, chosen by seed before any tuning (issue 41): ``builtin`` (the five apartments,
trimmed and full), ``dev`` (generated homes gen-0..gen-9, looked at while developing) and
``fresh`` (gen-100..gen-119, measured, not looked at while tuning); ``--homes`` also takes
a comma-separated list.

Printed per home and input: executable % as written (the strict run) and with repair
(goal: >= 99 % in every home), steps inserted per program, the p95 and largest time per
program (seconds, `time.process_time` of the worker: a busy machine's wait for a core
does not count) and the first failures. Then the steps inserted, by action, and the
lowest rate of each home set. ``--report FILE`` writes every failure and insertion.

    nice python benchmarks/repair.py [--homes builtin,dev,fresh] [--limit N] [--workers 2]
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import time
from collections import Counter
from pathlib import Path

from _real_programs import ungrounded_texts

SETS = {
    "builtin": [f"scene{i}{t}" for t in ("_trimmed", "") for i in range(1, 6)],
    "dev": [f"gen-{i}" for i in range(10)],
    "fresh": [f"gen-{i}" for i in range(100, 120)],
}
MINOR = frozenset({"WALK", "RUN", "FIND"})


def _run_home(job: tuple[str, list[str], bool]) -> tuple[tuple[str, bool], dict]:
    """Every program in one home (in a worker process)."""
    home, texts, strip = job
    from homesim.ground.pipeline import run_program
    from homesim.program import parse_program
    from homesim.world import load_home

    graph = load_home(home)
    c: dict = {"n": 0, "strict": 0, "after": 0, "inserted": 0, "times": [],
               "failures": [], "insertions": Counter()}
    for k, text in enumerate(texts):
        program = parse_program(text)
        if strip:
            program = program.with_steps([s for s in program.steps
                                          if s.action.key not in MINOR])
        if not program.steps:  # nothing left to run: runs trivially
            c["n"] += 1
            c["strict"] += 1
            c["after"] += 1
            continue
        t0 = time.process_time()
        run = run_program(program, graph)
        c["times"].append(time.process_time() - t0)
        c["n"] += 1
        c["strict"] += run.executable and run.strict is None
        c["after"] += run.executable
        c["inserted"] += len(run.insertions)
        for ins in run.insertions:
            c["insertions"][ins.step.action.name] += 1
        if not run.executable:
            c["failures"].append({"program": k, "message": run.message,
                                  "kind": None if run.kind is None else run.kind.value})
    return (home, strip), c


def _homes(spec: str) -> list[str]:
    homes: list[str] = []
    for part in spec.split(","):
        homes += SETS.get(part, [part])
    return homes


def _p(times: list[float], q: float) -> float:
    times = sorted(times)
    return times[min(len(times) - 1, int(q * len(times)))] if times else 0.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--homes", default="builtin,dev,fresh",
                        help="builtin, dev, fresh and/or home names, comma-separated")
    parser.add_argument("--limit", type=int, default=0, help="first N programs only")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--report", type=Path, help="write failures and insertions (JSON)")
    args = parser.parse_args()

    texts = ungrounded_texts(args.limit)
    homes = _homes(args.homes)
    jobs = [(h, texts, strip) for strip in (False, True) for h in homes]
    t0 = time.perf_counter()
    with mp.get_context("spawn").Pool(args.workers) as pool:
        results = dict(pool.imap_unordered(_run_home, jobs, chunksize=1))
    wall = time.perf_counter() - t0
    print(f"{len(texts)} real programs, ungrounded, through run_program; executable % as "
          f"written (strict) and with repair; {wall:.0f} s wall, {args.workers} workers")
    print(f"{'input':13} {'home':16} {'strict':>7} {'repair':>7} {'ins/prog':>9} "
          f"{'p95 s':>6} {'max s':>6}")
    for strip in (False, True):
        label = "no Walk/Find" if strip else "as written"
        for home in homes:
            c = results[(home, strip)]
            n = max(c["n"], 1)
            print(f"{label:13} {home:16} {100 * c['strict'] / n:7.1f} "
                  f"{100 * c['after'] / n:7.1f} {c['inserted'] / n:9.2f} "
                  f"{_p(c['times'], .95):6.3f} {max(c['times'], default=0):6.2f}")
            for f in c["failures"][:2]:
                print(f"    still failing: {f['message'][:110]}")
    inserted: Counter = sum((c["insertions"] for c in results.values()), Counter())
    print("steps inserted, by action:", dict(inserted.most_common()))
    all_times = [t for c in results.values() for t in c["times"]]
    print(f"time per program, all homes and inputs: p50 {_p(all_times, .5):.3f} s, "
          f"p95 {_p(all_times, .95):.3f} s, max {max(all_times, default=0):.2f} s")
    for name, members in SETS.items():
        rates = [100 * c["after"] / max(c["n"], 1) for (h, _), c in results.items()
                 if h in members]
        if rates:
            print(f"lowest executable % with repair, {name} homes: {min(rates):.1f} "
                  "(goal >= 99 in every home)")
    if args.report:
        data = {f"{h} {'no Walk/Find' if s else 'as written'}": {
            "failures": c["failures"], "insertions": dict(c["insertions"])}
            for (h, s), c in results.items()}
        args.report.write_text(json.dumps(data, indent=1))


if __name__ == "__main__":
    main()
