"""Learning-side speed: program synthesis and simulator-constrained decoding.

Each figure is a ratio against a reference measured in the same run:

- synthesis: sampling programs with the grammar (which runs every candidate step on the
  simulator and undoes failed tasks) against only re-executing the kept programs;
- decoding: constrained greedy decoding (tries steps in score order until one runs in the
  simulated home) against plain greedy decoding of the same model on the same examples.

Goal: constrained decoding at most 3x the cost of greedy decoding, so evaluating it stays
a small part of the table's wall time.

    python benchmarks/learn.py [--n 1000] [--repeat 3] [--checkpoint out/learn/synthetic/mle.pt]

Without --checkpoint a small model is trained first (8 epochs on 420 synthetic examples).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import torch

from _timing import best_of
from homesim.learn.data import split, synthetic_examples
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.text.train import TrainConfig, train_mle
from homesim.sim import execute
from homesim.synth import generate
from homesim.world.homes import open_home


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1000, help="programs to synthesise")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--checkpoint", type=Path, help="a synthetic-data text2prog model")
    args = parser.parse_args()
    torch.set_num_threads(1)

    programs = list(generate(args.n, seed=0))  # warm the home cache
    homes = {name: open_home(name) for name in {p.home for p in programs}}
    t_synth = best_of(lambda: list(generate(args.n, seed=0)), args.repeat)
    t_exec = best_of(lambda: [execute(p.program, homes[p.home], bindings=p.bindings)
                              for p in programs], args.repeat)
    print(f"synthesis: {args.n / t_synth:,.0f} programs/s; re-executing them: "
          f"{args.n / t_exec:,.0f} programs/s; ratio {t_synth / t_exec:.1f}x")

    if args.checkpoint:
        t2p = Text2Prog.load(args.checkpoint)
        test = synthetic_examples(300, seed=99)  # fresh programs (other seed than training)
    else:
        splits = split("synthetic", synthetic_examples(600, seed=0), seed=0)
        t2p = Text2Prog.create(splits.train, seed=0, embeddings="none")
        train_mle(t2p, splits.train, TrainConfig(epochs=8, batch_size=32))
        test = splits.test
    t_greedy = best_of(lambda: t2p.predict(test), args.repeat)
    t_constr = best_of(lambda: t2p.predict(test, constrained=True), args.repeat)
    n_greedy = sum(len(p) for p in t2p.predict(test)) / len(test)
    n_constr = sum(len(p) for p in t2p.predict(test, constrained=True)) / len(test)
    ratio = t_constr / t_greedy
    print(f"decoding {len(test)} descriptions: greedy {t_greedy * 1000:.0f} ms "
          f"({n_greedy:.1f} steps/program), constrained {t_constr * 1000:.0f} ms "
          f"({n_constr:.1f} steps/program); ratio {ratio:.2f}x "
          f"(goal <= 3x: {'met' if ratio <= 3 else 'NOT met'})")


if __name__ == "__main__":
    main()
