"""Procedural homes: generation time, validity, determinism, the 518 real programs, render.

For each seed: generate the home (time it, wall clock and CPU time of the process: on a
shared machine the wall clock mostly measures waiting; load a built-in home as the
reference in the same run), check it (`check_home`), generate again and compare bytes;
then run the 518 real programs (ungrounded, as in benchmarks/grounding.py) through
`homesim.run_program` as written (``repair=False``; `benchmarks/repair.py` measures
repair) and count the executable ones and the objects preparation added.
The built-in homes (full, with boxes) are measured the same way for comparison. In the homes of
`--render-seeds` (and the built-in ones), two typical real programs (the first that
watches TV from the sofa, the first that grabs a glass to drink) are grounded and
rendered with `render_keyframes` (small frames: what can fail is walking to the
standing spots grounding chose); the count of renders that succeed is printed.

    nice python benchmarks/homes.py [--seeds 0-99] [--programs 518] [--workers 2]
                                    [--render-seeds 0-19]
"""

from __future__ import annotations

import argparse
import gzip
import json
import multiprocessing as mp
import statistics
import time


def _typical_programs() -> list:
    """The first real program that watches TV from the sofa and the first that grabs a
    glass to drink, ungrounded."""
    from homesim.ground import unground
    from homesim.knowledge import real_programs

    programs = [unground(rp.program) for rp in real_programs()]
    texts = [str(p) for p in programs]
    watch = next(k for k, t in enumerate(texts) if "[Watch] <television>" in t and "[Sit]" in t)
    grab = next(k for k, t in enumerate(texts) if "[Grab] <water_glass>" in t)
    return [programs[watch], programs[grab]]


def _renders(graph) -> tuple[int, list[str]]:
    """How many of the typical programs render in a home, and why the others did not."""
    from homesim import run_program
    from homesim.errors import HomesimError
    from homesim.render import render_keyframes

    ok, why = 0, []
    for program in _typical_programs():
        run = run_program(program, graph, trace=True)
        if not run.executable or run.grounding is None:
            why.append(f"{program.title}: not executable ({run.message})")
            continue
        try:
            render_keyframes(run, width=64, height=48)
            ok += 1
        except HomesimError as e:
            why.append(f"{program.title}: {e}")
    return ok, why


def _measure(name: str, limit: int, render: bool) -> dict:
    from homesim import run_program
    from homesim.ground import unground
    from homesim.knowledge import real_programs
    from homesim.world import load_home
    from homesim.world.procedural import check_home, generate_home

    row: dict = {"home": name}
    if name.startswith("gen-"):
        seed = int(name[4:])
        t0, c0 = time.perf_counter(), time.process_time()
        graph = generate_home(seed)
        row["gen_s"] = time.perf_counter() - t0
        row["cpu_s"] = time.process_time() - c0
        again = generate_home(seed)
        row["same_bytes"] = (gzip.compress(json.dumps(graph.to_dict()).encode(), mtime=0)
                             == gzip.compress(json.dumps(again.to_dict()).encode(), mtime=0))
        row["problems"] = len(check_home(graph))
    else:
        load_home.cache_clear()
        t0, c0 = time.perf_counter(), time.process_time()
        graph = load_home(name)
        row["gen_s"] = time.perf_counter() - t0
        row["cpu_s"] = time.process_time() - c0
    rooms = graph.rooms()
    row["room_areas"] = [(r.class_name, _floor_area(graph, r.id)) for r in rooms]
    from homesim.world.procedural.checks import through_bathroom

    row["through_bathroom"] = len(through_bathroom(graph)) if name.startswith("gen-") else 0
    row["objects"] = len(graph)
    row["area"] = sum(r.bounding_box.size[0] * r.bounding_box.size[2] for r in rooms)
    programs = [unground(rp.program) for rp in real_programs()[:limit]]
    ok = added = 0
    for p in programs:
        run = run_program(p, graph, repair=False)  # as written (benchmarks/repair.py: repaired)
        ok += run.executable
        added += len(run.prepared.added) if run.prepared else 0
    row["rate"] = ok / max(1, len(programs))  # --programs 0: time and check homes only
    row["added"] = added / max(1, len(programs))
    if render:
        row["renders"], row["render_problems"] = _renders(graph)
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="0-99")
    parser.add_argument("--programs", type=int, default=518)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--render-seeds", default="0-19",
                        help="seeds whose homes render the two typical programs ('' none)")
    args = parser.parse_args()
    seeds = _seeds(args.seeds)
    rendered = set(_seeds(args.render_seeds)) if args.render_seeds else set()
    builtin = [f"scene{i}" for i in range(1, 6)]
    jobs = [(n, args.programs, bool(rendered)) for n in builtin]
    jobs += [(f"gen-{s}", args.programs, s in rendered) for s in seeds]
    with mp.Pool(args.workers) as pool:
        rows = pool.starmap(_measure, jobs, chunksize=1)
    base, gen = rows[:5], rows[5:]
    print(f"{'home':<10} {'load/gen s':>10} {'objects':>8} {'area m2':>8} {'exec %':>7} "
          f"{'added/prog':>10}")
    for r in base + gen[:12]:
        print(f"{r['home']:<10} {r['gen_s']:>10.3f} {r['objects']:>8} {r['area']:>8.0f} "
              f"{100 * r['rate']:>7.1f} {r['added']:>10.2f}")

    def summary(rs: list[dict], what: str) -> str:
        rates = [100 * r["rate"] for r in rs]
        return (f"{what}: {len(rs)} homes; executable min {min(rates):.1f}% median "
                f"{statistics.median(rates):.1f}%; objects mean "
                f"{statistics.mean(r['objects'] for r in rs):.0f}; floor area mean "
                f"{statistics.mean(r['area'] for r in rs):.0f} m2; objects added per program "
                f"mean {statistics.mean(r['added'] for r in rs):.2f}")

    print(summary(base, "built-in"))
    print(summary(gen, "generated"))
    times = [r["gen_s"] for r in gen]
    ref = statistics.median(r["gen_s"] for r in base)
    print(f"generation s/home: median {statistics.median(times):.3f} max {max(times):.3f} "
          f"(goal <= 1 s); loading a built-in home (reference) median {ref:.3f} s, ratio "
          f"{statistics.median(times) / ref:.1f}x")
    cpu = [r["cpu_s"] for r in gen]
    ref_cpu = statistics.median(r["cpu_s"] for r in base)
    print(f"generation CPU s/home (process time: what a shared machine's load does not "
          f"inflate): median {statistics.median(cpu):.3f} max {max(cpu):.3f}; loading a "
          f"built-in home {ref_cpu:.3f} s, ratio {statistics.median(cpu) / ref_cpu:.1f}x")
    print(f"checks: {sum(r['problems'] == 0 for r in gen)}/{len(gen)} pass; same seed, same "
          f"bytes: {sum(r['same_bytes'] for r in gen)}/{len(gen)}; homes under 95%: "
          f"{sum(r['rate'] < 0.95 for r in gen)}")
    _print_rooms(base, gen)
    if rendered:
        _print_renders(base, [r for r in gen if "renders" in r])


