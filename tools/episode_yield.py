"""How many planned episodes run in their drawn home, and how many after trying the other
homes (`homesim.dataset.episode.homes_to_try`): the program grounded and executed in the
randomised home, as `dataset generate` does before rendering (nothing is rendered).

    python tools/episode_yield.py [--n 500] [--seed 0]

Prints the counts and the reasons of the episodes that run in no home.
"""

from __future__ import annotations

import argparse
import re
from collections import Counter

from homesim.dataset.episode import EpisodeFailed, ground_episode
from homesim.dataset.generate import load_programs
from homesim.dataset.spec import DatasetConfig, plan_episodes

STEP_NUMBER = re.compile(r"^step \d+ ")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=500)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    config = DatasetConfig(n=args.n, seed=args.seed)
    specs = plan_episodes(config, load_programs(config))
    drawn, moved, reasons = 0, Counter[str](), Counter[str]()
    for spec in specs:
        try:
            home = ground_episode(spec, config.homes).home
        except EpisodeFailed as e:
            where = STEP_NUMBER.sub("", e.reason.split(":")[0])
            reasons[f"{e.stage}: {where}"] += 1
            continue
        if home == spec.home:
            drawn += 1
        else:
            moved[home] += 1
    made = drawn + sum(moved.values())
    print(f"{len(specs)} episodes (seed {args.seed}, homes {', '.join(config.homes)})")
    print(f"run in the drawn home: {drawn} ({drawn / len(specs):.1%})")
    print(f"run after trying other homes: {made} ({made / len(specs):.1%}); moved to "
          + ", ".join(f"{h} {c}" for h, c in sorted(moved.items())))
    print(f"run in no home: {len(specs) - made}")
    for reason, count in reasons.most_common():
        print(f"  {count:4d}  {reason}")


if __name__ == "__main__":
    main()
