"""What the real programs' stored homes give away about their programs (docs/learn.md,
"What a real program's home gives away").

    python tools/home_leak.py [--seeds 5] [--vectors out/learn/real/vectors.npz]

Each real program comes with the initial graph it was run from, and that graph was made
for the program: some classes are in a home only when its program uses them. Prints those
classes and how many homes hold one; then, per stratified seed, the reranker's dev steps
LCS with and without its only use of the home (the executability check of its best
candidates), beside the title-medoid with the same check: how much of the gap to the
baseline comes from reading the home.
"""

from __future__ import annotations

import argparse
import json
from collections import Counter
from pathlib import Path

import numpy as np

from homesim.knowledge.datasets import real_programs
from homesim.program.model import Program


def home_classes(graph_path: Path) -> set[str]:
    """The classes of the nodes of a real program's initial graph."""
    graph = json.loads(graph_path.read_text())["init_graph"]
    return {node["class_name"] for node in graph["nodes"]}


def leaked_classes() -> None:
    """Print the classes a home holds only when its program uses them."""
    records = [(home_classes(p.graph_path), {a.name for s in p.program.steps
                                             for a in s.args})
               for p in real_programs() if p.graph_path is not None]
    held = Counter(c for home, _ in records for c in home)
    used = Counter(c for home, objects in records for c in objects & home)
    leaks = sorted(c for c in held if used[c] == held[c] < len(records))
    homes = sum(1 for home, _ in records if home & set(leaks))
    print(f"{len(records)} homes; {len(leaks)} classes are in a home only when its program "
          f"uses them: " + ", ".join(f"{c} {held[c]}" for c in leaks))
    print(f"{homes} of {len(records)} homes ({100 * homes / len(records):.1f}%) hold one")


def reading_the_home(seeds: int, vectors: Path) -> None:
    """Print the dev steps LCS of the reranker and the title-medoid, each with and without
    the executability check in the example's home."""
    from homesim.learn.eval.baselines import medoid_order
    from homesim.learn.eval.experiment import HOLDOUT, RunSpec, load_run_splits
    from homesim.learn.execution import executable
    from homesim.learn.rerank.base import Query
    from homesim.learn.rerank.config import RerankConfig
    from homesim.learn.rerank.reranker import Reranker
    from homesim.program.metrics import normalized_lcs, step_tokens

    def first_runnable(programs: list[Program], example) -> Program:
        checked = programs[:RerankConfig().check_executable]
        return next((p for p in checked if executable(p, example)), programs[0])

    rows = []
    for seed in range(seeds):
        splits = load_run_splits(RunSpec("real", "stratified", seed), vectors)
        reranker = Reranker.fit(splits.train, HOLDOUT["stratified"])
        ranked = {activity: [Program(e.program.steps) for e in group]
                  for activity, group in medoid_order(splits.train).items()}
        everything = np.ones(len(splits.train), bool)
        row = np.zeros(4)
        for e in splits.dev:
            query = Query(reranker.bank, e, everything)
            order = np.argsort(-reranker.scores(query), kind="stable")
            programs = [query.candidates[int(i)].program for i in order]
            medoids = ranked[e.activity]
            truth = step_tokens(e.program)
            row += [normalized_lcs(step_tokens(p), truth) for p in (
                programs[0], first_runnable(programs, e),
                medoids[0], first_runnable(medoids, e))]
        rows.append(row / len(splits.dev))
        print(f"seed {seed}: " + describe(rows[-1]), flush=True)
    print("mean: " + describe(np.mean(rows, axis=0)))


def describe(row: np.ndarray) -> str:
    return (f"reranker {row[0]:.4f} (checked in the home {row[1]:.4f}), "
            f"title-medoid {row[2]:.4f} (checked {row[3]:.4f})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--vectors", type=Path, default=Path("out/learn/real/vectors.npz"))
    args = parser.parse_args()
    leaked_classes()
    if args.seeds:
        reading_the_home(args.seeds, args.vectors)


if __name__ == "__main__":
    main()
