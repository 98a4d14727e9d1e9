"""How well a plan's training programs cover its test rows' step classes, before anything
is rendered: the programs `homesim dataset generate --plan` would draw (the grammar, each
part's homes and seed), and the same measure for fewer training programs.

A clip model cannot name a step class it never saw (mean per-class accuracy counts such a
class as 0), so this bounds what the clip and program models can reach at each size of
the training part; it is the "program diversity of the grammar" measure of docs/learn.md.

    python tools/step_coverage.py [--plan paper] [--n 5200] [--seed 0]
"""

from __future__ import annotations

import argparse

from homesim.dataset.card import coverage
from homesim.dataset.generate import load_programs
from homesim.dataset.plan import load_plan, part_configs
from homesim.dataset.spec import DatasetConfig
from homesim.knowledge.datasets import ActivityDataset, ActivityProgram
from homesim.program.parse import parse_program


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plan", default="paper")
    parser.add_argument("--n", type=int, default=5200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    plan = load_plan(args.plan)
    programs = {}
    for name, config in part_configs(plan, args.n, args.seed, DatasetConfig()).items():
        programs[name] = [ActivityProgram(f"{name}/{pid}", parse_program(text), name)
                          for pid, text in load_programs(config)]
    train = [p for part in plan.parts if part.role == "train" for p in programs[part.name]]
    print(f"plan {plan.name}, {args.n} episodes, seed {args.seed}: {len(train)} training "
          "programs")
    print("| training programs | test row | test classes | seen in training | seen 5+ times "
          "| test steps of a seen class |")
    print("|---:|---|---:|---:|---:|---:|")
    sizes = sorted({len(train) // 8, len(train) // 4, len(train) // 2, len(train)})
    for size in sizes:
        subset = ActivityDataset(train[:size], "train")
        for row, _, parts in plan.rows:
            test = ActivityDataset([p for q in parts for p in programs[q]], row)
            c = coverage(subset, test)
            print(f"| {size} | {row} | {c['test_classes']} | {c['classes_seen']:.1%} | "
                  f"{c['classes_seen_5']:.1%} | {c['steps_seen']:.1%} |")


if __name__ == "__main__":
    main()
