"""Whether the writer and constrained decoding write programs that run, in each test
program's own home and in a generated one (issue 44: 100 % in both).

    python tools/writer_homes.py [--split stratified] [--seed 0] [--out out/learn]

At one development seed (never a locked one): the reranker fitted as the table fits it, and
the run's cached MLE model (``OUT/real/<split>/seed<k>/mle.pt``, made by ``homesim learn
table``; skipped when missing), write for every test description and for every test title
alone (`titles.title_only`), in the program's stored home and in the generated home
``gen-<i mod 10>`` (test program i). Prints the share of written programs that run there
(`execution.executable`), their mean length and steps LCS, and the wall time.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from homesim.learn.data import Example
from homesim.learn.eval.experiment import HOLDOUT, RunSpec, load_run_splits
from homesim.learn.eval.titles import title_only
from homesim.learn.execution import executable
from homesim.learn.rerank.reranker import Reranker
from homesim.learn.text.text2prog import Text2Prog
from homesim.program.metrics import lcs_steps
from homesim.program.model import Program


def in_generated(examples: list[Example]) -> list[Example]:
    """Each example in the generated home ``gen-<i mod 10>`` instead of its own."""
    return [replace(e, graph_path=None, home=f"gen-{i % 10}") for i, e in enumerate(examples)]


def line(name: str, preds: list[Program], examples: list[Example]) -> str:
    """One printed line: share that runs, mean length, mean steps LCS to the truth."""
    runs = np.mean([executable(p, e) for p, e in zip(preds, examples, strict=True)])
    lcs = np.mean([lcs_steps(p, e.program) for p, e in zip(preds, examples, strict=True)])
    length = np.mean([len(p) for p in preds])
    return f"{name:<48} runs {100 * runs:5.1f} %  steps {length:4.1f}  LCS {lcs:.3f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--split", default="stratified", choices=sorted(HOLDOUT))
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=Path("out/learn"))
    args = parser.parse_args()
    start = time.perf_counter()
    spec = RunSpec("real", args.split, args.seed)
    splits = load_run_splits(spec, args.out / "real" / "vectors.npz")
    model = Reranker.fit(splits.train, HOLDOUT[args.split])
    checkpoint = spec.folder(args.out) / "mle.pt"
    t2p = Text2Prog.load(checkpoint) if checkpoint.is_file() else None
    for text, examples in (("description", splits.test),
                           ("title only", [title_only(e) for e in splits.test])):
        for home, where in (("own home", examples), ("generated home", in_generated(examples))):
            print(line(f"writer, {text}, {home}", model.predict(where), where), flush=True)
            if t2p is not None:
                print(line(f"constrained decoding, {text}, {home}",
                           t2p.predict(where, constrained=True), where), flush=True)
    print(f"{args.split} seed {args.seed}: {len(splits.test)} test programs, "
          f"{time.perf_counter() - start:.0f} s wall time")


if __name__ == "__main__":
    main()
