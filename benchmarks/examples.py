"""The README's watch-TV example in every built-in home and in generated homes gen-0..99.

    nice python benchmarks/examples.py [--seeds 0-99]

For each home: `homesim.run_program` on the README's program (ungrounded; prepare,
ground, repair, execute), and the two halves the README and docs/grounding.md show
(`prepare_and_ground` on the program that ran, then `execute`). Prints how many homes run
it, the steps repair inserted (by action), the failures, and the time per home (`time.
process_time`; loading a generated home is timed apart: it is most of the time).
"""

from __future__ import annotations

import argparse
import time
from collections import Counter

WATCH_TV = ("[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[Walk] <sofa> (1)\n[Sit] <sofa> (1)\n"
            "[Watch] <tv> (1)\n")


def _seeds(text: str) -> list[int]:
    first, _, last = text.partition("-")
    return list(range(int(first), int(last or first) + 1))


def main() -> None:
    import homesim
    from homesim.world.homes import home_names

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="0-99", help="generated homes, e.g. 0-99")
    args = parser.parse_args()
    homes = [*home_names(), *(f"gen-{s}" for s in _seeds(args.seeds))]
    program = homesim.parse_program(WATCH_TV)
    ok = halves_ok = 0
    inserted: Counter = Counter()
    failures = []
    load_s = run_s = 0.0
    for home in homes:
        t0 = time.process_time()
        graph = homesim.load_home(home)
        t1 = time.process_time()
        run = homesim.run_program(program, graph, seed=0)
        prepared, grounding = homesim.prepare_and_ground(run.repaired or program, graph, seed=0)
        halves = homesim.execute(grounding.program, prepared.graph).executable
        run_s += time.process_time() - t1
        load_s += t1 - t0
        ok += run.executable
        halves_ok += halves
        inserted.update(str(i.step) for i in run.insertions)
        if not (run.executable and halves):
            failures.append(f"{home}: {run.message}")
    print(f"watch TV: runs in {ok} of {len(homes)} homes (10 built-in, "
          f"{len(homes) - 10} generated: gen-{args.seeds}); the halves in {halves_ok}")
    print("steps inserted by repair:", dict(inserted.most_common()))
    for f in failures:
        print("  failed:", f)
    print(f"time: {run_s / len(homes):.3f} s per home to run it, {load_s / len(homes):.3f} s "
          "per home to load or generate it (process time)")


if __name__ == "__main__":
    main()