def _floor_area(graph, room: int, cell: float = 0.05) -> float:
    """A room's floor area, m2: the ground its floor tiles cover inside the room's box,
    each spot once. A generated home's threshold tile reaches through the doorway into
    the next room and overlaps the tiles on both sides; the built-in homes' tiles lie
    inside their rooms and do not overlap, so there this is the tiles' sum, as
    `tools/fit_home_stats.py` measures the built-in range."""
    import numpy as np

    from homesim.world.floor import footprint, room_floor

    box = graph.node(room).bounding_box
    inside = (-1e9, -1e9, 1e9, 1e9) if box is None else footprint(box)
    boxes = []
    for tile in room_floor(graph, room)[0]:  # (the room's own box when it has no tiles)
        t = footprint(tile)
        b = (max(t[0], inside[0]), max(t[1], inside[1]), min(t[2], inside[2]),
             min(t[3], inside[3]))
        if b[0] < b[2] and b[1] < b[3]:
            boxes.append(b)
    if not boxes:
        return 0.0
    x0, z0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
    x1, z1 = max(b[2] for b in boxes), max(b[3] for b in boxes)
    covered = np.zeros((round((z1 - z0) / cell) + 1, round((x1 - x0) / cell) + 1), bool)
    for bx0, bz0, bx1, bz1 in boxes:
        covered[round((bz0 - z0) / cell):round((bz1 - z0) / cell),
                round((bx0 - x0) / cell):round((bx1 - x0) / cell)] = True
    return float(covered.sum()) * cell * cell


def _print_rooms(base: list[dict], gen: list[dict]) -> None:
    """Floor areas per room kind: the built-in range (scaled for derived kinds, as the
    generator draws them) against the generated homes' range, and the rooms outside it."""
    from homesim.world.procedural.stats import KINDS, kind_area, room_class

    print(f"{'room kind':<14} {'built-in m2':>14} {'generated m2':>14} {'rooms':>6} "
          f"{'outside':>8}")
    for kind in KINDS:
        cls = room_class(kind)
        lo, hi = kind_area(kind)
        built = [a for r in base for c, a in r["room_areas"] if c == cls]
        made = [a for r in gen for c, a in r["room_areas"] if c == cls]
        if not made:
            continue
        out = sum(not lo - 0.5 <= a <= hi + 0.5 for a in made)
        rng = f"{min(built):.1f}-{max(built):.1f}" if built else f"({lo:.1f}-{hi:.1f})"
        print(f"{kind:<14} {rng:>14} {min(made):>6.1f}-{max(made):<7.1f} {len(made):>6} "
              f"{out:>8}")
    print(f"rooms reachable only through a bathroom: "
          f"{sum(r['through_bathroom'] for r in gen)} in {len(gen)} generated homes")


def _print_renders(base: list[dict], gen: list[dict]) -> None:
    for what, rows in (("built-in", base), ("generated", gen)):
        done = sum(r["renders"] for r in rows)
        print(f"render (watch TV, grab a glass): {done}/{2 * len(rows)} succeed in {what} "
              f"homes ({len(rows)} homes)")
        for r in rows:
            for why in r["render_problems"]:
                print(f"  {r['home']}: {why}")


def _seeds(text: str) -> range:
    lo, _, hi = text.partition("-")
    return range(int(lo), int(hi or lo) + 1)


if __name__ == "__main__":
    main()
