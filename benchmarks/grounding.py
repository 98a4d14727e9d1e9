"""Scene preparation + grounding on the 518 real programs, in every home, against the reference.

Each real program is turned into ungrounded form (node ids replaced by per-class
counters, `homesim.sim.unground`), then prepared, grounded (`prepare_and_ground`) and
executed in each of the five apartments, trimmed graphs and full graphs (with 3D boxes,
where grounding also picks standing spots). Reported per home: executable rate, and the
time of preparation plus grounding per program (p50, p95, max; execution not included).

Agreement: each program in its own home (the stored eai initial graph, minus the
distractor objects with ids >= 2000 the original pipeline scattered), prepared and
grounded from its ungrounded form: how often the chosen node has the stored node's class,
and is the stored node itself.

Reference (same run, same programs): the VirtualHome reference pipeline
(``virtualhome==2.3.0`` ``check_programs.check_one_program``: add missing objects, pick
instances, execute; in a side venv) on the trimmed homes; its time per program and
executable rate are printed beside ours, with the ratio of p50 and p95 times.

Goals (issue 4): >= 95% executable in every home; p95 of prepare+ground <= 50 ms.

    python benchmarks/grounding.py [--homes scene1_trimmed,scene1,...] [--limit N]
                                   [--workers 2] [--seed 0] [--no-reference]
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import statistics
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from homesim.errors import HomesimError
from homesim.ground import prepare_and_ground, unground
from homesim.knowledge import load_kb, real_programs
from homesim.knowledge.fetch import dataset_dir
from homesim.sim import execute
from homesim.world import EnvironmentGraph, load_home

HOMES = [f"scene{i}{t}" for t in ("_trimmed", "") for i in range(1, 6)]
SCENES = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "virtualhome" / "scenes"
ADDED_FOR_PROGRAM = 2000
"""Ids from here up are the distractors the original pipeline scattered in the eai graphs."""


def _percentile(values: list[float], q: float) -> float:
    values = sorted(values)
    return values[min(len(values) - 1, round(q * (len(values) - 1)))]


def _run_home(job: tuple[str, list[str], int]) -> tuple[str, list[tuple[bool, float, str]]]:
    """Prepare, ground and execute every program in one home (in a worker process)."""
    home, texts, seed = job
    from homesim.program import parse_program

    graph = load_home(home)
    kb = load_kb()
    out = []
    for text in texts:
        program = parse_program(text)
        t0 = time.perf_counter()
        try:
            prepared, grounding = prepare_and_ground(program, graph, seed=seed, kb=kb)
            seconds = time.perf_counter() - t0
            result = execute(grounding.program, prepared.graph)
            out.append((result.executable, seconds, "" if result.executable
                        else f"execute: {result.reason}"))
        except HomesimError as e:
            out.append((False, time.perf_counter() - t0, str(e).split(": ", 1)[-1]))
    return home, out


def _agreement(job: tuple[str, int]) -> tuple[int, int, int, int, bool, bool, float]:
    """(refs, same class, same node, program all same node, executable, ok, seconds)."""
    pid, seed = job
    rp = next(r for r in real_programs() if r.id == pid)
    init, _ = rp.graph_dicts()
    nodes = [n for n in init["nodes"] if n["id"] < ADDED_FOR_PROGRAM]
    keep = {n["id"] for n in nodes}
    edges = [e for e in init["edges"] if e["from_id"] in keep and e["to_id"] in keep]
    graph = EnvironmentGraph.from_dict({"nodes": nodes, "edges": edges})
    stored = {}
    program = unground(rp.program)
    for s_orig, s_new in zip(rp.program.steps, program.steps, strict=True):
        for a, b in zip(s_orig.args, s_new.args, strict=True):
            stored[b.key] = a.node_id
    t0 = time.perf_counter()
    try:
        prepared, grounding = prepare_and_ground(program, graph, seed=seed)
    except HomesimError:
        return len(stored), 0, 0, 0, False, False, time.perf_counter() - t0
    seconds = time.perf_counter() - t0
    executable = execute(grounding.program, prepared.graph).executable
    same_node = sum(grounding.bindings[k] == v for k, v in stored.items())
    same_class = sum(prepared.graph.node(grounding.bindings[k]).class_name
                     == graph.node(v).class_name if v in graph else False
                     for k, v in stored.items())
    return (len(stored), same_class, same_node, int(same_node == len(stored)), executable,
            True, seconds)


def _reference(home: str, texts: list[str], seed: int) -> dict | None:
    from reference import reference_python

    graph_path = SCENES / f"{home}.json"
    if not graph_path.exists():
        return None
    lines = [[line for line in t.splitlines() if line.startswith("[")] for t in texts]
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(lines, f)
    import subprocess

    proc = subprocess.run([str(reference_python()),
                           str(Path(__file__).with_name("_ref_ground_runner.py")),
                           str(dataset_dir()), str(graph_path), f.name, str(seed)],
                          capture_output=True, text=True, check=False)
    Path(f.name).unlink()
    if proc.returncode != 0:
        print(f"  reference failed on {home}: {proc.stderr[-500:]}", flush=True)
        return None
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--homes", default=",".join(HOMES))
    parser.add_argument("--limit", type=int, default=0, help="first N programs only")
    parser.add_argument("--workers", type=int, default=mp.cpu_count())
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--no-reference", action="store_true")
    args = parser.parse_args()
    programs = real_programs()
    if args.limit:
        programs = programs[:args.limit]
    texts = [str(unground(rp.program)) for rp in programs]
    homes = args.homes.split(",")
    n = len(programs)
    print(f"{n} programs x {len(homes)} homes, {args.workers} worker processes", flush=True)

    with mp.Pool(args.workers) as pool:
        t0 = time.perf_counter()
        results = dict(pool.map(_run_home, [(h, texts, args.seed) for h in homes],
                                chunksize=1))
        wall = time.perf_counter() - t0
        agreement = pool.map(_agreement, [(rp.id, args.seed) for rp in programs],
                             chunksize=8)

    refs = {}
    if not args.no_reference:
        for home in homes:
            if home.endswith("_trimmed"):
                print(f"running the reference pipeline on {home} ...", flush=True)
                refs[home] = _reference(home, texts, args.seed)

    print(f"\n{'home':<16} {'executable':>12} {'p50 ms':>8} {'p95 ms':>8} {'max ms':>8}   "
          f"{'reference: executable':>22} {'p50 ms':>8} {'p95 ms':>8} {'p95 ratio':>9}")
    all_times: list[float] = []
    goals = []
    for home in homes:
        rows = results[home]
        ok = sum(r[0] for r in rows)
        times = [r[1] * 1e3 for r in rows]
        all_times += times
        goals.append(ok / n >= 0.95)
        line = (f"{home:<16} {ok:>4}/{n} {ok / n:>5.1%} {_percentile(times, .5):>8.1f} "
                f"{_percentile(times, .95):>8.1f} {max(times):>8.1f}")
        ref = refs.get(home)
        if ref:
            rt = [s * 1e3 for s in ref["seconds"]]
            rok = sum(ref["executable"])
            line += (f"   {rok:>14}/{n} {rok / n:>5.1%} {_percentile(rt, .5):>8.1f} "
                     f"{_percentile(rt, .95):>8.1f} "
                     f"{_percentile(rt, .95) / _percentile(times, .95):>8.0f}x")
        print(line)
    p95 = _percentile(all_times, .95)
    print(f"{'all':<16} {'':>12} {_percentile(all_times, .5):>8.1f} {p95:>8.1f} "
          f"{max(all_times):>8.1f}   ({len(all_times)} runs, {wall:.1f} s wall)")

    print("\nmost common failures:")
    reasons = Counter(r[2][:90] for rows in results.values() for r in rows if not r[0])
    for reason, count in reasons.most_common(8):
        print(f"  {count:>4}  {reason}")

    total = sum(a[0] for a in agreement)
    same_class = sum(a[1] for a in agreement)
    same_node = sum(a[2] for a in agreement)
    whole = sum(a[3] for a in agreement)
    executable = sum(a[4] for a in agreement)
    print(f"\nagreement in the original home (eai initial graphs minus ids >= "
          f"{ADDED_FOR_PROGRAM}; {n} programs, {total} objects):")
    print(f"  same class     {same_class:>5}/{total} {same_class / total:.1%}")
    print(f"  same instance  {same_node:>5}/{total} {same_node / total:.1%}")
    print(f"  programs with every instance the same  {whole}/{n} {whole / n:.1%}")
    print(f"  executable there  {executable}/{n} {executable / n:.1%}, prepare+ground p50 "
          f"{statistics.median(a[6] for a in agreement) * 1e3:.1f} ms")

    print(f"\ngoal >= 95% executable in every home: {'met' if all(goals) else 'NOT MET'}")
    print(f"goal p95 prepare+ground <= 50 ms: {'met' if p95 <= 50 else 'NOT MET'} "
          f"({p95:.1f} ms)")


if __name__ == "__main__":
    main()
