"""Grounding a program with many objects: time against comparing every pair.

A program of N steps ``[Walk] <cup> (i)``, i = 1..N, needs N different cups, which
preparation adds. To order the candidates of each new cup, the search looks at what it
has already chosen: objects close to a candidate or on the same surface, and the nearest
chosen object (full homes). Before issue 12 it compared every candidate with every chosen
object, so the cost grew with N cubed. Now it uses an index of chosen objects by surface
and a sweep over chosen objects sorted by x. The reference is the old candidate order,
kept below and run in the same process. The bindings must be the same.

    python benchmarks/grounding_many.py [--sizes 100,200,400] [--homes scene1_trimmed,scene1]
"""

from __future__ import annotations

import argparse
import time

from homesim.ground import search
from homesim.ground.search import prepare_and_ground
from homesim.program import parse_program
from homesim.world import load_home
from homesim.world.vocab import CLOSE, INSIDE, ON


def reference_order(self: search._Search, key: search.Key) -> list[int]:
    """The candidate order before issue 12: every candidate against every anchor."""
    st = self.st
    char_room = st.room_of(st.char)
    bound = [n for n in self.assign.values() if n not in st.rooms]
    anchors = bound + [n for n in self.fixed if n not in self.owner and n not in st.rooms]
    used_rooms = {st.room_of(n) for n in self.assign.values()}
    boxes = [b for b in (self.graph.nodes[n].bounding_box for n in bound
                         if n in self.graph.nodes) if b is not None]
    scored = []
    needs = self.needs.get(key, ())
    for node in self.domains[key]:
        props = st.properties(node)
        lacking = sum(1 for need in needs if props.isdisjoint(need))
        related = 0
        if anchors:
            near = st.targets(node, CLOSE)
            under = st.targets(node, ON) | st.targets(node, INSIDE)
            for b in anchors:
                if b in near or b in under or not under.isdisjoint(st.targets(b, ON)):
                    related += 1
        room = st.room_of(node)
        room_rank = 0 if room == char_room else (1 if room in used_rooms else 2)
        dist = 0.0
        box = self.graph.nodes[node].bounding_box if node in self.graph.nodes else None
        if boxes and box is not None:
            dist = min((box.center[0] - b.center[0]) ** 2 + (box.center[2] - b.center[2]) ** 2
                       for b in boxes)
        tie = self.tie.get(node)
        if tie is None:
            tie = self.tie[node] = self.rng.random()
        scored.append((lacking, -related, room_rank, dist, tie, node))
    scored.sort()
    return [s[-1] for s in scored]


def _ground(n: int, home_name: str) -> tuple[float, dict]:
    program = parse_program("".join(f"[Walk] <cup> ({i})\n" for i in range(1, n + 1)))
    home = load_home(home_name)
    start = time.perf_counter()
    _, grounding = prepare_and_ground(program, home)
    return time.perf_counter() - start, grounding.bindings


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,200,400")
    parser.add_argument("--homes", default="scene1_trimmed,scene1")
    args = parser.parse_args()
    ours = search._Search.order
    print(f"{'home':16} {'objects':>7} {'ours s':>8} {'ref s':>8} {'ref/ours':>9} same bindings")
    for home in args.homes.split(","):
        for n in map(int, args.sizes.split(",")):
            t_ours, b_ours = _ground(n, home)
            search._Search.order = reference_order
            try:
                t_ref, b_ref = _ground(n, home)
            finally:
                search._Search.order = ours
            print(f"{home:16} {n:>7} {t_ours:>8.2f} {t_ref:>8.2f} {t_ref / t_ours:>8.1f}x "
                  f"{b_ours == b_ref}")


if __name__ == "__main__":
    main()
