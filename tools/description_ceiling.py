"""How far the real descriptions determine their programs (docs/learn.md, "How much a
description says").

    python tools/description_ceiling.py [--vectors out/learn/real/vectors.npz]

Over every pair of distinct programs of one activity among the real ones (the 497 of the
splits: copies of training programs are left out of dev and test), prints the mean steps
LCS of the two programs by the MiniLM cosine of their descriptions: how much two people
who described a task nearly alike did the same steps. Then, per program, the
steps LCS of the program whose description is nearest (within its activity), of the best
program of its activity (what a perfect chooser among written programs reaches) and the
mean over its activity.
"""

from __future__ import annotations

import argparse
from itertools import pairwise
from pathlib import Path

import numpy as np

from homesim.learn.eval.experiment import RunSpec, load_run_splits
from homesim.learn.rerank.base import Bank

BINS = (-1.0, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 1.01)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vectors", type=Path, default=Path("out/learn/real/vectors.npz"))
    args = parser.parse_args()
    splits = load_run_splits(RunSpec("real", "stratified", 0), args.vectors)
    bank = Bank(splits.train + splits.dev + splits.test)
    activity = np.array([e.activity for e in bank.train])
    same = activity[:, None] == activity[None, :]
    copies = np.array([[a == b for b in bank.tokens] for a in bank.tokens])
    pairs = np.triu(same & ~copies, 1)
    cosine, lcs = (bank.desc @ bank.desc.T)[pairs], bank.lcs[pairs]
    print(f"{len(bank.train)} programs, {pairs.sum()} pairs of distinct programs of one "
          "activity")
    print("description cosine   pairs   mean steps LCS")
    for lo, hi in pairwise(BINS):
        inside = (cosine >= lo) & (cosine < hi)
        print(f"  [{max(lo, -1):.2f}, {min(hi, 1):.2f})  {inside.sum():7d}   "
              f"{lcs[inside].mean():.3f}")
    rows = []
    for i in range(len(bank.train)):
        others = same[i] & ~copies[i]
        if others.sum() >= 2:
            nearest = int(np.argmax(np.where(others, bank.desc @ bank.desc[i], -np.inf)))
            rows.append((bank.lcs[i, nearest], bank.lcs[i][others].max(),
                         bank.lcs[i][others].mean()))
    nearest, best, mean = np.mean(rows, axis=0)
    print(f"per program ({len(rows)}): nearest description's program {nearest:.3f}, best "
          f"program of its activity {best:.3f}, mean over its activity {mean:.3f}")


if __name__ == "__main__":
    main()
