"""Executor throughput: homesim against the VirtualHome reference, on the 518 real programs.

Both run in this one invocation, on the same programs and stored initial graphs, with
graphs and programs loaded beforehand (only execution is timed; best of --repeat runs):

- plain: homesim ``execute(p, g, reference=True)`` vs reference ``ScriptExecutor.execute(script,
  w_graph_list=False)`` (2.3.0 with its three crashing bugs patched in memory);
- with per-step changes: homesim ``execute(p, g, trace=True)`` (per-step deltas) vs
  reference ``w_graph_list=True`` (a full graph dict per step).

Goals (issue 2): >= 100x plain, >= 300x with per-step changes.

    python benchmarks/executor.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from homesim.knowledge.datasets import real_programs
from homesim.knowledge.fetch import dataset_dir, verify
from homesim.sim import execute
from reference import run_reference


def time_homesim(items, trace: bool, repeat: int) -> tuple[float, int]:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        ok = sum(execute(p, g, trace=trace, reference=True).executable for p, g in items)
        best = min(best, time.perf_counter() - t0)
    return best, ok


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    directory = dataset_dir()
    verify(directory)
    print("loading the 518 programs and their initial graphs ...", flush=True)
    items = [(rp.program, rp.graphs()[0]) for rp in real_programs(directory)]
    n = len(items)

    plain, ok_plain = time_homesim(items, False, args.repeat)
    traced, ok_traced = time_homesim(items, True, args.repeat)
    print("running the reference (side venv, virtualhome==2.3.0) ...", flush=True)
    ref = run_reference(directory, "time", "--repeat", str(args.repeat))

    rows = [
        ("plain", plain, ok_plain, ref["execute"], 100),
        ("per-step changes", traced, ok_traced, ref["graph_list"], 300),
    ]
    print(f"\n{'mode':<18} {'homesim prog/s':>15} {'reference prog/s':>17} {'ratio':>8} "
          f"{'goal':>6}  executable (homesim / reference)")
    worst = []
    for label, secs, ok, r, goal in rows:
        ours, theirs = n / secs, n / r["seconds"]
        ratio = ours / theirs
        worst.append(ratio >= goal)
        print(f"{label:<18} {ours:>15,.0f} {theirs:>17,.1f} {ratio:>7.0f}x {goal:>5}x  "
              f"{ok}/{n} / {r['executable']}/{n}")
    print("\nall goals met" if all(worst) else "\nGOAL NOT MET")


if __name__ == "__main__":
    main()
